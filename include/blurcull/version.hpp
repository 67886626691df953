#pragma once

#define BLURCULL_VERSION_MAJOR 0
#define BLURCULL_VERSION_MINOR 1
#define BLURCULL_VERSION_PATCH 0

namespace blurcull {
inline constexpr const char* version_string() { return "0.1.0"; }
}  // namespace blurcull
