// Umbrella header of the blurcull kernel.
#pragma once

#include "version.hpp"
#include "kernel.hpp"
#include "patterns.hpp"
#include "pattern_names.hpp"
#include "interleaved_tiles.hpp"
