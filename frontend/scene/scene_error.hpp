// The one exception type every scene loader throws: its message is a single
// line that names the file (or scene) and the problem, ready to print.
#pragma once

#include <stdexcept>
#include <string>

namespace blurcull::frontend {

struct SceneError : std::runtime_error {
    explicit SceneError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace blurcull::frontend
