// How every glTF unit reports: an error is one SceneError line
// "<path>: <problem>"; a warning is one line "<path>: warning: <message>"
// handed to the caller's sink the first time its kind comes up.
#pragma once

#include "scene/scene_error.hpp"
#include "scene/warnings.hpp"

#include <cstddef>
#include <set>
#include <string>
#include <utility>

namespace blurcull::frontend::gltf {

class Diagnostics {
public:
    Diagnostics(std::string path, WarningSink sink) : path_(std::move(path)), sink_(std::move(sink)) {}

    // The file's path as the caller gave it.
    const std::string& path() const { return path_; }

    // Throws SceneError("<path>: <problem>"), control characters from the
    // file (a name with a newline) shown as '?' so it stays one line.
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(path_ + ": " + one_line(problem)); }

    // Sends "<path>: warning: <message>" to the sink, once per `kind`, as
    // one line like fail's.
    void warn_once(const std::string& kind, const std::string& message) {
        if (warned_.insert(kind).second && sink_) sink_(path_ + ": warning: " + one_line(message));
    }

    // A string from the file (a name, a version, a URI) for a message: at
    // most `limit` characters, longer ones cut with "...".
    static std::string quoted(const std::string& text, std::size_t limit = 120) {
        return text.size() <= limit ? text : text.substr(0, limit) + "...";
    }

private:
    static std::string one_line(std::string text) {
        for (char& c : text) {
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
        }
        return text;
    }

    std::string path_;
    WarningSink sink_;
    std::set<std::string> warned_;
};

}  // namespace blurcull::frontend::gltf
