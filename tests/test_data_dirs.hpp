// Where the tests find their files. Every file a test needs is in the
// repository (tests/data/: the Khronos sample models in tests/data/khronos,
// with their licences), so the suite passes on a clone with nothing beside
// it. The team's larger scene folder, ../shared beside the source folder, is
// optional: only sweeps that also take whatever it holds read it, and they
// skip that part with a MESSAGE when it is absent. BLURCULL_SHARED_DIR in the
// environment names another folder in its place (.ci/run sets a missing one
// to check that the suite needs only the repository; docs/building.md).
#pragma once

#include <cstdlib>
#include <string>

namespace blurcull::testing {

// tests/data of this source tree.
inline std::string test_data_dir() { return std::string(BLURCULL_SOURCE_DIR) + "/tests/data"; }

// The Khronos glTF sample models the tests read (tests/data/khronos/README.md).
inline std::string khronos_test_dir() { return test_data_dir() + "/khronos"; }

// $BLURCULL_SHARED_DIR, else ../shared beside the source folder; it may not exist.
inline std::string shared_dir() {
    const char* folder = std::getenv("BLURCULL_SHARED_DIR");
    if (folder != nullptr && *folder != '\0') return folder;
    return std::string(BLURCULL_SOURCE_DIR) + "/../shared";
}

}  // namespace blurcull::testing
