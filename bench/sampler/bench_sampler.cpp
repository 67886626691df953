// Error of each sample pattern (--sampler) against a converged reference, on
// the built-in scenes (docs/sampling.md, "Choosing the default sampler").
//
// Per scene: the reference is the mean of two Embree renders of `--ref-spp`
// samples (hashed with seed 1001, sobol with seed 1002, so it favours no
// pattern); its own noise is estimated from their difference
// (E|a - b|^2 = var a + var b, the mean's variance a quarter of that). Then
// every sampler renders at each spp with `--seeds` seeds; the error is the
// RMSE over the linear RGB channels of all pixels, squared errors averaged
// over the seeds, printed raw and with the reference's variance removed.
// Embree draws exactly the CPU backend's samples (tests/test_sampler.cpp),
// and is the fastest backend here. With --noise SPP, also each sampler's
// two-seed noise (RMSE between seeds 1 and 2, / sqrt 2) at SPP on the
// scene with its motion removed (shutter 0.5,0.5: defocus only).
//
//   bench_sampler [--scenes hand,car,dragonfly,forest] [--size 128x96] [--ref-spp 4096]
//                 [--spp 4,16,64,256] [--samplers hashed,jittered,sobol,padded-sobol]
//                 [--seeds 2] [--noise 1024] [--error-table 1|0] [--threads 0]
#include "render/embree/embree_backend.hpp"
#include "scene/load_scene.hpp"

#include <blurcull/pattern_names.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;

namespace {

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream stream(text);
    for (std::string item; std::getline(stream, item, ',');) out.push_back(item);
    return out;
}

// Mean squared difference over the three channels of every pixel.
double mean_squared_difference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec3 d = a.pixels[i] - b.pixels[i];
        sum += double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    }
    return sum / (3.0 * double(a.pixels.size()));
}

Image render(const Scene& scene, RenderSettings settings, int sampler, int spp, std::uint32_t seed) {
    settings.sampler = sampler;
    settings.spp = spp;
    settings.seed = seed;
    return render_embree(scene, settings).image;
}

struct Options {
    std::vector<std::string> scenes{"hand", "car", "dragonfly", "forest"};
    std::vector<int> spps{4, 16, 64, 256};
    std::vector<std::string> samplers{"hashed", "jittered", "sobol", "padded-sobol"};
    int width = 128, height = 96, ref_spp = 4096, seeds = 2, noise_spp = 0, threads = 0;
    bool error_table = true;  // --error-table 0: only the noise table
};

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--scenes") o.scenes = split(value);
        else if (flag == "--samplers") o.samplers = split(value);
        else if (flag == "--spp") {
            o.spps.clear();
            for (const std::string& s : split(value)) o.spps.push_back(std::stoi(s));
        } else if (flag == "--size") {
            if (std::sscanf(value.c_str(), "%dx%d", &o.width, &o.height) != 2) throw std::invalid_argument("--size: WxH");
        } else if (flag == "--ref-spp") o.ref_spp = std::stoi(value);
        else if (flag == "--seeds") o.seeds = std::stoi(value);
        else if (flag == "--noise") o.noise_spp = std::stoi(value);
        else if (flag == "--threads") o.threads = std::stoi(value);
        else if (flag == "--error-table") o.error_table = value != "0";
        else throw std::invalid_argument("unknown flag " + flag);
    }
    for (const std::string& s : o.samplers) blurcull::parse_sample_pattern(s);  // one-line error for a bad name
    return o;
}

Scene load(const std::string& name, const Options& o, bool defocus_only) {
    SceneSettings settings;
    settings.aspect = float(o.width) / float(o.height);
    if (defocus_only) {
        settings.has_shutter = true;
        settings.shutter_open = settings.shutter_close = 0.5f;
    }
    return load_scene(name, settings);
}

void error_table(const Options& o, const RenderSettings& base) {
    std::printf("| scene | sampler |");
    for (int spp : o.spps) std::printf(" %d spp |", spp);
    std::printf("\n| --- | --- |");
    for (std::size_t i = 0; i < o.spps.size(); ++i) std::printf(" --- |");
    std::printf("\n");
    for (const std::string& name : o.scenes) {
        const Scene scene = load(name, o, false);
        const Image a = render(scene, base, BC_PATTERN_HASHED, o.ref_spp, 1001u);
        const Image b = render(scene, base, BC_PATTERN_SOBOL, o.ref_spp, 1002u);
        Image reference = a;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) reference.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
        const double reference_variance = 0.25 * mean_squared_difference(a, b);
        std::fprintf(stderr, "%s: reference RMSE noise %.6f\n", name.c_str(), std::sqrt(reference_variance));
        for (const std::string& sampler : o.samplers) {
            std::printf("| %s | %s |", name.c_str(), sampler.c_str());
            for (int spp : o.spps) {
                double mse = 0.0;
                for (int s = 0; s < o.seeds; ++s) {
                    const Image image = render(scene, base, blurcull::parse_sample_pattern(sampler), spp,
                                               static_cast<std::uint32_t>(1 + s));
                    mse += mean_squared_difference(image, reference) / o.seeds;
                }
                std::printf(" %.5f (%.5f) |", std::sqrt(mse), std::sqrt(std::max(0.0, mse - reference_variance)));
            }
            std::printf("\n");
            std::fflush(stdout);
        }
    }
}

void noise_table(const Options& o, const RenderSettings& base) {
    std::printf("\nTwo-seed noise, RMSE(seed 1, seed 2) / sqrt 2, %d spp, motion removed (shutter 0.5,0.5)\n\n",
                o.noise_spp);
    std::printf("| scene |");
    for (const std::string& sampler : o.samplers) std::printf(" %s |", sampler.c_str());
    std::printf("\n| --- |");
    for (std::size_t i = 0; i < o.samplers.size(); ++i) std::printf(" --- |");
    std::printf("\n");
    for (const std::string& name : o.scenes) {
        const Scene scene = load(name, o, true);
        std::printf("| %s |", name.c_str());
        for (const std::string& sampler : o.samplers) {
            const int id = blurcull::parse_sample_pattern(sampler);
            const double mse =
                mean_squared_difference(render(scene, base, id, o.noise_spp, 1u), render(scene, base, id, o.noise_spp, 2u));
            std::printf(" %.6f |", std::sqrt(0.5 * mse));
        }
        std::printf("\n");
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parse(argc, argv);
        RenderSettings base;
        base.width = o.width;
        base.height = o.height;
        base.threads = o.threads;
        base.progress = false;
        if (o.error_table) {
            std::printf("RMSE against the reference (%dx%d, reference %d + %d spp), mean over %d seeds; "
                        "in brackets with the reference's noise removed\n\n",
                        o.width, o.height, o.ref_spp, o.ref_spp, o.seeds);
            error_table(o, base);
        }
        if (o.noise_spp > 0) noise_table(o, base);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_sampler: %s\n", error.what());
        return 1;
    }
}
