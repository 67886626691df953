// Run time against error: renders each built-in scene with each blur renderer
// (docs/sampling.md) over a range of sample counts, and measures wall time and
// the error against a converged Embree reference. Writes a CSV that
// bench/pareto/plot.py turns into one error-against-time plot per scene, and a
// table of the results and the Pareto front into docs/benchmarks.md.
//
//   bench_pareto [--size 256x192] [--repeat 3] [--threads 1]
//                [--scenes hand,car,dragonfly,forest]
//                [--methods stochastic-clip2,stochastic-bbox,interleave,interval,accum]
//                [--spp 1,4,16,64] [--reference-spp 1024] [--blur-sigma 2]
//                [--cache DIR] [--csv docs/pareto.csv] [--markdown docs/benchmarks.md]
//
// Errors are deterministic (every renderer is); times are medians over
// --repeat runs with the methods interleaved within each repeat, so a drifting
// machine load hits all of them alike.
#include "bench_common.hpp"
#include "render/cpu/cpu_backend.hpp"
#include "render/embree/embree_backend.hpp"
#include "render/common/image.hpp"
#include "render/cpu/methods.hpp"
#include "scene/builtin_scenes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace blurcull::frontend;

namespace {

// The reference is rendered with seeds far from the test renders' seed (1),
// so its noise is independent of theirs.
constexpr std::uint32_t reference_seed_a = 7919;
constexpr std::uint32_t reference_seed_b = 104729;
constexpr std::uint32_t test_seed = 1;

// The stochastic rasterizer with two culls (its labels are those of the
// published CSVs), then every other render method of the registry.
const std::vector<std::string>& known_methods() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list = {"stochastic-clip2", "stochastic-bbox"};
        for (const RenderMethodInfo& info : render_methods()) {
            // dof-secondary is the stochastic rasterizer plus bounces off mirrors,
            // which these diffuse scenes do not have.
            if (info.method != RenderMethod::stochastic && info.method != RenderMethod::dof_secondary)
                list.emplace_back(info.name);
        }
        return list;
    }();
    return names;
}

struct Options {
    int width = 256, height = 192, repeat = 3, threads = 1, reference_spp = 1024;
    double blur_sigma = 2.0;
    std::vector<std::string> scenes = builtin_scene_names();
    std::vector<std::string> methods = known_methods();
    std::vector<int> spps = {1, 4, 16, 64};
    std::string cache_dir = (std::filesystem::temp_directory_path() / "blurcull-pareto-cache").string();
    std::string csv_path, markdown_path;
};

// One renderer at one sample count.
struct Config {
    std::string method;  // stochastic-clip2, stochastic-bbox, interleave, interval, accum
    int spp = 1;
};

struct Row {
    std::string scene, method, setting;
    int spp = 0;
    double ms = 0, rmse = 0, structured = 0;
    std::uint64_t tested = 0, hit = 0;
};

struct Reference {
    Image image;
    // The reference's own error, estimated from its two independent halves:
    // the mean of two halves has half the variance of one, and their
    // difference twice, so error(mean) = rms(difference) / 2.
    double rmse_floor = 0, structured_floor = 0;
};

using Clock = std::chrono::steady_clock;

using blurcull::bench::median;
using blurcull::bench::split;

int parse_int(const std::string& option, const std::string& text, int lo, int hi) {
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || value < lo || value > hi)
        throw std::invalid_argument(option + ": expected an integer in [" + std::to_string(lo) + ", " +
                                    std::to_string(hi) + "], got '" + text + "'");
    return static_cast<int>(value);
}

int square_root(int n) {
    int root = 0;
    while ((root + 1) * (root + 1) <= n) ++root;
    return root;
}

// No commas: the label is a CSV field.
std::string setting_label(const Config& config) {
    const std::string n = std::to_string(config.spp);
    if (config.method == "stochastic-clip2") return n + " spp (clip2 cull)";
    if (config.method == "stochastic-bbox") return n + " spp (bbox cull)";
    if (config.method == to_string(RenderMethod::interleave)) {
        const std::string w = std::to_string(square_root(config.spp));
        return "N = " + n + " tuples (tile " + w + "x" + w + ")";
    }
    if (config.method == to_string(RenderMethod::interval)) return "N = " + n + " shutter strata";
    return "K = " + n + " passes";
}

RenderResult render(const Scene& scene, RenderSettings settings, const Config& config) {
    settings.spp = config.spp;
    if (config.method == "stochastic-clip2" || config.method == "stochastic-bbox") {
        settings.method = RenderMethod::stochastic;
        settings.cull = config.method == "stochastic-clip2" ? CullMethod::two_stage : CullMethod::bbox;
        return render_cpu(scene, settings);
    }
    if (config.method == to_string(RenderMethod::interleave)) {
        // N = spp tuples: a tile is one pixel's s x s lattice cells, so every
        // pixel sees every tuple once (the "N = spp" point of the comparison).
        InterleaveOptions options;
        options.tile_width = square_root(config.spp);
        return render_interleave(scene, settings, options);
    }
    settings.method = parse_render_method(config.method);
    return render_with_method(scene, settings);
}

// Separable Gaussian blur with clamped borders; weights normalised to 1.
Image gaussian_blur(const Image& image, double sigma) {
    const int radius = static_cast<int>(std::ceil(3.0 * sigma));
    std::vector<float> weights(static_cast<std::size_t>(2 * radius + 1));
    double sum = 0;
    for (int i = -radius; i <= radius; ++i) {
        const double w = std::exp(-0.5 * i * i / (sigma * sigma));
        weights[static_cast<std::size_t>(i + radius)] = static_cast<float>(w);
        sum += w;
    }
    for (float& w : weights) w = static_cast<float>(w / sum);
    Image across(image.width, image.height), out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            glm::vec3 acc(0.0f);
            for (int i = -radius; i <= radius; ++i)
                acc += weights[static_cast<std::size_t>(i + radius)] *
                       image.at(std::clamp(x + i, 0, image.width - 1), y);
            across.at(x, y) = acc;
        }
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            glm::vec3 acc(0.0f);
            for (int i = -radius; i <= radius; ++i)
                acc += weights[static_cast<std::size_t>(i + radius)] *
                       across.at(x, std::clamp(y + i, 0, image.height - 1));
            out.at(x, y) = acc;
        }
    return out;
}

// The structured error: RMS of the Gaussian-blurred difference. Blurring
// averages independent per-pixel noise away (by 1 / (2 sqrt(pi) sigma), 7x
// at sigma = 2) but keeps errors coherent over several pixels — ghost copies,
// strobing, banding — nearly whole (docs/benchmarks.md).
double structured_error(const Image& image, const Image& reference, double sigma) {
    if (image.width != reference.width || image.height != reference.height)
        throw std::invalid_argument("structured_error: image sizes differ");
    Image difference(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) difference.pixels[i] = image.pixels[i] - reference.pixels[i];
    return rmse(gaussian_blur(difference, sigma), Image(image.width, image.height));
}

// Float images in the PFM format (little-endian, rows bottom to top): the
// reference must keep its precision, which an 8-bit PNG would not.
void write_pfm(const std::string& path, const Image& image) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    for (int y = image.height - 1; y >= 0; --y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3& p = image.at(x, y);
            const float rgb[3] = {p.x, p.y, p.z};
            out.write(reinterpret_cast<const char*>(rgb), sizeof rgb);
        }
    if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

// Returns false (and leaves `image` alone) when the file is missing or not a
// PFM of the expected size: the cache is then rebuilt.
bool read_pfm(const std::string& path, int width, int height, Image& image) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    in.get();  // the single whitespace after the scale
    if (!in || magic != "PF" || w != width || h != height || scale >= 0) return false;
    Image loaded(w, h);
    for (int y = h - 1; y >= 0; --y)
        for (int x = 0; x < w; ++x) {
            float rgb[3];
            in.read(reinterpret_cast<char*>(rgb), sizeof rgb);
            loaded.at(x, y) = glm::vec3(rgb[0], rgb[1], rgb[2]);
        }
    if (!in) return false;
    image = std::move(loaded);
    return true;
}

// One half of the reference, cached by scene, size, sample count and seed.
Image reference_half(const Scene& scene, const std::string& name, const Options& options, std::uint32_t seed) {
    const int spp = options.reference_spp / 2;
    const std::string file = options.cache_dir + "/" + name + "-" + std::to_string(options.width) + "x" +
                             std::to_string(options.height) + "-embree-" + std::to_string(spp) + "spp-seed" +
                             std::to_string(seed) + ".pfm";
    Image image;
    if (read_pfm(file, options.width, options.height, image)) return image;
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.spp = spp;
    settings.seed = seed;
    settings.threads = 0;  // rendered once and cached: take every core
    settings.progress = false;
    const Clock::time_point start = Clock::now();
    image = render_embree(scene, settings).image;
    std::fprintf(stderr, "%s: reference half (Embree, %d spp, seed %u) in %.1f s -> %s\n", name.c_str(), spp,
                 static_cast<unsigned>(seed), std::chrono::duration<double>(Clock::now() - start).count(),
                 file.c_str());
    std::filesystem::create_directories(options.cache_dir);
    write_pfm(file, image);
    return image;
}

Reference make_reference(const Scene& scene, const std::string& name, const Options& options) {
    const Image a = reference_half(scene, name, options, reference_seed_a);
    const Image b = reference_half(scene, name, options, reference_seed_b);
    Reference reference;
    reference.image = Image(a.width, a.height);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) reference.image.pixels[i] = 0.5f * (a.pixels[i] + b.pixels[i]);
    reference.rmse_floor = rmse(a, b) / 2;
    reference.structured_floor = structured_error(a, b, options.blur_sigma) / 2;
    return reference;
}

// Rows no other row of the scene beats in both time and `error` (ties kept),
// in order of time.
std::vector<const Row*> pareto_front(const std::vector<Row>& rows, const std::string& scene,
                                     double Row::*error) {
    std::vector<const Row*> front;
    for (const Row& r : rows) {
        if (r.scene != scene) continue;
        bool dominated = false;
        for (const Row& o : rows)
            if (o.scene == scene && o.ms <= r.ms && o.*error <= r.*error && (o.ms < r.ms || o.*error < r.*error))
                dominated = true;
        if (!dominated) front.push_back(&r);
    }
    std::sort(front.begin(), front.end(), [](const Row* a, const Row* b) { return a->ms < b->ms; });
    return front;
}

std::string join(const std::vector<int>& values) {
    std::string out;
    for (int v : values) out += (out.empty() ? "" : ",") + std::to_string(v);
    return out;
}

std::string join(const std::vector<std::string>& values) {
    std::string out;
    for (const std::string& v : values) out += (out.empty() ? "" : ",") + v;
    return out;
}

std::string markdown(const std::vector<Row>& rows, const std::vector<Reference>& references, const Options& o) {
    std::ostringstream md;
    char line[512];
    md << "Generated by `bench_pareto --size " << o.width << "x" << o.height << " --repeat " << o.repeat
       << " --threads " << o.threads << " --scenes " << join(o.scenes) << " --methods " << join(o.methods)
       << " --spp " << join(o.spps) << " --reference-spp " << o.reference_spp << " --blur-sigma " << o.blur_sigma
       << "`.\n"
       << "Time: median of " << o.repeat << " wall-clock renders on " << o.threads
       << " thread(s), in ms. Errors against the Embree reference (" << o.reference_spp
       << " spp), in linear RGB; *blurred* = RMS of the difference after a Gaussian blur of sigma "
       << o.blur_sigma << " px. A row marked `R` is on the Pareto front of (time, RMSE), `B` of (time, blurred).\n\n";
    for (std::size_t s = 0; s < o.scenes.size(); ++s) {
        const std::string& scene = o.scenes[s];
        const std::vector<const Row*> by_rmse = pareto_front(rows, scene, &Row::rmse);
        const std::vector<const Row*> by_blur = pareto_front(rows, scene, &Row::structured);
        std::snprintf(line, sizeof line,
                      "#### %s\n\nReference noise (from its two halves): RMSE %.5f, blurred %.5f.\n\n",
                      scene.c_str(), references[s].rmse_floor, references[s].structured_floor);
        md << line;
        md << "| method | setting | ms | RMSE | blurred | blurred / RMSE | front |\n";
        md << "|---|---|---:|---:|---:|---:|---|\n";
        for (const Row& r : rows) {
            if (r.scene != scene) continue;
            const bool on_r = std::find(by_rmse.begin(), by_rmse.end(), &r) != by_rmse.end();
            const bool on_b = std::find(by_blur.begin(), by_blur.end(), &r) != by_blur.end();
            std::snprintf(line, sizeof line, "| %s | %s | %.0f | %.5f | %.5f | %.2f | %s%s |\n", r.method.c_str(),
                          r.setting.c_str(), r.ms, r.rmse, r.structured, r.structured / r.rmse, on_r ? "R" : "",
                          on_b ? "B" : "");
            md << line;
        }
        md << "\n";
    }
    return md.str();
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(arg + ": missing value");
            return argv[++i];
        };
        if (arg == "--size") {
            const std::string v = value();
            char tail = 0;
            if (std::sscanf(v.c_str(), "%dx%d%c", &o.width, &o.height, &tail) != 2 || o.width < 1 || o.height < 1 ||
                o.width > 8192 || o.height > 8192)
                throw std::invalid_argument("--size: expected WxH between 1x1 and 8192x8192, got '" + v + "'");
        } else if (arg == "--repeat") {
            o.repeat = parse_int(arg, value(), 1, 1000);
        } else if (arg == "--threads") {
            o.threads = parse_int(arg, value(), 0, 1024);
        } else if (arg == "--reference-spp") {
            o.reference_spp = parse_int(arg, value(), 2, 65536);
            if (o.reference_spp % 2 != 0)
                throw std::invalid_argument("--reference-spp: must be even (two halves), got " +
                                            std::to_string(o.reference_spp));
        } else if (arg == "--blur-sigma") {
            const std::string v = value();
            char* end = nullptr;
            o.blur_sigma = std::strtod(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(o.blur_sigma >= 0.5 && o.blur_sigma <= 64))
                throw std::invalid_argument("--blur-sigma: expected a number in [0.5, 64], got '" + v + "'");
        } else if (arg == "--scenes") {
            o.scenes = split(value());
            const std::vector<std::string> known = builtin_scene_names();
            for (const std::string& s : o.scenes)
                if (std::find(known.begin(), known.end(), s) == known.end())
                    throw std::invalid_argument("--scenes: unknown scene '" + s + "' (valid: " + join(known) + ")");
        } else if (arg == "--methods") {
            o.methods = split(value());
            for (const std::string& m : o.methods)
                if (std::find(known_methods().begin(), known_methods().end(), m) == known_methods().end())
                    throw std::invalid_argument("--methods: unknown method '" + m +
                                                "' (valid: " + join(known_methods()) + ")");
        } else if (arg == "--spp") {
            o.spps.clear();
            for (const std::string& s : split(value())) {
                const int spp = parse_int(arg, s, 1, 4096);
                if (square_root(spp) * square_root(spp) != spp)
                    throw std::invalid_argument("--spp: every count must be a square (interleave needs one), got " +
                                                s);
                o.spps.push_back(spp);
            }
        } else if (arg == "--cache") {
            o.cache_dir = value();
        } else if (arg == "--csv") {
            o.csv_path = value();
        } else if (arg == "--markdown") {
            o.markdown_path = value();
        } else {
            throw std::invalid_argument("unknown option '" + arg + "'");
        }
    }
    if (o.scenes.empty()) throw std::invalid_argument("--scenes: no scene given");
    if (o.methods.empty()) throw std::invalid_argument("--methods: no method given");
    if (o.spps.empty()) throw std::invalid_argument("--spp: no sample count given");
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parse(argc, argv);
        std::vector<Config> configs;
        for (const std::string& method : o.methods)
            for (int spp : o.spps)
                // N = spp tuples needs tiles of at least 2 x 2 cells.
                if (method != to_string(RenderMethod::interleave) || spp >= 4) configs.push_back({method, spp});

        std::vector<Row> rows;
        std::vector<Reference> references;
        for (const std::string& name : o.scenes) {
            SceneOptions scene_options;
            scene_options.aspect = float(o.width) / float(o.height);
            const Scene scene = make_builtin_scene(name, scene_options);
            references.push_back(make_reference(scene, name, o));
            const Reference& reference = references.back();

            RenderSettings settings;
            settings.width = o.width;
            settings.height = o.height;
            settings.seed = test_seed;
            settings.threads = o.threads;
            settings.progress = false;
            std::vector<Row> scene_rows(configs.size());
            std::vector<std::vector<double>> times(configs.size());
            for (int r = 0; r < o.repeat; ++r) {
                for (std::size_t c = 0; c < configs.size(); ++c) {
                    const Clock::time_point start = Clock::now();
                    const RenderResult result = render(scene, settings, configs[c]);
                    times[c].push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
                    if (r > 0) continue;  // every renderer is deterministic: measure the error once
                    Row& row = scene_rows[c];
                    row.scene = name;
                    row.method = configs[c].method;
                    row.setting = setting_label(configs[c]);
                    row.spp = configs[c].spp;
                    row.rmse = rmse(result.image, reference.image);
                    row.structured = structured_error(result.image, reference.image, o.blur_sigma);
                    row.tested = result.stats.samples_tested;
                    row.hit = result.stats.samples_hit;
                }
            }
            for (std::size_t c = 0; c < configs.size(); ++c) {
                Row& row = scene_rows[c];
                row.ms = median(times[c]);
                std::fprintf(stderr, "%s %s %d: %.0f ms, RMSE %.5f, blurred %.5f\n", name.c_str(),
                             row.method.c_str(), row.spp, row.ms, row.rmse, row.structured);
                rows.push_back(row);
            }
        }

        const std::string md = markdown(rows, references, o);
        std::printf("%s", md.c_str());
        if (!o.markdown_path.empty()) blurcull::bench::write_doc_section(o.markdown_path, "pareto-table", md);
        if (!o.csv_path.empty()) {
            std::ofstream csv(o.csv_path);
            if (!csv) throw std::runtime_error("cannot write '" + o.csv_path + "'");
            csv << "scene,method,setting,spp,ms,rmse,structured_error,reference_rmse,reference_structured,"
                   "samples_tested,samples_hit,width,height,threads,repeat,reference_spp,blur_sigma\n";
            char line[1024];
            for (const Row& r : rows) {
                const std::size_t s = static_cast<std::size_t>(
                    std::find(o.scenes.begin(), o.scenes.end(), r.scene) - o.scenes.begin());
                std::snprintf(line, sizeof line,
                              "%s,%s,%s,%d,%.2f,%.6g,%.6g,%.6g,%.6g,%llu,%llu,%d,%d,%d,%d,%d,%g\n", r.scene.c_str(),
                              r.method.c_str(), r.setting.c_str(), r.spp, r.ms, r.rmse, r.structured,
                              references[s].rmse_floor, references[s].structured_floor,
                              static_cast<unsigned long long>(r.tested), static_cast<unsigned long long>(r.hit),
                              o.width, o.height, o.threads, o.repeat, o.reference_spp, o.blur_sigma);
                csv << line;
            }
            if (!csv) throw std::runtime_error("cannot write '" + o.csv_path + "'");
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_pareto: error: %s\n", error.what());
        return 1;
    }
    return 0;
}
