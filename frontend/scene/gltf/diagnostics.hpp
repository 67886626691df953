// How every glTF unit reports: an error is one SceneError line
// "<path>: <problem>"; a warning is one line "<path>: warning: <message>"
// handed to the caller's sink the first time its kind comes up.
#pragma once

#include "scene/scene_error.hpp"
#include "scene/warnings.hpp"

#include <set>
#include <string>
#include <utility>

namespace blurcull::frontend::gltf {

class Diagnostics {
public:
    Diagnostics(std::string path, WarningSink sink) : path_(std::move(path)), sink_(std::move(sink)) {}

    // The file's path as the caller gave it.
    const std::string& path() const { return path_; }

    // Throws SceneError("<path>: <problem>").
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(path_ + ": " + problem); }

    // Sends "<path>: warning: <message>" to the sink, once per `kind`.
    void warn_once(const std::string& kind, const std::string& message) {
        if (warned_.insert(kind).second && sink_) sink_(path_ + ": warning: " + message);
    }

private:
    std::string path_;
    WarningSink sink_;
    std::set<std::string> warned_;
};

}  // namespace blurcull::frontend::gltf
