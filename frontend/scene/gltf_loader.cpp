#include "scene/gltf_loader.hpp"

#include "scene/scene_checks.hpp"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace blurcull::frontend {

namespace {

namespace tg = tinygltf;

constexpr std::size_t kMaxNodeDepth = 1000;
// An accessor without a buffer view is all zeros (plus sparse values) and is
// bounded by no byte range: cap its element count so a huge count neither
// overflows count * components nor allocates without limit.
constexpr std::size_t kMaxElementsWithoutView = std::size_t{1} << 24;

std::string lowercase(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool has_extension(const std::string& path, const std::string& extension) {
    const std::string lower = lowercase(path);
    return lower.size() >= extension.size() &&
           lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0;
}

std::string directory_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash + 1);
}

std::string stem_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const std::size_t dot = name.find_last_of('.');
    return dot == std::string::npos ? name : name.substr(0, dot);
}

// tinygltf reports several lines; a SceneError is one line.
std::string one_line(const std::string& text) {
    std::string out;
    bool pending_separator = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pending_separator = !out.empty();
            continue;
        }
        if (pending_separator) {
            out += "; ";
            pending_separator = false;
        }
        out += c;
    }
    return out;
}

// Images are irrelevant to blurcull (flat base colours only): skip decoding,
// so a broken or exotic texture never stops a scene from loading.
bool ignore_image(tg::Image*, const int, std::string*, std::string*, int, int,
                  const unsigned char*, int, void*) {
    return true;
}

std::size_t component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

// Rows and columns of an accessor type (SCALAR 1x1, VEC3 3x1, MAT4 4x4).
bool type_shape(int type, std::size_t& rows, std::size_t& columns) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: rows = 1; columns = 1; return true;
        case TINYGLTF_TYPE_VEC2: rows = 2; columns = 1; return true;
        case TINYGLTF_TYPE_VEC3: rows = 3; columns = 1; return true;
        case TINYGLTF_TYPE_VEC4: rows = 4; columns = 1; return true;
        case TINYGLTF_TYPE_MAT2: rows = 2; columns = 2; return true;
        case TINYGLTF_TYPE_MAT3: rows = 3; columns = 3; return true;
        case TINYGLTF_TYPE_MAT4: rows = 4; columns = 4; return true;
        default: return false;
    }
}

// Where the components of one accessor element sit. Matrix columns start
// on 4-byte boundaries (glTF's padding rule for 1- and 2-byte components).
struct ElementLayout {
    std::size_t component_bytes = 0;
    std::size_t rows = 0;
    std::size_t columns = 0;
    std::size_t column_stride = 0;
    std::size_t size = 0;  // bytes of one element
    std::size_t components() const { return rows * columns; }
    std::size_t offset_of(std::size_t component) const {
        return (component / rows) * column_stride + (component % rows) * component_bytes;
    }
};

ElementLayout layout_of(const tg::Accessor& accessor) {
    ElementLayout layout;
    layout.component_bytes = component_size(accessor.componentType);
    if (layout.component_bytes == 0 || !type_shape(accessor.type, layout.rows, layout.columns)) {
        return ElementLayout{};
    }
    layout.column_stride = layout.rows * layout.component_bytes;
    if (layout.columns > 1) layout.column_stride = (layout.column_stride + 3) / 4 * 4;
    layout.size = layout.columns == 1 ? layout.column_stride
                                      : layout.column_stride * (layout.columns - 1) +
                                            layout.rows * layout.component_bytes;
    return layout;
}

double decode_component(const unsigned char* bytes, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t v;
            std::memcpy(&v, bytes, sizeof v);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            std::uint8_t v;
            std::memcpy(&v, bytes, sizeof v);
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, bytes, sizeof v);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, bytes, sizeof v);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_INT: {
            std::int32_t v;
            std::memcpy(&v, bytes, sizeof v);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, bytes, sizeof v);
            return v;
        }
        default: {
            float v;
            std::memcpy(&v, bytes, sizeof v);
            return v;
        }
    }
}

// True when `count` elements of `element_size` bytes, `stride` apart,
// starting at `offset`, fit in `length` bytes (without overflowing).
bool span_fits(std::size_t offset, std::size_t count, std::size_t stride, std::size_t element_size,
               std::size_t length) {
    if (count == 0) return offset <= length;
    if (offset > length || element_size > length - offset) return false;
    return count - 1 <= (length - offset - element_size) / stride;
}

bool finite_values(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

struct NodeTransform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
    bool uses_matrix = false;
    glm::mat4 matrix{1.0f};

    glm::mat4 local() const {
        if (uses_matrix) return matrix;
        return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
               glm::scale(glm::mat4(1.0f), scale);
    }
};

struct Sampler {
    std::vector<float> times;
    std::vector<float> values;  // keyframe values only (cubic tangents dropped)
    std::size_t components = 0;
    bool step = false;
};

class GltfLoader {
public:
    GltfLoader(const std::string& path, const GltfOptions& options)
        : path_(path), options_(options) {}

    Scene load() {
        check_options();
        parse_file();
        validate_buffers_and_accessors();
        validate_nodes();
        validate_meshes_skins_materials();
        validate_cameras();
        validate_animations();

        t_open_ = options_.shutter_open;
        t_close_ = options_.shutter_open +
                   (options_.shutter_close - options_.shutter_open) * options_.blur_scale;
        select_rendered_nodes();
        global_open_ = global_matrices(t_open_);
        global_close_ = global_matrices(t_close_);

        Scene scene;
        scene.name = stem_of(path_);
        for (int node : rendered_nodes_) {
            const tg::Node& n = model_.nodes[static_cast<std::size_t>(node)];
            if (n.mesh >= 0) add_mesh_instance(scene, node);
        }
        if (scene.triangles.empty()) fail("no triangles to render");
        setup_camera(scene);
        try {
            validate_scene(scene);
        } catch (const SceneError& error) {
            fail(error.what());
        }
        return scene;
    }

private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw SceneError(path_ + ": " + problem);
    }

    void warn_once(const std::string& kind, const std::string& message) {
        if (warned_.insert(kind).second) {
            std::cerr << path_ << ": warning: " << message << "\n";
        }
    }

    void check_options() const {
        const GltfOptions& o = options_;
        if (!std::isfinite(o.shutter_open) || !std::isfinite(o.shutter_close) ||
            o.shutter_close < o.shutter_open) {
            fail("shutter interval [" + std::to_string(o.shutter_open) + ", " +
                 std::to_string(o.shutter_close) + "] is not a finite, ordered interval");
        }
        if (!std::isfinite(o.blur_scale) || o.blur_scale < 0.0f) {
            fail("blur scale " + std::to_string(o.blur_scale) + " must be finite and non-negative");
        }
        if (!std::isfinite(o.aspect) || !(o.aspect > 0.0f)) {
            fail("aspect " + std::to_string(o.aspect) + " must be finite and positive");
        }
        if (!std::isfinite(o.lens_radius) || o.lens_radius < 0.0f) {
            fail("lens radius " + std::to_string(o.lens_radius) + " must be finite and non-negative");
        }
        if (!std::isfinite(o.focus_distance)) fail("focus distance is not finite");
    }

    void parse_file() {
        std::ifstream file(path_, std::ios::binary);
        if (!file) fail("cannot open file");
        std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                         std::istreambuf_iterator<char>());
        if (file.bad()) fail("cannot read file");
        if (bytes.size() >= UINT_MAX) fail("file is larger than 4 GiB");
        const auto length = static_cast<unsigned int>(bytes.size());

        tg::TinyGLTF parser;
        parser.SetImageLoader(ignore_image, nullptr);
        std::string error;
        std::string warning;
        bool ok = false;
        if (has_extension(path_, ".glb")) {
            check_glb_header(bytes);
            ok = parser.LoadBinaryFromMemory(&model_, &error, &warning, bytes.data(), length,
                                             directory_of(path_));
        } else {
            if (bytes.empty()) fail("file is empty");
            ok = parser.LoadASCIIFromString(&model_, &error, &warning,
                                            reinterpret_cast<const char*>(bytes.data()), length,
                                            directory_of(path_));
        }
        if (!ok) {
            const std::string reason = one_line(error.empty() ? warning : error);
            fail("cannot parse glTF: " + (reason.empty() ? std::string("unknown error") : reason));
        }
        if (!warning.empty()) warn_once("tinygltf", one_line(warning));
    }

    // tinygltf trusts the GLB chunk lengths; check them first.
    void check_glb_header(const std::vector<unsigned char>& bytes) const {
        auto u32 = [&](std::size_t offset) {
            std::uint32_t v;
            std::memcpy(&v, bytes.data() + offset, sizeof v);
            return v;  // GLB is little-endian, as is every platform blurcull runs on
        };
        if (bytes.size() < 20) fail("GLB file is shorter than its 20-byte header");
        if (std::memcmp(bytes.data(), "glTF", 4) != 0) fail("GLB file does not start with 'glTF'");
        if (u32(4) != 2) fail("GLB version " + std::to_string(u32(4)) + " is not 2");
        if (u32(8) > bytes.size()) {
            fail("GLB header says " + std::to_string(u32(8)) + " bytes but the file has " +
                 std::to_string(bytes.size()));
        }
        const std::uint64_t json_end = 20ull + u32(12);
        if (json_end > u32(8)) fail("GLB JSON chunk runs past the end of the file");
        if (u32(16) != 0x4E4F534Au) fail("GLB first chunk is not JSON");
    }

    // --- validation: every index and byte range, before any data is read ---

    void validate_buffers_and_accessors() {
        for (std::size_t v = 0; v < model_.bufferViews.size(); ++v) {
            const tg::BufferView& view = model_.bufferViews[v];
            if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
                fail("buffer view " + std::to_string(v) + " refers to buffer " +
                     std::to_string(view.buffer) + ", which does not exist");
            }
            const std::size_t buffer_size = model_.buffers[static_cast<std::size_t>(view.buffer)].data.size();
            if (!span_fits(view.byteOffset, 1, 1, view.byteLength, buffer_size)) {
                fail("buffer view " + std::to_string(v) + " (offset " + std::to_string(view.byteOffset) +
                     ", length " + std::to_string(view.byteLength) + ") reads past the end of buffer " +
                     std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes)");
            }
        }
        for (std::size_t a = 0; a < model_.accessors.size(); ++a) validate_accessor(a);
    }

    void check_view_index(int view, const std::string& owner) const {
        if (view < 0 || static_cast<std::size_t>(view) >= model_.bufferViews.size()) {
            fail(owner + " refers to buffer view " + std::to_string(view) + ", which does not exist");
        }
    }

    void validate_accessor(std::size_t index) const {
        const tg::Accessor& accessor = model_.accessors[index];
        const std::string name = "accessor " + std::to_string(index);
        const ElementLayout layout = layout_of(accessor);
        if (layout.size == 0) {
            fail(name + " has an unknown component type " + std::to_string(accessor.componentType) +
                 " or type " + std::to_string(accessor.type));
        }
        if (accessor.bufferView >= 0) {
            check_view_index(accessor.bufferView, name);
            const tg::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
            const std::size_t stride = view.byteStride == 0 ? layout.size : view.byteStride;
            if (stride < layout.size) {
                fail(name + ": buffer view " + std::to_string(accessor.bufferView) + " stride " +
                     std::to_string(stride) + " is smaller than an element (" +
                     std::to_string(layout.size) + " bytes)");
            }
            if (!span_fits(accessor.byteOffset, accessor.count, stride, layout.size, view.byteLength)) {
                fail(name + " reads past the end of buffer view " + std::to_string(accessor.bufferView));
            }
        } else if (accessor.bufferView != -1) {
            check_view_index(accessor.bufferView, name);
        } else if (accessor.count > kMaxElementsWithoutView) {
            fail(name + " has no buffer view and count " + std::to_string(accessor.count) + " (limit " +
                 std::to_string(kMaxElementsWithoutView) + ")");
        }
        if (accessor.sparse.isSparse) {
            const auto& sparse = accessor.sparse;
            if (sparse.count < 0 || static_cast<std::size_t>(sparse.count) > accessor.count) {
                fail(name + ": sparse count " + std::to_string(sparse.count) + " exceeds its count " +
                     std::to_string(accessor.count));
            }
            const std::size_t index_bytes = component_size(sparse.indices.componentType);
            if (index_bytes == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
                fail(name + ": sparse indices have an invalid component type");
            }
            check_view_index(sparse.indices.bufferView, name + " (sparse indices)");
            check_view_index(sparse.values.bufferView, name + " (sparse values)");
            const auto count = static_cast<std::size_t>(sparse.count);
            if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0 ||
                !span_fits(static_cast<std::size_t>(sparse.indices.byteOffset), count, index_bytes,
                           index_bytes,
                           model_.bufferViews[static_cast<std::size_t>(sparse.indices.bufferView)].byteLength)) {
                fail(name + ": sparse indices read past the end of buffer view " +
                     std::to_string(sparse.indices.bufferView));
            }
            if (!span_fits(static_cast<std::size_t>(sparse.values.byteOffset), count, layout.size,
                           layout.size,
                           model_.bufferViews[static_cast<std::size_t>(sparse.values.bufferView)].byteLength)) {
                fail(name + ": sparse values read past the end of buffer view " +
                     std::to_string(sparse.values.bufferView));
            }
        }
    }

    void check_accessor_index(int accessor, const std::string& owner) const {
        if (accessor < 0 || static_cast<std::size_t>(accessor) >= model_.accessors.size()) {
            fail(owner + " refers to accessor " + std::to_string(accessor) + ", which does not exist");
        }
    }

    void validate_nodes() {
        const std::size_t count = model_.nodes.size();
        parent_.assign(count, -1);
        for (std::size_t i = 0; i < count; ++i) {
            const tg::Node& node = model_.nodes[i];
            const std::string name = "node " + std::to_string(i);
            for (int child : node.children) {
                if (child < 0 || static_cast<std::size_t>(child) >= count) {
                    fail(name + " has child " + std::to_string(child) + ", which does not exist");
                }
                if (static_cast<std::size_t>(child) == i) fail("node cycle: " + name + " is its own child");
                int& parent = parent_[static_cast<std::size_t>(child)];
                if (parent >= 0) {
                    fail("node " + std::to_string(child) + " has two parents (nodes " +
                         std::to_string(parent) + " and " + std::to_string(i) + ")");
                }
                parent = static_cast<int>(i);
            }
            auto check_reference = [&](int value, std::size_t available, const char* what) {
                if (value < -1 || (value >= 0 && static_cast<std::size_t>(value) >= available)) {
                    fail(name + " refers to " + what + " " + std::to_string(value) + ", which does not exist");
                }
            };
            check_reference(node.mesh, model_.meshes.size(), "mesh");
            check_reference(node.camera, model_.cameras.size(), "camera");
            check_reference(node.skin, model_.skins.size(), "skin");
            if (!node.matrix.empty() && node.matrix.size() != 16) fail(name + " matrix does not have 16 numbers");
            if (!node.translation.empty() && node.translation.size() != 3) fail(name + " translation does not have 3 numbers");
            if (!node.rotation.empty() && node.rotation.size() != 4) fail(name + " rotation does not have 4 numbers");
            if (!node.scale.empty() && node.scale.size() != 3) fail(name + " scale does not have 3 numbers");
            if (!finite_values(node.matrix) || !finite_values(node.translation) ||
                !finite_values(node.rotation) || !finite_values(node.scale)) {
                fail(name + " has a non-finite transform");
            }
        }
        // Every node has at most one parent now, so walking up terminates
        // unless there is a cycle; depths are memoised.
        depth_.assign(count, 0);
        std::vector<char> known(count, 0);
        for (std::size_t start = 0; start < count; ++start) {
            std::vector<std::size_t> chain;
            std::size_t node = start;
            while (!known[node] && parent_[node] >= 0) {
                chain.push_back(node);
                if (chain.size() > count) fail("node cycle: node " + std::to_string(start) + " is its own ancestor");
                node = static_cast<std::size_t>(parent_[node]);
            }
            std::size_t depth = known[node] ? depth_[node] : 0;
            known[node] = 1;
            for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
                depth_[*it] = ++depth;
                known[*it] = 1;
            }
            if (depth > kMaxNodeDepth) {
                fail("node " + std::to_string(start) + " is nested " + std::to_string(depth) +
                     " levels deep (limit " + std::to_string(kMaxNodeDepth) + ")");
            }
        }
        for (std::size_t s = 0; s < model_.scenes.size(); ++s) {
            for (int root : model_.scenes[s].nodes) {
                if (root < 0 || static_cast<std::size_t>(root) >= count) {
                    fail("scene " + std::to_string(s) + " refers to node " + std::to_string(root) +
                         ", which does not exist");
                }
            }
        }
    }

    void validate_meshes_skins_materials() const {
        for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
            const auto& primitives = model_.meshes[m].primitives;
            for (std::size_t p = 0; p < primitives.size(); ++p) {
                const tg::Primitive& primitive = primitives[p];
                const std::string name = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
                for (const auto& attribute : primitive.attributes) {
                    check_accessor_index(attribute.second, name + " attribute " + attribute.first);
                }
                if (primitive.indices != -1) check_accessor_index(primitive.indices, name + " indices");
                if (primitive.material < -1 ||
                    (primitive.material >= 0 &&
                     static_cast<std::size_t>(primitive.material) >= model_.materials.size())) {
                    fail(name + " refers to material " + std::to_string(primitive.material) +
                         ", which does not exist");
                }
            }
        }
        for (std::size_t s = 0; s < model_.skins.size(); ++s) {
            const tg::Skin& skin = model_.skins[s];
            const std::string name = "skin " + std::to_string(s);
            for (int joint : skin.joints) {
                if (joint < 0 || static_cast<std::size_t>(joint) >= model_.nodes.size()) {
                    fail(name + " refers to joint node " + std::to_string(joint) + ", which does not exist");
                }
            }
            if (skin.inverseBindMatrices != -1) {
                check_accessor_index(skin.inverseBindMatrices, name + " inverseBindMatrices");
                const tg::Accessor& accessor = model_.accessors[static_cast<std::size_t>(skin.inverseBindMatrices)];
                if (accessor.type != TINYGLTF_TYPE_MAT4 || accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
                    fail(name + " inverseBindMatrices accessor is not float MAT4");
                }
                if (accessor.count < skin.joints.size()) {
                    fail(name + " has " + std::to_string(skin.joints.size()) + " joints but only " +
                         std::to_string(accessor.count) + " inverse bind matrices");
                }
            }
        }
    }

    void validate_cameras() const {
        for (std::size_t c = 0; c < model_.cameras.size(); ++c) {
            const tg::Camera& camera = model_.cameras[c];
            const std::string name = "camera " + std::to_string(c);
            if (camera.type == "perspective") {
                const double yfov = camera.perspective.yfov;
                if (!std::isfinite(yfov) || yfov <= 0.0 || yfov >= 3.14159265) {
                    fail(name + " has yfov " + std::to_string(yfov) + " (must be in (0, pi))");
                }
                const double znear = camera.perspective.znear;
                if (!std::isfinite(znear) || znear <= 0.0) {
                    fail(name + " has znear " + std::to_string(znear) + " (must be positive)");
                }
                // zfar 0 is tinygltf's "absent" (an infinite projection).
                const double zfar = camera.perspective.zfar;
                if (zfar != 0.0 && !(zfar > znear)) {
                    fail(name + " has zfar " + std::to_string(zfar) + " (must be greater than znear " +
                         std::to_string(znear) + ")");
                }
            } else if (camera.type != "orthographic") {
                fail(name + " has unknown type '" + camera.type + "'");
            }
        }
    }

    void validate_animations() {
        for (std::size_t a = 0; a < model_.animations.size(); ++a) {
            const tg::Animation& animation = model_.animations[a];
            const std::string name = "animation " + std::to_string(a);
            for (std::size_t c = 0; c < animation.channels.size(); ++c) {
                const tg::AnimationChannel& channel = animation.channels[c];
                if (channel.sampler < 0 || static_cast<std::size_t>(channel.sampler) >= animation.samplers.size()) {
                    fail(name + " channel " + std::to_string(c) + " refers to sampler " +
                         std::to_string(channel.sampler) + ", which does not exist");
                }
                if (channel.target_node >= 0 &&
                    static_cast<std::size_t>(channel.target_node) >= model_.nodes.size()) {
                    fail(name + " channel " + std::to_string(c) + " targets node " +
                         std::to_string(channel.target_node) + ", which does not exist");
                }
            }
            for (std::size_t s = 0; s < animation.samplers.size(); ++s) {
                read_sampler(a, s);  // reading validates; the result is cached
            }
        }
    }

    // --- reading ---

    // count * components values of an accessor, normalised integers mapped
    // to [0, 1] / [-1, 1], sparse substitutions applied.
    std::vector<double> read_values(int accessor_index) const {
        const tg::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessor_index)];
        const ElementLayout layout = layout_of(accessor);
        const std::size_t components = layout.components();
        std::vector<double> values(accessor.count * components, 0.0);
        auto decode_element = [&](const unsigned char* element, std::size_t target) {
            for (std::size_t c = 0; c < components; ++c) {
                values[target * components + c] = decode_component(
                    element + layout.offset_of(c), accessor.componentType, accessor.normalized);
            }
        };
        if (accessor.bufferView >= 0) {
            const tg::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
            const unsigned char* base =
                model_.buffers[static_cast<std::size_t>(view.buffer)].data.data() + view.byteOffset + accessor.byteOffset;
            const std::size_t stride = view.byteStride == 0 ? layout.size : view.byteStride;
            for (std::size_t i = 0; i < accessor.count; ++i) decode_element(base + i * stride, i);
        }
        if (accessor.sparse.isSparse) {
            const auto& sparse = accessor.sparse;
            const tg::BufferView& index_view = model_.bufferViews[static_cast<std::size_t>(sparse.indices.bufferView)];
            const tg::BufferView& value_view = model_.bufferViews[static_cast<std::size_t>(sparse.values.bufferView)];
            const unsigned char* indices = model_.buffers[static_cast<std::size_t>(index_view.buffer)].data.data() +
                                           index_view.byteOffset + static_cast<std::size_t>(sparse.indices.byteOffset);
            const unsigned char* substitutes = model_.buffers[static_cast<std::size_t>(value_view.buffer)].data.data() +
                                               value_view.byteOffset + static_cast<std::size_t>(sparse.values.byteOffset);
            const std::size_t index_bytes = component_size(sparse.indices.componentType);
            for (std::size_t k = 0; k < static_cast<std::size_t>(sparse.count); ++k) {
                const double target = decode_component(indices + k * index_bytes, sparse.indices.componentType, false);
                if (!(target >= 0.0) || target >= static_cast<double>(accessor.count)) {
                    fail("accessor " + std::to_string(accessor_index) + ": sparse index " +
                         std::to_string(target) + " is outside its " + std::to_string(accessor.count) + " elements");
                }
                decode_element(substitutes + k * layout.size, static_cast<std::size_t>(target));
            }
        }
        return values;
    }

    std::vector<std::uint32_t> read_integers(int accessor_index, const std::string& what) const {
        const tg::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessor_index)];
        if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            fail(what + " accessor " + std::to_string(accessor_index) + " holds floats, not integers");
        }
        const std::vector<double> values = read_values(accessor_index);
        std::vector<std::uint32_t> integers(values.size());
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (values[i] < 0.0) {
                fail(what + " accessor " + std::to_string(accessor_index) + " holds a negative value " +
                     std::to_string(values[i]));
            }
            integers[i] = static_cast<std::uint32_t>(values[i]);
        }
        return integers;
    }

    const Sampler& read_sampler(std::size_t animation_index, std::size_t sampler_index) {
        const auto key = std::make_pair(animation_index, sampler_index);
        const auto cached = samplers_.find(key);
        if (cached != samplers_.end()) return cached->second;

        const tg::AnimationSampler& source = model_.animations[animation_index].samplers[sampler_index];
        const std::string name =
            "animation " + std::to_string(animation_index) + " sampler " + std::to_string(sampler_index);
        check_accessor_index(source.input, name + " input");
        check_accessor_index(source.output, name + " output");
        const tg::Accessor& input = model_.accessors[static_cast<std::size_t>(source.input)];
        const tg::Accessor& output = model_.accessors[static_cast<std::size_t>(source.output)];
        if (input.type != TINYGLTF_TYPE_SCALAR || input.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
            fail(name + ": keyframe times are not float scalars");
        }
        if (input.count == 0) fail(name + " has no keyframes");
        Sampler sampler;
        const bool cubic = source.interpolation == "CUBICSPLINE";
        if (source.interpolation == "STEP") {
            sampler.step = true;
        } else if (source.interpolation != "LINEAR" && !cubic) {
            fail(name + " has unknown interpolation '" + source.interpolation + "'");
        }
        for (double t : read_values(source.input)) sampler.times.push_back(static_cast<float>(t));
        for (std::size_t k = 0; k < sampler.times.size(); ++k) {
            if (!std::isfinite(sampler.times[k])) {
                fail(name + ": keyframe time " + std::to_string(k) + " is not finite");
            }
            if (k > 0 && sampler.times[k] < sampler.times[k - 1]) {
                fail(name + ": keyframe times are not increasing (time " + std::to_string(k) + " = " +
                     std::to_string(sampler.times[k]) + " after " + std::to_string(sampler.times[k - 1]) + ")");
            }
        }
        const std::size_t per_key = cubic ? 3 : 1;
        if (output.count % (input.count * per_key) != 0 || output.count == 0) {
            fail(name + " has " + std::to_string(output.count) + " output values for " +
                 std::to_string(input.count) + " keyframes");
        }
        // Morph weights have several values per keyframe; node channels one.
        const std::size_t elements_per_key = output.count / (input.count * per_key);
        const std::vector<double> raw = read_values(source.output);
        if (!finite_values(raw)) fail(name + " has a non-finite output value");
        sampler.components = raw.size() / output.count * elements_per_key;
        for (std::size_t k = 0; k < input.count; ++k) {
            // CUBICSPLINE stores (in-tangent, value, out-tangent) per key: keep the value.
            const std::size_t first = (k * per_key + (cubic ? 1 : 0)) * sampler.components;
            for (std::size_t c = 0; c < sampler.components; ++c) {
                sampler.values.push_back(static_cast<float>(raw[first + c]));
            }
        }
        return samplers_.emplace(key, std::move(sampler)).first->second;
    }

    // The sampler's value at time t: clamped outside the keyframes; STEP
    // holds the earlier key; LINEAR lerps (or slerps for rotations).
    static std::vector<float> evaluate(const Sampler& sampler, float t, bool rotation) {
        const std::size_t n = sampler.times.size();
        const std::size_t c = sampler.components;
        auto key = [&](std::size_t k) {
            return std::vector<float>(sampler.values.begin() + static_cast<std::ptrdiff_t>(k * c),
                                      sampler.values.begin() + static_cast<std::ptrdiff_t>((k + 1) * c));
        };
        if (t <= sampler.times.front()) return key(0);
        if (t >= sampler.times.back()) return key(n - 1);
        const std::size_t upper = static_cast<std::size_t>(
            std::upper_bound(sampler.times.begin(), sampler.times.end(), t) - sampler.times.begin());
        const std::size_t lower = upper - 1;
        if (sampler.step) return key(lower);
        const float span = sampler.times[upper] - sampler.times[lower];
        const float f = span > 0.0f ? (t - sampler.times[lower]) / span : 0.0f;
        std::vector<float> a = key(lower);
        const std::vector<float> b = key(upper);
        if (rotation && c == 4) {
            const glm::quat qa = glm::normalize(glm::quat(a[3], a[0], a[1], a[2]));
            const glm::quat qb = glm::normalize(glm::quat(b[3], b[0], b[1], b[2]));
            const glm::quat q = glm::slerp(qa, qb, f);
            return {q.x, q.y, q.z, q.w};
        }
        for (std::size_t i = 0; i < c; ++i) a[i] += (b[i] - a[i]) * f;
        return a;
    }

    // --- scene graph ---

    void select_rendered_nodes() {
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            const std::size_t scene =
                model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) < model_.scenes.size()
                    ? static_cast<std::size_t>(model_.defaultScene) : 0;
            roots = model_.scenes[scene].nodes;
        } else {
            for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
                if (parent_[i] < 0) roots.push_back(static_cast<int>(i));
            }
        }
        std::vector<char> seen(model_.nodes.size(), 0);
        std::vector<int> stack(roots.rbegin(), roots.rend());
        while (!stack.empty()) {
            const int node = stack.back();
            stack.pop_back();
            if (seen[static_cast<std::size_t>(node)]) continue;
            seen[static_cast<std::size_t>(node)] = 1;
            rendered_nodes_.push_back(node);
            const auto& children = model_.nodes[static_cast<std::size_t>(node)].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
        }
    }

    std::vector<glm::mat4> global_matrices(float t) {
        const std::size_t count = model_.nodes.size();
        std::vector<NodeTransform> transforms(count);
        for (std::size_t i = 0; i < count; ++i) {
            const tg::Node& node = model_.nodes[i];
            NodeTransform& transform = transforms[i];
            if (node.matrix.size() == 16) {
                transform.uses_matrix = true;
                for (int k = 0; k < 16; ++k) {
                    glm::value_ptr(transform.matrix)[k] = static_cast<float>(node.matrix[static_cast<std::size_t>(k)]);
                }
            }
            if (node.translation.size() == 3) {
                transform.translation = glm::vec3(static_cast<float>(node.translation[0]),
                                                  static_cast<float>(node.translation[1]),
                                                  static_cast<float>(node.translation[2]));
            }
            if (node.rotation.size() == 4) {
                transform.rotation = glm::quat(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                               static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
            }
            if (node.scale.size() == 3) {
                transform.scale = glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                            static_cast<float>(node.scale[2]));
            }
        }
        apply_animation(transforms, t);
        for (NodeTransform& transform : transforms) {
            const float length = glm::length(transform.rotation);
            transform.rotation = length > 0.0f ? transform.rotation / length : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
        }
        // Parents before children: process in order of depth.
        std::vector<std::size_t> order(count);
        for (std::size_t i = 0; i < count; ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return depth_[a] < depth_[b]; });
        std::vector<glm::mat4> global(count, glm::mat4(1.0f));
        for (std::size_t i : order) {
            const glm::mat4 local = transforms[i].local();
            global[i] = parent_[i] >= 0 ? global[static_cast<std::size_t>(parent_[i])] * local : local;
        }
        return global;
    }

    void apply_animation(std::vector<NodeTransform>& transforms, float t) {
        if (options_.animation_index < 0 || model_.animations.empty()) return;
        const auto index = static_cast<std::size_t>(options_.animation_index);
        if (index >= model_.animations.size()) {
            fail("animation " + std::to_string(options_.animation_index) + " does not exist (the file has " +
                 std::to_string(model_.animations.size()) + ")");
        }
        const tg::Animation& animation = model_.animations[index];
        for (const tg::AnimationChannel& channel : animation.channels) {
            if (channel.target_node < 0) continue;  // e.g. targets an extension's object
            NodeTransform& transform = transforms[static_cast<std::size_t>(channel.target_node)];
            const std::string& path = channel.target_path;
            if (path == "weights") {
                warn_once("weights", "morph target weight animation is ignored");
                continue;
            }
            if (path != "translation" && path != "rotation" && path != "scale") {
                warn_once("path " + path, "animation path '" + path + "' is ignored");
                continue;
            }
            if (transform.uses_matrix) {
                warn_once("matrix", "animation of a node given by a matrix is ignored (glTF requires TRS there)");
                continue;
            }
            const Sampler& sampler = read_sampler(index, static_cast<std::size_t>(channel.sampler));
            const std::size_t expected = path == "rotation" ? 4 : 3;
            if (sampler.components != expected) {
                fail("animation " + std::to_string(index) + " channel for '" + path + "' has " +
                     std::to_string(sampler.components) + " components per key, expected " +
                     std::to_string(expected));
            }
            const std::vector<float> v = evaluate(sampler, t, path == "rotation");
            if (path == "translation") transform.translation = glm::vec3(v[0], v[1], v[2]);
            if (path == "scale") transform.scale = glm::vec3(v[0], v[1], v[2]);
            if (path == "rotation") transform.rotation = glm::quat(v[3], v[0], v[1], v[2]);
        }
    }

    // --- geometry ---

    std::uint32_t material_for(Scene& scene, int gltf_material) {
        const auto found = material_map_.find(gltf_material);
        if (found != material_map_.end()) return found->second;
        Material material;
        if (gltf_material >= 0) {
            const tg::Material& source = model_.materials[static_cast<std::size_t>(gltf_material)];
            material.name = source.name;
            const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() >= 3 && finite_values(factor)) {
                material.base_color = glm::clamp(glm::vec3(static_cast<float>(factor[0]), static_cast<float>(factor[1]),
                                                           static_cast<float>(factor[2])),
                                                 0.0f, 1.0f);
            }
        } else {
            material.name = "default";
        }
        scene.materials.push_back(material);
        const auto index = static_cast<std::uint32_t>(scene.materials.size() - 1);
        material_map_.emplace(gltf_material, index);
        return index;
    }

    std::vector<glm::mat4> joint_matrices(const tg::Skin& skin, const std::vector<glm::mat4>& global) const {
        std::vector<glm::mat4> inverse_bind(skin.joints.size(), glm::mat4(1.0f));
        if (skin.inverseBindMatrices >= 0) {
            const std::vector<double> values = read_values(skin.inverseBindMatrices);
            for (std::size_t j = 0; j < skin.joints.size(); ++j) {
                for (std::size_t k = 0; k < 16; ++k) {
                    glm::value_ptr(inverse_bind[j])[k] = static_cast<float>(values[j * 16 + k]);
                }
            }
        }
        std::vector<glm::mat4> joints(skin.joints.size());
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            joints[j] = global[static_cast<std::size_t>(skin.joints[j])] * inverse_bind[j];
        }
        return joints;
    }

    void add_mesh_instance(Scene& scene, int node_index) {
        const tg::Node& node = model_.nodes[static_cast<std::size_t>(node_index)];
        const tg::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            add_primitive(scene, node_index, mesh.primitives[p],
                          "mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p));
        }
    }

    void add_primitive(Scene& scene, int node_index, const tg::Primitive& primitive, const std::string& name) {
        const tg::Node& node = model_.nodes[static_cast<std::size_t>(node_index)];
        const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
        if (mode == TINYGLTF_MODE_POINTS) {
            warn_once("points", "points primitives are skipped");
            return;
        }
        if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
            warn_once("lines", "line primitives are skipped");
            return;
        }
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            fail(name + " has unknown mode " + std::to_string(mode));
        }
        const auto position_attribute = primitive.attributes.find("POSITION");
        if (position_attribute == primitive.attributes.end()) {
            warn_once("no position", name + " has no POSITION attribute; skipped");
            return;
        }
        if (!primitive.targets.empty()) warn_once("morph", "morph targets are ignored");
        const int position_accessor = position_attribute->second;
        if (model_.accessors[static_cast<std::size_t>(position_accessor)].type != TINYGLTF_TYPE_VEC3) {
            fail(name + " POSITION accessor " + std::to_string(position_accessor) + " is not VEC3");
        }
        const std::vector<double> raw = read_values(position_accessor);
        const std::size_t vertex_count = raw.size() / 3;
        if (!finite_values(raw)) {
            warn_once("nonfinite " + name, name + " has non-finite positions; skipped");
            return;
        }

        std::vector<std::uint32_t> indices;
        if (primitive.indices >= 0) {
            if (model_.accessors[static_cast<std::size_t>(primitive.indices)].type != TINYGLTF_TYPE_SCALAR) {
                fail(name + " index accessor " + std::to_string(primitive.indices) + " is not SCALAR");
            }
            indices = read_integers(primitive.indices, name + " index");
            for (std::size_t i = 0; i < indices.size(); ++i) {
                if (indices[i] >= vertex_count) {
                    fail(name + ": index value " + std::to_string(indices[i]) + " (at " + std::to_string(i) +
                         ") is not below the vertex count " + std::to_string(vertex_count));
                }
            }
        } else {
            if (vertex_count > std::numeric_limits<std::uint32_t>::max()) fail(name + " has too many vertices");
            indices.resize(vertex_count);
            for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
        }

        std::vector<glm::uvec3> triangles;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (indices.size() % 3 != 0) warn_once("partial " + name, name + ": index count is not a multiple of 3; the rest is ignored");
            for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
                triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other triangle swaps its first two corners to keep the winding.
            for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
                if (i % 2 == 0) triangles.emplace_back(indices[i], indices[i + 1], indices[i + 2]);
                else triangles.emplace_back(indices[i + 1], indices[i], indices[i + 2]);
            }
        } else {
            for (std::size_t i = 1; i + 1 < indices.size(); ++i) {
                triangles.emplace_back(indices[i], indices[i + 1], indices[0]);
            }
        }
        if (triangles.empty()) return;

        // Per-vertex transforms at both shutter ends: skinning when the node
        // has a skin and the primitive has joints, the node's matrix otherwise.
        std::vector<glm::vec3> open(vertex_count), close(vertex_count);
        bool skinned = false;
        if (node.skin >= 0 && primitive.attributes.count("JOINTS_0") && primitive.attributes.count("WEIGHTS_0")) {
            skinned = skin_vertices(raw, node, primitive, name, open, close);
        }
        if (!skinned) {
            const glm::mat4& m0 = global_open_[static_cast<std::size_t>(node_index)];
            const glm::mat4& m1 = global_close_[static_cast<std::size_t>(node_index)];
            for (std::size_t v = 0; v < vertex_count; ++v) {
                const glm::vec4 p(static_cast<float>(raw[3 * v]), static_cast<float>(raw[3 * v + 1]),
                                  static_cast<float>(raw[3 * v + 2]), 1.0f);
                open[v] = glm::vec3(m0 * p);
                close[v] = glm::vec3(m1 * p);
            }
        }
        for (std::size_t v = 0; v < vertex_count; ++v) {
            const glm::vec3 both[2] = {open[v], close[v]};
            for (const glm::vec3& q : both) {
                if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
                    warn_once("nonfinite " + name, name + " has non-finite transformed positions; skipped");
                    return;
                }
            }
        }

        const std::size_t base = scene.position_open.size();
        if (base + vertex_count > std::numeric_limits<std::uint32_t>::max()) fail("scene has too many vertices");
        scene.position_open.insert(scene.position_open.end(), open.begin(), open.end());
        scene.position_close.insert(scene.position_close.end(), close.begin(), close.end());
        const std::uint32_t material = material_for(scene, primitive.material);
        const glm::uvec3 offset(static_cast<std::uint32_t>(base));
        for (const glm::uvec3& triangle : triangles) {
            scene.triangles.push_back(triangle + offset);
            scene.triangle_material.push_back(material);
        }
    }

    // Linear blend skinning at both shutter ends. Returns false (use the
    // node transform) when no vertex has any weight.
    bool skin_vertices(const std::vector<double>& raw, const tg::Node& node, const tg::Primitive& primitive,
                       const std::string& name, std::vector<glm::vec3>& open, std::vector<glm::vec3>& close) {
        const tg::Skin& skin = model_.skins[static_cast<std::size_t>(node.skin)];
        const std::size_t vertex_count = raw.size() / 3;
        const std::vector<glm::mat4> joints_open = joint_matrices(skin, global_open_);
        const std::vector<glm::mat4> joints_close = joint_matrices(skin, global_close_);
        std::vector<glm::mat4> blend_open(vertex_count, glm::mat4(0.0f));
        std::vector<glm::mat4> blend_close(vertex_count, glm::mat4(0.0f));
        std::vector<float> weight_sum(vertex_count, 0.0f);
        for (int set = 0;; ++set) {
            const auto joints_attribute = primitive.attributes.find("JOINTS_" + std::to_string(set));
            const auto weights_attribute = primitive.attributes.find("WEIGHTS_" + std::to_string(set));
            if (joints_attribute == primitive.attributes.end() || weights_attribute == primitive.attributes.end()) break;
            const std::string set_name = name + " JOINTS_" + std::to_string(set);
            const tg::Accessor& joints_accessor = model_.accessors[static_cast<std::size_t>(joints_attribute->second)];
            const tg::Accessor& weights_accessor = model_.accessors[static_cast<std::size_t>(weights_attribute->second)];
            if (joints_accessor.type != TINYGLTF_TYPE_VEC4 || weights_accessor.type != TINYGLTF_TYPE_VEC4) {
                fail(set_name + " / WEIGHTS_" + std::to_string(set) + " are not VEC4");
            }
            if (joints_accessor.count != vertex_count || weights_accessor.count != vertex_count) {
                fail(set_name + " / WEIGHTS_" + std::to_string(set) + " do not have one entry per vertex");
            }
            const std::vector<std::uint32_t> joint_ids = read_integers(joints_attribute->second, set_name);
            const std::vector<double> weights = read_values(weights_attribute->second);
            for (std::size_t v = 0; v < vertex_count; ++v) {
                for (std::size_t k = 0; k < 4; ++k) {
                    const auto weight = static_cast<float>(weights[4 * v + k]);
                    if (!std::isfinite(weight)) fail(name + " has a non-finite skin weight");
                    if (weight == 0.0f) continue;
                    const std::uint32_t joint = joint_ids[4 * v + k];
                    if (joint >= skin.joints.size()) {
                        fail(set_name + ": joint " + std::to_string(joint) + " of vertex " + std::to_string(v) +
                             " is not below the skin's joint count " + std::to_string(skin.joints.size()));
                    }
                    blend_open[v] += weight * joints_open[joint];
                    blend_close[v] += weight * joints_close[joint];
                    weight_sum[v] += weight;
                }
            }
        }
        bool any_weight = false;
        for (std::size_t v = 0; v < vertex_count; ++v) {
            const glm::vec4 p(static_cast<float>(raw[3 * v]), static_cast<float>(raw[3 * v + 1]),
                              static_cast<float>(raw[3 * v + 2]), 1.0f);
            if (weight_sum[v] > 0.0f) {
                any_weight = true;
                // Exporters round weights; renormalise instead of shrinking.
                open[v] = glm::vec3(blend_open[v] * p) / weight_sum[v];
                close[v] = glm::vec3(blend_close[v] * p) / weight_sum[v];
            } else {
                warn_once("unweighted " + name, name + " has vertices without skin weights; they are left untransformed");
                open[v] = close[v] = glm::vec3(p);
            }
        }
        return any_weight;
    }

    // --- camera ---

    glm::mat4 view_from_node(const glm::mat4& global, int node) const {
        glm::mat4 camera_to_world = global;
        // Cameras ignore scale: keep the orientation and position only.
        for (int axis = 0; axis < 3; ++axis) {
            const glm::vec3 column(camera_to_world[axis]);
            const float length = glm::length(column);
            if (!(length > 1e-12f) || !std::isfinite(length)) {
                fail("camera node " + std::to_string(node) + " has a degenerate (zero-scale) transform");
            }
            camera_to_world[axis] = glm::vec4(column / length, 0.0f);
        }
        return glm::inverse(camera_to_world);
    }

    void setup_camera(Scene& scene) {
        const SceneStats stats = describe(scene);
        const glm::vec3 center = 0.5f * (stats.bounds_min + stats.bounds_max);
        const float radius = std::max(0.5f * glm::length(stats.bounds_max - stats.bounds_min), 1e-3f);

        int camera_node = -1;
        if (options_.camera_index >= 0) {
            if (static_cast<std::size_t>(options_.camera_index) >= model_.cameras.size()) {
                fail("camera " + std::to_string(options_.camera_index) + " does not exist (the file has " +
                     std::to_string(model_.cameras.size()) + ")");
            }
            if (model_.cameras[static_cast<std::size_t>(options_.camera_index)].type != "perspective") {
                fail("camera " + std::to_string(options_.camera_index) +
                     " is orthographic; only perspective cameras are supported");
            }
            camera_node = find_camera_node(options_.camera_index);
            if (camera_node < 0) {
                fail("camera " + std::to_string(options_.camera_index) + " is not attached to any node of the scene");
            }
        } else {
            bool saw_orthographic = false;
            for (int node : rendered_nodes_) {
                const int camera = model_.nodes[static_cast<std::size_t>(node)].camera;
                if (camera < 0) continue;
                if (model_.cameras[static_cast<std::size_t>(camera)].type == "perspective") {
                    camera_node = node;
                    break;
                }
                saw_orthographic = true;
            }
            if (camera_node < 0 && saw_orthographic) {
                warn_once("orthographic", "orthographic cameras are not supported; using an automatic perspective camera");
            }
        }

        Camera& camera = scene.camera;
        if (camera_node >= 0) {
            const tg::Camera& source =
                model_.cameras[static_cast<std::size_t>(model_.nodes[static_cast<std::size_t>(camera_node)].camera)];
            camera.yfov = static_cast<float>(source.perspective.yfov);
            camera.znear = static_cast<float>(source.perspective.znear);
            camera.view_open = view_from_node(global_open_[static_cast<std::size_t>(camera_node)], camera_node);
            camera.view_close = view_from_node(global_close_[static_cast<std::size_t>(camera_node)], camera_node);
            const float center_depth = -(camera.view_open * glm::vec4(center, 1.0f)).z;
            camera.focus_distance = std::max(center_depth, 10.0f * camera.znear);
        } else {
            // Automatic camera: looks at the bounds' centre from the front
            // (+z, glTF's "forward" for models), slightly from above and right,
            // far enough that the bounding sphere fits both fields of view.
            camera.yfov = 0.8f;
            const float half_fit = std::min(0.4f, std::atan(std::tan(0.4f) * options_.aspect));
            const float distance = radius / std::sin(half_fit) * 1.05f;
            const glm::vec3 eye = center + glm::normalize(glm::vec3(0.25f, 0.3f, 1.0f)) * distance;
            camera.view_open = glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f));
            camera.view_close = camera.view_open;
            camera.znear = std::max(0.5f * (distance - radius), 1e-3f * distance);
            camera.focus_distance = distance;
        }
        if (options_.focus_distance > 0.0f) camera.focus_distance = options_.focus_distance;
        camera.lens_radius = options_.lens_radius;
    }

    int find_camera_node(int camera) const {
        for (int node : rendered_nodes_) {
            if (model_.nodes[static_cast<std::size_t>(node)].camera == camera) return node;
        }
        return -1;
    }

    std::string path_;
    GltfOptions options_;
    tg::Model model_;
    std::vector<int> parent_;
    std::vector<std::size_t> depth_;
    std::vector<int> rendered_nodes_;
    std::map<std::pair<std::size_t, std::size_t>, Sampler> samplers_;
    std::map<int, std::uint32_t> material_map_;
    std::set<std::string> warned_;
    float t_open_ = 0.0f;
    float t_close_ = 0.0f;
    std::vector<glm::mat4> global_open_;
    std::vector<glm::mat4> global_close_;
};

}  // namespace

Scene load_gltf_scene(const std::string& path, const GltfOptions& options) {
    return GltfLoader(path, options).load();
}

Scene load_scene(const std::string& name_or_path, const GltfOptions& options) {
    if (has_extension(name_or_path, ".gltf") || has_extension(name_or_path, ".glb")) {
        return load_gltf_scene(name_or_path, options);
    }
    const std::size_t slash = name_or_path.find_last_of('/');
    const std::size_t dot = name_or_path.find_last_of('.');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
        throw SceneError(name_or_path + ": unsupported scene file type (expected .gltf or .glb)");
    }
    SceneOptions builtin;
    builtin.blur_scale = options.blur_scale;
    builtin.aspect = options.aspect;
    return make_builtin_scene(name_or_path, builtin);
}

}  // namespace blurcull::frontend
