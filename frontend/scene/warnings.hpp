// Non-fatal problems met while making a scene (a skipped primitive, an
// ignored animation path, ...). The scene layer prints nothing: it hands each
// one to the caller's sink as one finished line ("<path>: warning: ..."),
// and the command decides where it goes.
#pragma once

#include <functional>
#include <string>

namespace blurcull::frontend {

// Called once per warning, in the order they arise, before any SceneError
// the same load throws. An empty sink drops the warnings.
using WarningSink = std::function<void(const std::string& line)>;

}  // namespace blurcull::frontend
