// What the scene benchmarks share: medians, comma lists, and writing a
// generated block into a Markdown file between two markers, so they can
// refresh their tables in docs/benchmarks.md in place.
#pragma once

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace blurcull::bench {

// The median of the values (the upper one of an even count; 0 for none).
inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values.empty() ? 0.0 : values[values.size() / 2];
}

// "a,b,,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

// Replaces the text between "<!-- NAME:begin -->" and "<!-- NAME:end -->" in
// `path` with `body`, or appends the marked block when the markers are
// missing. Throws std::runtime_error when the file cannot be written.
inline void write_doc_section(const std::string& path, const std::string& name, const std::string& body) {
    const std::string begin = "<!-- " + name + ":begin -->", end = "<!-- " + name + ":end -->";
    std::string text;
    {
        std::ifstream in(path);
        if (in) {
            std::stringstream buffer;
            buffer << in.rdbuf();
            text = buffer.str();
        }
    }
    const std::string block = begin + "\n" + body + end + "\n";
    const std::size_t b = text.find(begin), e = text.find(end);
    if (b != std::string::npos && e != std::string::npos && e > b) {
        text.replace(b, e + end.size() + 1 - b, block);
    } else {
        if (text.empty()) text = "# Benchmarks\n\n";
        text += "\n" + block;
    }
    std::ofstream out(path);
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
    out << text;
}

}  // namespace blurcull::bench
