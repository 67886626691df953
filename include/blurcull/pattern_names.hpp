// The names of the sample patterns (BC_PATTERN_*), for command lines and
// reports: "hashed", "random", "jittered", "sobol", "padded-sobol".
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
        case BC_PATTERN_PADDED_SOBOL: return "padded-sobol";
        default: return "unknown";
    }
}

// "hashed, random, jittered, sobol, padded-sobol": every name, in id order.
inline std::string sample_pattern_list() {
    std::string list;
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        if (pattern > 0) list += ", ";
        list += sample_pattern_name(pattern);
    }
    return list;
}

// "hashed", "random", "jittered", "sobol" or "padded-sobol" -> BC_PATTERN_*. Throws
// std::invalid_argument naming the valid patterns otherwise.
inline int parse_sample_pattern(const std::string& name) {
    for (int pattern = 0; pattern < BC_PATTERN_COUNT; ++pattern) {
        if (name == sample_pattern_name(pattern)) return pattern;
    }
    throw std::invalid_argument("unknown sample pattern '" + name + "' (valid: " + sample_pattern_list() + ")");
}

}  // namespace blurcull
