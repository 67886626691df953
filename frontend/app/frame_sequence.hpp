// The parts of `blurcull render --frames` that are plain text: the frame
// range A:B[:STEP] and the output name's printf-style frame field
// (NAME_%04d.png), with their one-line errors naming the flag.
#pragma once

#include <string>
#include <vector>

namespace blurcull::frontend {

// Frames first, first + step, ... up to and including last.
struct FrameRange {
    long first = 0;
    long last = 0;
    long step = 1;

    // The frame numbers of the range, in order.
    std::vector<long> frames() const;
};

// "A:B" or "A:B:STEP", whole numbers with 0 <= A <= B and STEP >= 1 (B is
// included). Throws std::invalid_argument naming --frames: malformed,
// empty, reversed (A > B) or a step below 1.
FrameRange parse_frame_range(const std::string& text);

// An output name with at most one frame field: %d or %0Nd / %Nd (N in
// 1..9: the frame number padded to N digits, with zeros for %0Nd); %% is a
// literal %.
struct OutputPattern {
    std::string before;  // the text before the field, %% already undone
    std::string after;   // the text after it
    bool has_field = false;
    int width = 0;       // digits to pad to; 0: none
    bool zero_pad = false;

    // The name of frame `frame` (the pattern itself when it has no field).
    std::string path_for(long frame) const;
};

// Parses -o's value. For a sequence (`sequence`), the name must have
// exactly one frame field and any other % is refused; for one frame, a
// name without a valid frame field is taken as it is, and one with a field
// is refused (it needs --frames). Throws std::invalid_argument naming -o.
OutputPattern parse_output_pattern(const std::string& text, bool sequence);

}  // namespace blurcull::frontend
