#include "app/frame_sequence.hpp"

#include <cctype>
#include <cstdio>
#include <stdexcept>

namespace blurcull::frontend {

namespace {

// A whole number >= 0 spelled with digits only (no sign, no spaces), or -1.
long parse_count(const std::string& text) {
    if (text.empty() || text.size() > 12) return -1;
    for (char c : text) {
        if (!std::isdigit(static_cast<unsigned char>(c))) return -1;
    }
    return std::stol(text);
}

// A frame field starting at text[at] == '%': its length (0 when it is not
// one), its width and whether it pads with zeros.
std::size_t frame_field_at(const std::string& text, std::size_t at, int& width, bool& zero_pad) {
    std::size_t i = at + 1;
    zero_pad = i < text.size() && text[i] == '0';
    if (zero_pad) ++i;
    width = 0;
    if (i < text.size() && text[i] >= '1' && text[i] <= '9') width = text[i++] - '0';
    if (zero_pad && width == 0) return 0;  // "%0d"
    if (i < text.size() && text[i] == 'd') return i + 1 - at;
    return 0;
}

}  // namespace

std::vector<long> FrameRange::frames() const {
    std::vector<long> numbers;
    for (long frame = first; frame <= last; frame += step) numbers.push_back(frame);
    return numbers;
}

FrameRange parse_frame_range(const std::string& text) {
    const auto bad = [&](const std::string& why) {
        return std::invalid_argument("--frames '" + text + "': " + why);
    };
    const std::string expected = "expected A:B or A:B:STEP with whole numbers 0 <= A <= B and STEP >= 1";
    if (text.empty()) throw bad("the range is empty; " + expected);
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) throw bad(expected);
    const std::size_t second = text.find(':', colon + 1);
    FrameRange range;
    range.first = parse_count(text.substr(0, colon));
    range.last = parse_count(text.substr(colon + 1, second == std::string::npos ? std::string::npos : second - colon - 1));
    range.step = second == std::string::npos ? 1 : parse_count(text.substr(second + 1));
    if (range.first < 0 || range.last < 0 || range.step < 0) throw bad(expected);
    if (range.first > range.last) {
        throw bad("the range is reversed (" + std::to_string(range.first) + " > " + std::to_string(range.last) +
                  "); frames run from A up to B");
    }
    if (range.step < 1) throw bad("the step must be at least 1");
    return range;
}

std::string OutputPattern::path_for(long frame) const {
    if (!has_field) return before;
    char digits[32];
    if (zero_pad) {
        std::snprintf(digits, sizeof digits, "%0*ld", width, frame);
    } else {
        std::snprintf(digits, sizeof digits, "%*ld", width, frame);
    }
    return before + digits + after;
}

OutputPattern parse_output_pattern(const std::string& text, bool sequence) {
    OutputPattern pattern;
    std::string literal;  // the text so far, %% undone
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            literal += text[i];
            continue;
        }
        if (i + 1 < text.size() && text[i + 1] == '%') {
            literal += '%';
            ++i;
            continue;
        }
        int width = 0;
        bool zero_pad = false;
        const std::size_t length = frame_field_at(text, i, width, zero_pad);
        if (length == 0) {
            // One frame: a % that starts no field is part of the name.
            if (!sequence) return OutputPattern{text, "", false, 0, false};
            throw std::invalid_argument("-o " + text + ": '%' at character " + std::to_string(i + 1) +
                                        " starts no frame field (use %d or %04d for the frame number, %% for a %)");
        }
        if (pattern.has_field) {
            throw std::invalid_argument("-o " + text + ": more than one frame field (%d, %04d, ...)");
        }
        pattern.has_field = true;
        pattern.width = width;
        pattern.zero_pad = zero_pad;
        pattern.before = literal;
        literal.clear();
        i += length - 1;
    }
    if (!pattern.has_field) {
        if (sequence) {
            throw std::invalid_argument("-o " + text +
                                        ": a sequence (--frames) needs a frame field in the output name, "
                                        "e.g. NAME_%04d.png");
        }
        return OutputPattern{text, "", false, 0, false};
    }
    if (!sequence) {
        throw std::invalid_argument("-o " + text + ": the frame field needs --frames (one frame takes a plain name)");
    }
    pattern.after = literal;
    return pattern;
}

}  // namespace blurcull::frontend
