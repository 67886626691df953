// The names of the sample patterns (BC_PATTERN_*), for command lines and
// reports: "hashed", "random", "jittered", "sobol".
#pragma once

#include "patterns.hpp"

#include <stdexcept>
#include <string>

namespace blurcull {

// BC_PATTERN_* -> its name; "unknown" for any other id.
inline const char* sample_pattern_name(int pattern) {
    switch (pattern) {
        case BC_PATTERN_HASHED: return "hashed";
        case BC_PATTERN_RANDOM: return "random";
        case BC_PATTERN_JITTERED: return "jittered";
        case BC_PATTERN_SOBOL: return "sobol";
        default: return "unknown";
    }
}

// "hashed", "random", "jittered" or "sobol" -> BC_PATTERN_*. Throws
// std::invalid_argument naming the valid patterns otherwise.
inline int parse_sample_pattern(const std::string& name) {
    for (int pattern : {BC_PATTERN_HASHED, BC_PATTERN_RANDOM, BC_PATTERN_JITTERED, BC_PATTERN_SOBOL}) {
        if (name == sample_pattern_name(pattern)) return pattern;
    }
    throw std::invalid_argument("unknown sample pattern '" + name + "' (valid: hashed, random, jittered, sobol)");
}

}  // namespace blurcull
