// Umbrella header of the blurcull kernel.
#pragma once

#include <blurcull/version.hpp>  // generated from the project version (cmake/version.hpp.in)
#include "kernel.hpp"
#include "patterns.hpp"
#include "pattern_names.hpp"
#include "interleaved_tiles.hpp"
#include "secondary_clusters.hpp"
#include "layer_trace.hpp"
