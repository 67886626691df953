// Uses the installed (or add_subdirectory'd) kernel the way a user would, and
// checks a few properties that a broken package or include path would break.
#include <blurcull/blurcull.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

int failures = 0;

void expect(bool condition, const char* what) {
    if (!condition) {
        std::fprintf(stderr, "blurcull_consumer: FAILED: %s\n", what);
        ++failures;
    }
}

}  // namespace

int main() {
    const std::string version = blurcull::version_string();
    const std::string from_macros = std::to_string(BLURCULL_VERSION_MAJOR) + "." +
                                    std::to_string(BLURCULL_VERSION_MINOR) + "." +
                                    std::to_string(BLURCULL_VERSION_PATCH);
    expect(version == from_macros, "version_string() matches the BLURCULL_VERSION_* macros");
    const char* expected = BLURCULL_CONSUMER_EXPECTED_VERSION;
    if (std::strlen(expected) != 0) {
        expect(version == expected, "version_string() matches the package config's version");
    }

    // One pixel's samples: every field in range, and the shutter strata each
    // hit exactly once (the pattern is stratified in time).
    const unsigned spp = 16;
    std::vector<int> time_strata_hit(spp, 0);
    for (unsigned index = 0; index < spp; ++index) {
        const blurcull::kernelf::PixelSample sample =
            blurcull::kernelf::pixel_sample(7u, 3u, index, spp, 12345u);
        expect(sample.offset.x >= 0.0f && sample.offset.x < 1.0f, "offset.x in [0, 1)");
        expect(sample.offset.y >= 0.0f && sample.offset.y < 1.0f, "offset.y in [0, 1)");
        expect(std::abs(sample.lens.x) <= 1.0f && std::abs(sample.lens.y) <= 1.0f, "lens in [-1, 1]^2");
        expect(sample.lens.x * sample.lens.x + sample.lens.y * sample.lens.y <= 1.0f + 1e-5f,
               "lens in the unit disk");
        expect(sample.time >= 0.0f && sample.time < 1.0f, "time in [0, 1)");
        if (sample.time >= 0.0f && sample.time < 1.0f) {
            ++time_strata_hit[static_cast<unsigned>(sample.time * static_cast<float>(spp))];
        }
    }
    for (int hits : time_strata_hit) {
        expect(hits == 1, "each of the spp shutter strata holds exactly one sample");
    }

    // The same pattern in double precision: the host's two instantiations agree.
    const blurcull::kerneld::PixelSample in_double = blurcull::kerneld::pixel_sample(7u, 3u, 5u, spp, 12345u);
    const blurcull::kernelf::PixelSample in_float = blurcull::kernelf::pixel_sample(7u, 3u, 5u, spp, 12345u);
    expect(std::abs(in_double.time - static_cast<double>(in_float.time)) < 1e-6, "float and double agree on time");

    if (failures != 0) {
        return 1;
    }
    std::printf("blurcull_consumer: blurcull %s OK\n", version.c_str());
    return 0;
}
