// libFuzzer target: the glTF loader on arbitrary bytes. The bytes go to a
// file (.glb when they start with "glTF", else .gltf) in a private empty
// folder, so external buffer URIs resolve to nothing, and load_gltf_scene
// runs the project's whole validation. A SceneError is the expected outcome
// for bad input; any other exception, crash, leak or sanitizer report is a bug,
// and so is an error or warning that is not one line naming the file.
#include "scene/gltf/gltf_loader.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <unistd.h>

namespace {

std::string scratch_folder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/blurcull_fuzz_gltf.XXXXXX";
    if (!mkdtemp(pattern.data())) {
        std::perror("fuzz_gltf: mkdtemp");
        std::abort();
    }
    return pattern;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string folder = scratch_folder();
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = folder + (binary ? "/input.glb" : "/input.gltf");
    FILE* file = std::fopen(path.c_str(), "wb");
    if (!file || std::fwrite(data, 1, size, file) != size || std::fclose(file) != 0) {
        std::perror("fuzz_gltf: writing the input");
        std::abort();
    }
    blurcull::frontend::GltfOptions options;
    options.animation_index = size > 0 ? int(data[size - 1] % 3) - 1 : 0;  // none, first, second
    // The loader prints nothing; each warning it returns is one line.
    const auto check_warning = [&](const std::string& line) {
        if (line.rfind(path + ": warning: ", 0) != 0 || line.find('\n') != std::string::npos) {
            std::fprintf(stderr, "fuzz_gltf: bad warning: %s\n", line.c_str());
            std::abort();
        }
    };
    try {
        const blurcull::frontend::Scene scene = blurcull::frontend::load_gltf_scene(path, options, check_warning);
        // A loaded scene must be consistent: indices in range.
        for (const auto& triangle : scene.triangles) {
            for (int k = 0; k < 3; ++k) {
                if (triangle[k] >= scene.position_open.size()) std::abort();
            }
        }
    } catch (const blurcull::frontend::SceneError& error) {
        // One line naming the file.
        const std::string message = error.what();
        if (message.rfind(path + ": ", 0) != 0 || message.find('\n') != std::string::npos) {
            std::fprintf(stderr, "fuzz_gltf: bad error message: %s\n", message.c_str());
            std::abort();
        }
    }
    return 0;
}
