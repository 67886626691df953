// Compressed glTF geometry (docs/scenes.md): KHR_draco_mesh_compression and
// EXT_meshopt_compression. Each test encodes one known mesh with the
// library itself (draco::Encoder, meshopt_encode*), writes it as a .gltf
// or .glb using the extension, loads it and compares it with the same mesh
// stored plainly: the loaded vertices and triangles, and the cpu and Embree
// renders. Broken compressed data is refused in one line naming the
// extension.
#include "frontend_test_helpers.hpp"
#include "render/cpu/cpu_backend.hpp"
#if BLURCULL_HAVE_EMBREE
#include "render/embree/embree_backend.hpp"
#endif
#include "scene/gltf/gltf_loader.hpp"
#include "scene/scene_error.hpp"

#include <doctest/doctest.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <glm/glm.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace blurcull::frontend;
using blurcull::frontend::test::quiet_settings;
using blurcull::frontend::test::same_pixels;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kComponentFloat = 5126;
constexpr int kComponentByte = 5120;
constexpr int kComponentUnsignedByte = 5121;
constexpr int kComponentUnsignedInt = 5125;

// A bumpy 5 x 5 grid: 25 vertices with positions, normals, texture
// coordinates and 8-bit colours, 32 triangles.
struct SourceMesh {
    std::vector<float> positions, normals, texcoords;  // 3, 3, 2 per vertex
    std::vector<std::uint8_t> colors;                  // RGBA, normalized
    std::vector<std::uint32_t> indices;
    std::size_t vertices() const { return positions.size() / 3; }
};

SourceMesh grid_mesh() {
    SourceMesh mesh;
    constexpr int n = 5;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const float x = -1.0f + 2.0f * float(i) / float(n - 1), y = -1.0f + 2.0f * float(j) / float(n - 1);
            const float z = 0.3f * std::sin(2.0f * x) * std::cos(2.0f * y);
            const glm::vec3 normal = glm::normalize(glm::vec3(-0.6f * std::cos(2.0f * x) * std::cos(2.0f * y),
                                                              0.6f * std::sin(2.0f * x) * std::sin(2.0f * y), 1.0f));
            mesh.positions.insert(mesh.positions.end(), {x, y, z});
            mesh.normals.insert(mesh.normals.end(), {normal.x, normal.y, normal.z});
            mesh.texcoords.insert(mesh.texcoords.end(), {float(i) / float(n - 1), float(j) / float(n - 1)});
            mesh.colors.insert(mesh.colors.end(), {std::uint8_t(60 * i), std::uint8_t(60 * j), 200, 255});
        }
    }
    for (std::uint32_t j = 0; j + 1 < n; ++j) {
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
            const std::uint32_t a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        }
    }
    // meshoptimizer's triangle codec keeps each triangle and its winding but
    // may rotate its corners: the source holds them in the rotation the
    // codec keeps, so every file stores the very same triangles.
    std::vector<unsigned char> encoded(meshopt_encodeIndexBufferBound(mesh.indices.size(), mesh.vertices()));
    encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), mesh.indices.data(), mesh.indices.size()));
    std::vector<std::uint32_t> kept(mesh.indices.size());
    REQUIRE(meshopt_decodeIndexBuffer(kept.data(), kept.size(), encoded.data(), encoded.size()) == 0);
    for (std::size_t t = 0; t < kept.size(); t += 3) {
        const std::uint32_t* a = &mesh.indices[t];
        const std::uint32_t* b = &kept[t];
        const bool rotation = (b[0] == a[0] && b[1] == a[1] && b[2] == a[2]) ||
                              (b[0] == a[1] && b[1] == a[2] && b[2] == a[0]) ||
                              (b[0] == a[2] && b[1] == a[0] && b[2] == a[1]);
        REQUIRE(rotation);
    }
    mesh.indices = kept;
    return mesh;
}

template <typename T>
std::size_t append(std::vector<unsigned char>& bin, const std::vector<T>& values) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const std::size_t offset = bin.size();
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    bin.insert(bin.end(), bytes, bytes + values.size() * sizeof(T));
    return offset;
}

// A glTF document and its first buffer's bytes (the .bin, or the GLB's BIN
// chunk); buffers[0] gets its uri (or none, for a GLB) when saved.
struct Gltf {
    json doc;
    std::vector<unsigned char> bin;
};

json accessor(int view, int component_type, const char* type, std::size_t count) {
    json a = {{"componentType", component_type}, {"type", type}, {"count", count}};
    if (view >= 0) a["bufferView"] = view;
    return a;
}

// The document around one primitive whose accessors 0..4 are POSITION,
// NORMAL, TEXCOORD_0, the indices and COLOR_0; `views` are the accessors'
// views (-1: none).
json document(const SourceMesh& mesh, const std::vector<int>& views) {
    json doc;
    doc["asset"] = {{"version", "2.0"}};
    doc["scene"] = 0;
    doc["scenes"] = json::array({{{"nodes", {0}}}});
    doc["nodes"] = json::array({{{"mesh", 0}}});
    json position = accessor(views[0], kComponentFloat, "VEC3", mesh.vertices());
    position["min"] = {-1.0, -1.0, -0.3};
    position["max"] = {1.0, 1.0, 0.3};
    doc["accessors"] = json::array({position, accessor(views[1], kComponentFloat, "VEC3", mesh.vertices()),
                                    accessor(views[2], kComponentFloat, "VEC2", mesh.vertices()),
                                    accessor(views[3], kComponentUnsignedInt, "SCALAR", mesh.indices.size())});
    json color = accessor(views[4], kComponentUnsignedByte, "VEC4", mesh.vertices());
    color["normalized"] = true;
    doc["accessors"].push_back(color);
    json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"COLOR_0", 4}}},
                      {"indices", 3}};
    doc["meshes"] = json::array({{{"primitives", json::array({primitive})}}});
    return doc;
}

void declare(json& doc, const std::string& extension, bool required) {
    doc["extensionsUsed"].push_back(extension);
    if (required) doc["extensionsRequired"].push_back(extension);
}

Gltf plain_gltf(const SourceMesh& mesh) {
    Gltf g;
    const std::size_t p = append(g.bin, mesh.positions), n = append(g.bin, mesh.normals),
                      t = append(g.bin, mesh.texcoords), i = append(g.bin, mesh.indices),
                      c = append(g.bin, mesh.colors);
    g.doc = document(mesh, {0, 1, 2, 3, 4});
    g.doc["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", p}, {"byteLength", mesh.positions.size() * 4}},
                                        {{"buffer", 0}, {"byteOffset", n}, {"byteLength", mesh.normals.size() * 4}},
                                        {{"buffer", 0}, {"byteOffset", t}, {"byteLength", mesh.texcoords.size() * 4}},
                                        {{"buffer", 0}, {"byteOffset", i}, {"byteLength", mesh.indices.size() * 4}},
                                        {{"buffer", 0}, {"byteOffset", c}, {"byteLength", mesh.colors.size()}}});
    g.doc["buffers"] = json::array({{{"byteLength", g.bin.size()}}});
    return g;
}

// --- EXT_meshopt_compression -------------------------------------------------

struct MeshoptOptions {
    bool required = true;
    std::string index_mode = "TRIANGLES";  // or INDICES
    bool octahedral_normals = false;       // normals as 8-bit octahedral (filter OCTAHEDRAL, stride 4)
};

// The compressed streams in buffer 0; buffer 1 the fallback without data.
Gltf meshopt_gltf(const SourceMesh& mesh, const MeshoptOptions& options) {
    Gltf g;
    json views = json::array();
    std::size_t fallback_offset = 0;
    const auto add_view = [&](const std::vector<unsigned char>& encoded, std::size_t count, std::size_t stride,
                              const std::string& mode, const std::string& filter, bool vertex) {
        const std::size_t offset = append(g.bin, encoded);
        json extension = {{"buffer", 0},         {"byteOffset", offset}, {"byteLength", encoded.size()},
                          {"byteStride", stride}, {"count", count},       {"mode", mode}};
        if (!filter.empty()) extension["filter"] = filter;
        json view = {{"buffer", 1}, {"byteOffset", fallback_offset}, {"byteLength", count * stride}};
        if (vertex) view["byteStride"] = stride;
        view["extensions"] = {{"EXT_meshopt_compression", extension}};
        views.push_back(view);
        fallback_offset += (count * stride + 3) / 4 * 4;
    };
    const auto encode_vertices = [&](const void* data, std::size_t count, std::size_t stride) {
        std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(count, stride));
        encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
        REQUIRE(!encoded.empty());
        return encoded;
    };
    const std::size_t count = mesh.vertices();
    add_view(encode_vertices(mesh.positions.data(), count, 12), count, 12, "ATTRIBUTES", "", true);
    if (options.octahedral_normals) {
        std::vector<float> xyzw;
        for (std::size_t v = 0; v < count; ++v) {
            xyzw.insert(xyzw.end(), {mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2], 0.0f});
        }
        std::vector<unsigned char> filtered(count * 4);
        meshopt_encodeFilterOct(filtered.data(), count, 4, 8, xyzw.data());
        add_view(encode_vertices(filtered.data(), count, 4), count, 4, "ATTRIBUTES", "OCTAHEDRAL", true);
    } else {
        add_view(encode_vertices(mesh.normals.data(), count, 12), count, 12, "ATTRIBUTES", "", true);
    }
    add_view(encode_vertices(mesh.texcoords.data(), count, 8), count, 8, "ATTRIBUTES", "", true);
    const std::size_t index_count = mesh.indices.size();
    std::vector<unsigned char> indices;
    if (options.index_mode == "TRIANGLES") {
        indices.resize(meshopt_encodeIndexBufferBound(index_count, count));
        indices.resize(meshopt_encodeIndexBuffer(indices.data(), indices.size(), mesh.indices.data(), index_count));
    } else {
        indices.resize(meshopt_encodeIndexSequenceBound(index_count, count));
        indices.resize(meshopt_encodeIndexSequence(indices.data(), indices.size(), mesh.indices.data(), index_count));
    }
    REQUIRE(!indices.empty());
    add_view(indices, index_count, 4, options.index_mode, "", false);
    add_view(encode_vertices(mesh.colors.data(), count, 4), count, 4, "ATTRIBUTES", "", true);

    g.doc = document(mesh, {0, 1, 2, 3, 4});
    if (options.octahedral_normals) {
        g.doc["accessors"][1]["componentType"] = kComponentByte;
        g.doc["accessors"][1]["normalized"] = true;
        declare(g.doc, "KHR_mesh_quantization", true);
    }
    g.doc["bufferViews"] = views;
    g.doc["buffers"] = json::array(
        {{{"byteLength", g.bin.size()}},
         {{"byteLength", fallback_offset}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    declare(g.doc, "EXT_meshopt_compression", options.required);
    return g;
}

// --- KHR_draco_mesh_compression ----------------------------------------------

struct DracoOptions {
    bool required = true;
    // Sequential and lossless (points and triangles keep their order), or
    // edgebreaker with 14-bit positions, 10-bit normals, 12-bit texcoords.
    bool quantized = false;
    // With extensionsUsed only: plain fallback accessors, moved 10 units so
    // that reading them instead of the Draco mesh shows.
    bool fallback = false;
};

struct DracoStream {
    std::vector<unsigned char> bytes;
    int position_id = 0, normal_id = 0, texcoord_id = 0, color_id = 0;
};

DracoStream draco_encode(const SourceMesh& mesh, bool quantized) {
    draco::Mesh dm;
    const auto count = static_cast<std::uint32_t>(mesh.vertices());
    dm.set_num_points(count);
    const auto add = [&](draco::GeometryAttribute::Type type, const std::vector<float>& values, int components) {
        draco::GeometryAttribute attribute;
        attribute.Init(type, nullptr, static_cast<std::uint8_t>(components), draco::DT_FLOAT32, false,
                       static_cast<std::int64_t>(sizeof(float)) * components, 0);
        const int id = dm.AddAttribute(attribute, true, count);
        for (std::uint32_t v = 0; v < count; ++v) {
            dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v), &values[v * std::size_t(components)]);
        }
        return static_cast<int>(dm.attribute(id)->unique_id());
    };
    DracoStream stream;
    stream.position_id = add(draco::GeometryAttribute::POSITION, mesh.positions, 3);
    stream.normal_id = add(draco::GeometryAttribute::NORMAL, mesh.normals, 3);
    stream.texcoord_id = add(draco::GeometryAttribute::TEX_COORD, mesh.texcoords, 2);
    {
        draco::GeometryAttribute attribute;
        attribute.Init(draco::GeometryAttribute::COLOR, nullptr, 4, draco::DT_UINT8, true, 4, 0);
        const int id = dm.AddAttribute(attribute, true, count);
        for (std::uint32_t v = 0; v < count; ++v) {
            dm.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v), &mesh.colors[v * 4u]);
        }
        stream.color_id = static_cast<int>(dm.attribute(id)->unique_id());
    }
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        dm.AddFace({draco::PointIndex(mesh.indices[t]), draco::PointIndex(mesh.indices[t + 1]),
                    draco::PointIndex(mesh.indices[t + 2])});
    }
    draco::Encoder encoder;
    if (quantized) {
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
        encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    } else {
        encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    }
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(dm, &buffer);
    REQUIRE_MESSAGE(status.ok(), status.error_msg_string());
    stream.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    return stream;
}

Gltf draco_gltf(const SourceMesh& mesh, const DracoOptions& options) {
    const DracoStream stream = draco_encode(mesh, options.quantized);
    Gltf g;
    append(g.bin, stream.bytes);
    json views = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", stream.bytes.size()}}});
    std::vector<int> accessor_views = {-1, -1, -1, -1, -1};
    if (options.fallback) {
        std::vector<float> moved = mesh.positions;
        for (float& x : moved) x += 10.0f;
        const std::size_t p = append(g.bin, moved), n = append(g.bin, mesh.normals),
                          t = append(g.bin, mesh.texcoords), i = append(g.bin, mesh.indices),
                          c = append(g.bin, mesh.colors);
        for (const auto& [offset, length] : std::vector<std::pair<std::size_t, std::size_t>>{
                 {p, moved.size() * 4}, {n, mesh.normals.size() * 4}, {t, mesh.texcoords.size() * 4},
                 {i, mesh.indices.size() * 4}, {c, mesh.colors.size()}}) {
            views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
        }
        accessor_views = {1, 2, 3, 4, 5};
    }
    g.doc = document(mesh, accessor_views);
    g.doc["meshes"][0]["primitives"][0]["extensions"] = {
        {"KHR_draco_mesh_compression",
         {{"bufferView", 0},
          {"attributes",
           {{"POSITION", stream.position_id},
            {"NORMAL", stream.normal_id},
            {"TEXCOORD_0", stream.texcoord_id},
            {"COLOR_0", stream.color_id}}}}}};
    g.doc["bufferViews"] = views;
    g.doc["buffers"] = json::array({{{"byteLength", g.bin.size()}}});
    declare(g.doc, "KHR_draco_mesh_compression", options.required);
    return g;
}

// --- files -------------------------------------------------------------------

fs::path scratch_folder() {
    static const fs::path folder = [] {
        const fs::path f = fs::temp_directory_path() / ("blurcull_gltf_compression_" + std::to_string(::getpid()));
        fs::create_directories(f);
        return f;
    }();
    return folder;
}

void write_file(const fs::path& path, const std::vector<unsigned char>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    REQUIRE(out.good());
}

void append_u32(std::vector<unsigned char>& bytes, std::uint32_t v) {
    unsigned char raw[4];
    std::memcpy(raw, &v, 4);
    bytes.insert(bytes.end(), raw, raw + 4);
}

std::vector<unsigned char> glb_bytes(Gltf g) {
    std::string text = g.doc.dump();
    while (text.size() % 4 != 0) text += ' ';
    while (g.bin.size() % 4 != 0) g.bin.push_back(0);
    std::vector<unsigned char> out = {'g', 'l', 'T', 'F'};
    append_u32(out, 2);
    append_u32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + g.bin.size()));
    append_u32(out, static_cast<std::uint32_t>(text.size()));
    append_u32(out, 0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    append_u32(out, static_cast<std::uint32_t>(g.bin.size()));
    append_u32(out, 0x004E4942u);
    out.insert(out.end(), g.bin.begin(), g.bin.end());
    return out;
}

// Writes `name`.gltf (+ .bin) or `name`.glb in the scratch folder; its path.
std::string save(const std::string& name, Gltf g, bool glb = false) {
    const fs::path folder = scratch_folder();
    if (glb) {
        const fs::path path = folder / (name + ".glb");
        write_file(path, glb_bytes(std::move(g)));
        return path.string();
    }
    g.doc["buffers"][0]["uri"] = name + ".bin";
    write_file(folder / (name + ".bin"), g.bin);
    const std::string text = g.doc.dump(1);
    write_file(folder / (name + ".gltf"), std::vector<unsigned char>(text.begin(), text.end()));
    return (folder / (name + ".gltf")).string();
}

Scene load(const std::string& path) { return load_gltf_scene(path, GltfOptions{}); }

// The SceneError message of loading `path` ("" when it loads).
std::string error_of(const std::string& path) {
    try {
        load(path);
    } catch (const SceneError& error) {
        return error.what();
    } catch (const std::exception& error) {
        FAIL("not a SceneError: " << error.what());
    }
    return "";
}

void check_refused(const std::string& path, const std::string& extension) {
    const std::string message = error_of(path);
    INFO(message);
    CHECK(message.rfind(path + ": ", 0) == 0);
    CHECK(message.find(extension) != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
}

// Both renderers draw `a` and `b` alike: the same pixels, or (tolerant)
// every channel within 1/255 at `min_close` of the pixels.
void check_same_renders(const Scene& a, const Scene& b, bool tolerant = false, double min_close = 1.0) {
    const RenderSettings settings = quiet_settings(32, 24, 4);
    const Image cpu_a = render_cpu(a, settings).image, cpu_b = render_cpu(b, settings).image;
    if (tolerant) {
        CHECK(blurcull::frontend::test::fraction_close(cpu_a, cpu_b) >= min_close);
    } else {
        CHECK(same_pixels(cpu_a, cpu_b));
    }
#if BLURCULL_HAVE_EMBREE
    const Image embree_a = render_embree(a, settings).image, embree_b = render_embree(b, settings).image;
    if (tolerant) {
        CHECK(blurcull::frontend::test::fraction_close(embree_a, embree_b) >= min_close);
    } else {
        CHECK(same_pixels(embree_a, embree_b));
    }
#endif
}

void check_same_geometry(const Scene& plain, const Scene& loaded) {
    CHECK(loaded.position_open == plain.position_open);
    CHECK(loaded.triangles == plain.triangles);
    CHECK(loaded.normal == plain.normal);
    CHECK(loaded.texcoord == plain.texcoord);
    CHECK(loaded.vertex_color == plain.vertex_color);
}

float max_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    REQUIRE(a.size() == b.size());
    float d = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
    return d;
}

// Overwrites `length` bytes of g.bin from `offset` with a fixed pattern.
void garble(Gltf& g, std::size_t offset, std::size_t length) {
    for (std::size_t k = 0; k < length && offset + k < g.bin.size(); ++k) {
        g.bin[offset + k] = static_cast<unsigned char>(0xA5 ^ (k * 37));
    }
}

}  // namespace

TEST_CASE("EXT_meshopt_compression: lossless streams load and render as the plain file does") {
    const SourceMesh mesh = grid_mesh();
    const Scene plain = load(save("plain", plain_gltf(mesh)));
    REQUIRE(plain.triangles.size() == 32);
    REQUIRE(plain.position_open.size() == 25);
    REQUIRE(plain.vertex_color.size() == 25);
    REQUIRE(plain.texcoord.size() == 25);
    REQUIRE(plain.normal.size() == 25);
    for (bool required : {true, false}) {
        for (const char* mode : {"TRIANGLES", "INDICES"}) {
            for (bool glb : {false, true}) {
                CAPTURE(required);
                CAPTURE(mode);
                CAPTURE(glb);
                MeshoptOptions options;
                options.required = required;
                options.index_mode = mode;
                const Gltf g = meshopt_gltf(mesh, options);
                const Scene loaded =
                    load(save(std::string("meshopt_") + mode + (required ? "_required" : "_used"), g, glb));
                check_same_geometry(plain, loaded);
                if (required && glb) check_same_renders(plain, loaded);
            }
        }
    }
}

TEST_CASE("EXT_meshopt_compression: the OCTAHEDRAL filter decodes 8-bit normals") {
    const SourceMesh mesh = grid_mesh();
    const Scene plain = load(save("plain", plain_gltf(mesh)));
    MeshoptOptions options;
    options.octahedral_normals = true;
    const Scene loaded = load(save("meshopt_octahedral", meshopt_gltf(mesh, options)));
    CHECK(loaded.position_open == plain.position_open);
    CHECK(loaded.triangles == plain.triangles);
    REQUIRE(loaded.normal.size() == plain.normal.size());
    // 8-bit octahedral: within a few hundredths of the unit normal.
    CHECK(max_distance(loaded.normal, plain.normal) < 0.03f);
    CHECK(max_distance(loaded.normal, plain.normal) > 0.0f);
}

TEST_CASE("EXT_meshopt_compression: broken streams are refused in one line") {
    const SourceMesh mesh = grid_mesh();
    const Gltf good = meshopt_gltf(mesh, MeshoptOptions{});
    const json& positions = good.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    const json& indices = good.doc["bufferViews"][3]["extensions"]["EXT_meshopt_compression"];
    const std::string extension = "EXT_meshopt_compression";

    Gltf truncated = good;  // the positions' stream cut in half
    truncated.doc["bufferViews"][0]["extensions"][extension]["byteLength"] = positions["byteLength"].get<int>() / 2;
    check_refused(save("meshopt_truncated", truncated), extension);
    check_refused(save("meshopt_truncated", truncated, true), extension);

    Gltf garbage = good;  // the positions' and indices' bytes replaced
    garble(garbage, positions["byteOffset"].get<std::size_t>(), positions["byteLength"].get<std::size_t>());
    check_refused(save("meshopt_garbage_vertices", garbage), extension);
    garbage = good;
    garble(garbage, indices["byteOffset"].get<std::size_t>(), indices["byteLength"].get<std::size_t>());
    check_refused(save("meshopt_garbage_indices", garbage), extension);

    Gltf huge = good;  // four billion vertices claimed from a few hundred bytes: refused before allocating
    huge.doc["bufferViews"][0]["extensions"][extension]["count"] = 4000000000u / 12 * 12 / 12;
    huge.doc["bufferViews"][0]["byteLength"] = 4000000000u / 12 * 12;
    check_refused(save("meshopt_huge", huge), extension);

    Gltf bad_stride = good;
    bad_stride.doc["bufferViews"][0]["extensions"][extension]["byteStride"] = 6;
    check_refused(save("meshopt_stride", bad_stride), extension);

    Gltf bad_filter = good;
    bad_filter.doc["bufferViews"][0]["extensions"][extension]["filter"] = "QUATERNION";
    check_refused(save("meshopt_filter", bad_filter), extension);

    Gltf outside = good;  // the stream runs past its buffer
    outside.doc["bufferViews"][0]["extensions"][extension]["byteOffset"] = good.bin.size();
    check_refused(save("meshopt_outside", outside), extension);

    Gltf plain_in_fallback = good;  // a view without the extension into the data-less fallback
    plain_in_fallback.doc["bufferViews"][0].erase("extensions");
    check_refused(save("meshopt_plain_in_fallback", plain_in_fallback), extension);
}

TEST_CASE("KHR_draco_mesh_compression: a lossless sequential mesh loads and renders as the plain file does") {
    const SourceMesh mesh = grid_mesh();
    const Scene plain = load(save("plain", plain_gltf(mesh)));
    for (bool required : {true, false}) {
        for (bool glb : {false, true}) {
            CAPTURE(required);
            CAPTURE(glb);
            DracoOptions options;
            options.required = required;
            options.fallback = !required;
            const Scene loaded =
                load(save(std::string("draco_sequential_") + (required ? "required" : "used"), draco_gltf(mesh, options),
                          glb));
            check_same_geometry(plain, loaded);
            if (glb) check_same_renders(plain, loaded);
        }
    }
}

TEST_CASE("KHR_draco_mesh_compression: a quantized edgebreaker mesh matches within its quantization") {
    const SourceMesh mesh = grid_mesh();
    const Scene plain = load(save("plain", plain_gltf(mesh)));
    DracoOptions options;
    options.quantized = true;
    const Gltf g = draco_gltf(mesh, options);
    const Scene loaded = load(save("draco_edgebreaker", g));
    REQUIRE(loaded.triangles.size() == plain.triangles.size());
    REQUIRE(loaded.position_open.size() == plain.position_open.size());
    // Edgebreaker reorders points and triangles: each source triangle's
    // corners are found in some loaded triangle within the 14-bit step
    // (the grid spans 2 units: 2 / 2^14 per step, half a step of error).
    const float step = 2.0f / 16384.0f;
    std::size_t matched = 0;
    for (const glm::uvec3& t : plain.triangles) {
        for (const glm::uvec3& u : loaded.triangles) {
            bool same = true;
            for (int k = 0; k < 3 && same; ++k) {
                bool found = false;
                for (int l = 0; l < 3; ++l) {
                    found = found || glm::length(plain.position_open[t[k]] - loaded.position_open[u[l]]) <= step;
                }
                same = found;
            }
            if (same) {
                ++matched;
                break;
            }
        }
    }
    CHECK(matched == plain.triangles.size());
    check_same_renders(plain, loaded, true, 0.97);
}

TEST_CASE("KHR_draco_mesh_compression: broken meshes are refused in one line") {
    const SourceMesh mesh = grid_mesh();
    const Gltf good = draco_gltf(mesh, DracoOptions{});
    const std::size_t length = good.doc["bufferViews"][0]["byteLength"].get<std::size_t>();
    const std::string extension = "KHR_draco_mesh_compression";
    for (bool quantized : {false, true}) {
        CAPTURE(quantized);
        DracoOptions options;
        options.quantized = quantized;
        const Gltf source = draco_gltf(mesh, options);
        const std::size_t size = source.doc["bufferViews"][0]["byteLength"].get<std::size_t>();
        for (std::size_t cut : {std::size_t{0}, std::size_t{4}, std::size_t{12}, size / 3, size / 2, size - 8}) {
            CAPTURE(cut);
            Gltf truncated = source;
            truncated.doc["bufferViews"][0]["byteLength"] = cut;
            check_refused(save("draco_truncated", truncated), extension);
        }
        for (std::size_t from : {std::size_t{0}, std::size_t{11}, size / 4, size / 2}) {
            CAPTURE(from);
            Gltf garbage = source;
            garble(garbage, from, size - from);
            const std::string path = save("draco_garbage", garbage);
            const std::string message = error_of(path);
            INFO(message);
            // Garbage in the header or connectivity is refused by Draco;
            // garbage in raw float values may decode to some mesh, which
            // then loads or is refused for its values: in one line either way.
            if (from < size / 4) CHECK(message.find(extension) != std::string::npos);
            if (!message.empty()) {
                CHECK(message.rfind(path + ": ", 0) == 0);
                CHECK(message.find('\n') == std::string::npos);
            }
        }
    }

    Gltf missing_id = good;
    missing_id.doc["meshes"][0]["primitives"][0]["extensions"][extension]["attributes"]["NORMAL"] = 77;
    check_refused(save("draco_missing_id", missing_id), extension);

    Gltf wrong_count = good;
    wrong_count.doc["accessors"][0]["count"] = 24;
    check_refused(save("draco_wrong_count", wrong_count), extension);

    Gltf huge_count = good;  // refused before decoding
    huge_count.doc["accessors"][3]["count"] = 3000000000u;
    check_refused(save("draco_huge_count", huge_count), extension);

    Gltf no_view = good;
    no_view.doc["meshes"][0]["primitives"][0]["extensions"][extension]["bufferView"] = 9;
    check_refused(save("draco_no_view", no_view), extension);
    CHECK(length > 0);
}

TEST_CASE("compressed geometry: the fuzz seeds load as the plain mesh") {
    const SourceMesh mesh = grid_mesh();
    const Scene plain = load(save("plain", plain_gltf(mesh)));
    const std::string corpus = std::string(BLURCULL_SOURCE_DIR) + "/fuzz/corpus/gltf/";
    // BLURCULL_WRITE_COMPRESSION_SEEDS=1 rewrites them (from this file's encoders).
    const char* write = std::getenv("BLURCULL_WRITE_COMPRESSION_SEEDS");
    if (write != nullptr && std::string(write) == "1") {
        write_file(corpus + "meshopt_compression.glb", glb_bytes(meshopt_gltf(mesh, MeshoptOptions{})));
        write_file(corpus + "draco_compression.glb", glb_bytes(draco_gltf(mesh, DracoOptions{})));
        DracoOptions edgebreaker;
        edgebreaker.quantized = true;
        write_file(corpus + "draco_edgebreaker.glb", glb_bytes(draco_gltf(mesh, edgebreaker)));
    }
    check_same_geometry(plain, load(corpus + "meshopt_compression.glb"));
    check_same_geometry(plain, load(corpus + "draco_compression.glb"));
    CHECK(load(corpus + "draco_edgebreaker.glb").triangles.size() == plain.triangles.size());
}

TEST_CASE("compressed geometry: every second byte of the streams replaced, and cuts, never crash") {
    // Beside the fuzzer (which sees nothing inside libdraco or meshoptimizer,
    // not instrumented): deterministic corruption of the three seed kinds,
    // run by CI under the sanitizers too. Each variant loads or is refused
    // in one line naming the file.
    const SourceMesh mesh = grid_mesh();
    DracoOptions edgebreaker;
    edgebreaker.quantized = true;
    const std::vector<std::pair<std::string, Gltf>> sources = {
        {"meshopt", meshopt_gltf(mesh, MeshoptOptions{})},
        {"draco", draco_gltf(mesh, DracoOptions{})},
        {"draco_edgebreaker", draco_gltf(mesh, edgebreaker)}};
    std::size_t loads = 0, refusals = 0;
    const auto attempt = [&](const std::string& name, const Gltf& g) {
        const std::string path = save("corrupt_" + name, g, true);
        const std::string message = error_of(path);
        if (message.empty()) {
            ++loads;
            return;
        }
        ++refusals;
        if (message.rfind(path + ": ", 0) != 0 || message.find('\n') != std::string::npos) FAIL(message);
    };
    for (const auto& [name, source] : sources) {
        CAPTURE(name);
        for (std::size_t at = 0; at < source.bin.size(); at += 2) {
            for (int kind = 0; kind < 3; ++kind) {
                Gltf g = source;
                const unsigned char original = g.bin[at];
                g.bin[at] = kind == 0 ? 0x00 : kind == 1 ? 0xFF : static_cast<unsigned char>(original ^ 0x5A);
                if (g.bin[at] != original) attempt(name, g);
            }
        }
        // Cuts: the Draco view, or each meshopt stream, shortened.
        const std::size_t views = source.doc["bufferViews"].size();
        for (std::size_t v = 0; v < views; ++v) {
            const json& view = source.doc["bufferViews"][v];
            const bool meshopt = view.contains("extensions");
            const std::size_t length = (meshopt ? view["extensions"]["EXT_meshopt_compression"]["byteLength"]
                                                : view["byteLength"])
                                           .get<std::size_t>();
            for (std::size_t cut = 0; cut < length; cut += 5) {
                Gltf g = source;
                if (meshopt) {
                    g.doc["bufferViews"][v]["extensions"]["EXT_meshopt_compression"]["byteLength"] = cut;
                } else {
                    g.doc["bufferViews"][v]["byteLength"] = cut;
                }
                attempt(name, g);
            }
        }
    }
    MESSAGE(loads << " corrupted files loaded, " << refusals << " refused in one line");
    CHECK(refusals > 1000);
}

TEST_CASE("GLB: a BIN chunk 8 bytes too long for the file is refused, not read past the end") {
    // tinygltf 2.7 checks the BIN chunk's length without its 8-byte header;
    // found by fuzz_gltf once the meshopt rewrite rebuilt GLBs to their
    // declared length (parse.cpp's check_glb_header now checks it).
    for (bool meshopt : {false, true}) {
        CAPTURE(meshopt);
        const SourceMesh mesh = grid_mesh();
        std::vector<unsigned char> bytes = glb_bytes(meshopt ? meshopt_gltf(mesh, MeshoptOptions{}) : plain_gltf(mesh));
        std::uint32_t json_length = 0, bin_length = 0;
        std::memcpy(&json_length, bytes.data() + 12, 4);
        std::memcpy(&bin_length, bytes.data() + 20 + json_length, 4);
        bin_length += 8;
        std::memcpy(bytes.data() + 20 + json_length, &bin_length, 4);
        const fs::path path = scratch_folder() / "bin_chunk_too_long.glb";
        write_file(path, bytes);
        const std::string message = error_of(path.string());
        CHECK(message == path.string() + ": GLB BIN chunk runs past the end of the file");
    }
}

TEST_CASE("compressed geometry: many views or primitives sharing one stream are held to a total") {
    // One stream decoded over and over is bounded by the file's buffers:
    // 128x (meshopt) and 256x plus 1 MiB (Draco), not per view only.
    const SourceMesh mesh = grid_mesh();
    Gltf meshopt = meshopt_gltf(mesh, MeshoptOptions{});
    const json view = meshopt.doc["bufferViews"][0];
    for (int k = 0; k < 1000; ++k) meshopt.doc["bufferViews"].push_back(view);
    const std::string meshopt_path = save("meshopt_shared", meshopt, true);
    const std::string meshopt_message = error_of(meshopt_path);
    CHECK(meshopt_message.find("EXT_meshopt_compression views decode to more than") != std::string::npos);

    Gltf draco = draco_gltf(mesh, DracoOptions{});
    const json primitive = draco.doc["meshes"][0]["primitives"][0];
    for (int k = 0; k < 2000; ++k) draco.doc["meshes"][0]["primitives"].push_back(primitive);
    const std::string draco_path = save("draco_shared", draco, true);
    const std::string draco_message = error_of(draco_path);
    CHECK(draco_message.find("KHR_draco_mesh_compression meshes decode to more than") != std::string::npos);

    // A few sharing one stream still load.
    Gltf few = draco_gltf(mesh, DracoOptions{});
    for (int k = 0; k < 3; ++k) few.doc["meshes"][0]["primitives"].push_back(primitive);
    CHECK(load(save("draco_shared_few", few, true)).triangles.size() == 4 * mesh.indices.size() / 3);
}
