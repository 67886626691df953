// The three backends by name, and sets of them: what the registries of cull
// methods, render methods and backend options say about which backend takes what.
#pragma once

#include <string>
#include <vector>

namespace blurcull::frontend {

enum class Backend { cpu, embree, gl };

// A set of backends as bits (1 << Backend).
using BackendSet = unsigned;

constexpr BackendSet backend_bit(Backend backend) { return 1u << static_cast<unsigned>(backend); }
constexpr BackendSet all_backends = backend_bit(Backend::cpu) | backend_bit(Backend::embree) | backend_bit(Backend::gl);

// Whether `backend` is in `set`.
constexpr bool takes(BackendSet set, Backend backend) { return (set & backend_bit(backend)) != 0; }

// "cpu", "embree", "gl".
const char* to_string(Backend backend);

// The names of every backend, in the order of the enum.
std::vector<std::string> backend_names();

// The backend named `name`; throws std::invalid_argument naming the valid ones otherwise.
Backend parse_backend(const std::string& name);

// Whether this build has `backend`: the cpu backend always; embree and gl
// when their libraries or headers were found at configure time
// (frontend/CMakeLists.txt sets BLURCULL_HAVE_EMBREE and BLURCULL_HAVE_GL).
bool backend_built(Backend backend);

// Why `backend` is not in this build ("" when it is): what was missing at
// configure time and the Debian package that brings it.
std::string backend_missing_reason(Backend backend);

// "the cpu backend", "the cpu and gl backends", "the cpu, embree and gl backends".
std::string describe_backends(BackendSet set);

// "only the cpu backend takes it", "only the cpu and gl backends take it":
// the reason a setting is refused on a backend outside `set`.
std::string only_backends_take_it(BackendSet set);

}  // namespace blurcull::frontend
