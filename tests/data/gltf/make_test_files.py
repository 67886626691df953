#!/usr/bin/env python3
"""Writes the small glTF files that tests/test_frontend_scenes.cpp loads.

Each malformed file breaks exactly one rule, so each test can check that the
loader's one-line error names that problem. Run from this folder:
    python3 make_test_files.py
"""
import base64
import copy
import json
import math
import struct

POSITIONS = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]


def data_uri(payload):
    return "data:application/octet-stream;base64," + base64.b64encode(payload).decode("ascii")


def floats(values):
    return struct.pack("<%df" % len(values), *values)


def triangle_model(indices=(0, 1, 2), positions=POSITIONS):
    """One indexed triangle: buffer = positions (float VEC3) then uint16 indices."""
    position_bytes = floats([c for p in positions for c in p])
    index_bytes = struct.pack("<%dH" % len(indices), *indices)
    index_bytes += b"\0" * (-len(index_bytes) % 4)
    payload = position_bytes + index_bytes
    return {
        "asset": {"version": "2.0", "generator": "blurcull make_test_files.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.4, 0.8, 1.0]}}],
        "buffers": [{"byteLength": len(payload), "uri": data_uri(payload)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(position_bytes)},
            {"buffer": 0, "byteOffset": len(position_bytes), "byteLength": 2 * len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }


def add_animation(model, times, translations):
    """Appends a translation animation of node 0 with the given keyframes."""
    payload = floats(times) + floats([c for t in translations for c in t])
    buffer_index = len(model["buffers"])
    model["buffers"].append({"byteLength": len(payload), "uri": data_uri(payload)})
    view = len(model["bufferViews"])
    model["bufferViews"] += [
        {"buffer": buffer_index, "byteOffset": 0, "byteLength": 4 * len(times)},
        {"buffer": buffer_index, "byteOffset": 4 * len(times), "byteLength": 12 * len(translations)},
    ]
    accessor = len(model["accessors"])
    model["accessors"] += [
        {"bufferView": view, "componentType": 5126, "count": len(times), "type": "SCALAR"},
        {"bufferView": view + 1, "componentType": 5126, "count": len(translations), "type": "VEC3"},
    ]
    model["animations"] = [{
        "samplers": [{"input": accessor, "output": accessor + 1, "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
    }]
    return model


def add_camera(model, yfov, znear=0.1):
    model["cameras"] = [{"type": "perspective", "perspective": {"yfov": yfov, "znear": znear}}]
    model["nodes"].append({"camera": 0, "translation": [0.3, 0.3, 3.0]})
    model["scenes"][0]["nodes"].append(len(model["nodes"]) - 1)
    return model


def write(name, model):
    with open(name, "w", encoding="ascii") as out:
        json.dump(model, out, indent=1, allow_nan=True)
        out.write("\n")


def glb(model):
    text = json.dumps(model).encode("ascii")
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def add_accessor(model, payload, component_type, count, type_, normalized=False, stride=None):
    """Appends a buffer holding `payload`, a view over it and an accessor; returns its index."""
    buffer_index = len(model["buffers"])
    model["buffers"].append({"byteLength": len(payload), "uri": data_uri(payload)})
    view = {"buffer": buffer_index, "byteOffset": 0, "byteLength": len(payload)}
    if stride is not None:
        view["byteStride"] = stride
    model["bufferViews"].append(view)
    accessor = {"bufferView": len(model["bufferViews"]) - 1, "componentType": component_type, "count": count,
                "type": type_}
    if normalized:
        accessor["normalized"] = True
    model["accessors"].append(accessor)
    return len(model["accessors"]) - 1


def add_sparse_accessor(model, count, indices, values):
    """A float VEC3 accessor without a buffer view (zeros) whose elements at
    `indices` (uint16) are `values`; returns its index."""
    index_bytes = struct.pack("<%dH" % len(indices), *indices)
    index_bytes += b"\0" * (-len(index_bytes) % 4)
    payload = index_bytes + floats([c for v in values for c in v])
    buffer_index = len(model["buffers"])
    model["buffers"].append({"byteLength": len(payload), "uri": data_uri(payload)})
    first_view = len(model["bufferViews"])
    model["bufferViews"] += [
        {"buffer": buffer_index, "byteOffset": 0, "byteLength": 2 * len(indices)},
        {"buffer": buffer_index, "byteOffset": len(index_bytes), "byteLength": 12 * len(values)},
    ]
    model["accessors"].append({
        "componentType": 5126, "count": count, "type": "VEC3",
        "sparse": {"count": len(indices),
                   "indices": {"bufferView": first_view, "componentType": 5123},
                   "values": {"bufferView": first_view + 1}}})
    return len(model["accessors"]) - 1


def add_weights_animation(model, node, times, weights, interpolation="LINEAR"):
    """Appends an animation of node `node`'s morph weights (one list per key)."""
    times_accessor = add_accessor(model, floats(times), 5126, len(times), "SCALAR")
    flat = [w for key in weights for w in key]
    values_accessor = add_accessor(model, floats(flat), 5126, len(flat), "SCALAR")
    model.setdefault("animations", []).append({
        "samplers": [{"input": times_accessor, "output": values_accessor, "interpolation": interpolation}],
        "channels": [{"sampler": 0, "target": {"node": node, "path": "weights"}}],
    })
    return model


# Morph targets of the triangle (tests/test_frontend_gltf_corpus.cpp repeats
# these numbers to compute the expected positions on its own).
MORPH_DENSE = [(0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (0.0, 0.0, 1.0)]
MORPH_SPARSE_INDEX = 1
MORPH_SPARSE = (0.0, 2.0, 0.0)


def morph_model():
    """The triangle with two morph targets: a dense float one (all +z) and a
    sparse one (no buffer view; vertex 1 moves +2 y); mesh weights 0.5, 0."""
    model = triangle_model()
    dense = add_accessor(model, floats([c for p in MORPH_DENSE for c in p]), 5126, 3, "VEC3")
    sparse = add_sparse_accessor(model, 3, [MORPH_SPARSE_INDEX], [MORPH_SPARSE])
    model["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": dense}, {"POSITION": sparse}]
    model["meshes"][0]["weights"] = [0.5, 0.0]
    return model


def quantized_model():
    """KHR_mesh_quantization: the triangle four times, positions stored as
    SHORT (unnormalized, node scale 1/1000 dequantises), normalized BYTE,
    normalized UNSIGNED_SHORT and UNSIGNED_BYTE (unnormalized, translated);
    the SHORT primitive has a normalized SHORT morph target."""
    model = triangle_model()
    model["extensionsUsed"] = ["KHR_mesh_quantization"]
    model["extensionsRequired"] = ["KHR_mesh_quantization"]
    # Vertex attributes are aligned to 4 bytes: 3 shorts padded to 8, 3 bytes to 4.
    shorts = b"".join(struct.pack("<3hxx", *v) for v in [(0, 0, 0), (1000, 0, 0), (0, 1000, 0)])
    bytes_ = b"".join(struct.pack("<3bx", *v) for v in [(0, 0, 0), (127, 0, 0), (0, -127, 0)])
    ushorts = b"".join(struct.pack("<3Hxx", *v) for v in [(0, 0, 0), (65535, 0, 0), (0, 65535, 0)])
    ubytes = b"".join(struct.pack("<3Bx", *v) for v in [(0, 0, 0), (2, 0, 0), (0, 2, 0)])
    target = b"".join(struct.pack("<3hxx", *v) for v in [(0, 0, 32767), (0, 0, 32767), (0, 0, 32767)])
    position_short = add_accessor(model, shorts, 5122, 3, "VEC3", stride=8)
    position_byte = add_accessor(model, bytes_, 5120, 3, "VEC3", normalized=True, stride=4)
    position_ushort = add_accessor(model, ushorts, 5123, 3, "VEC3", normalized=True, stride=8)
    position_ubyte = add_accessor(model, ubytes, 5121, 3, "VEC3", stride=4)
    morph_target = add_accessor(model, target, 5122, 3, "VEC3", normalized=True, stride=8)
    model["meshes"] = [
        {"primitives": [{"attributes": {"POSITION": position_short}, "targets": [{"POSITION": morph_target}]}],
         "weights": [0.5]},
        {"primitives": [{"attributes": {"POSITION": position_byte}}]},
        {"primitives": [{"attributes": {"POSITION": position_ushort}}]},
        {"primitives": [{"attributes": {"POSITION": position_ubyte}}]},
    ]
    model["nodes"] = [
        {"mesh": 0, "scale": [0.001, 0.001, 0.001]},
        {"mesh": 1, "translation": [2.0, 0.0, 0.0]},
        {"mesh": 2, "translation": [4.0, 0.0, 0.0]},
        {"mesh": 3, "translation": [6.0, 0.0, 0.0], "scale": [0.5, 0.5, 0.5]},
    ]
    model["scenes"][0]["nodes"] = [0, 1, 2, 3]
    return model


def morph_skinned_model():
    """A morph target (+1 x), skinned to one joint that the animation turns
    90 degrees about z and moves +1 y over 1 s; glTF's order (morph, then
    skin, then node) turns the morph offset into +y."""
    model = triangle_model()
    target = add_accessor(model, floats([1.0, 0.0, 0.0] * 3), 5126, 3, "VEC3")
    joints = add_accessor(model, struct.pack("<12B", *([0, 0, 0, 0] * 3)), 5121, 3, "VEC4")
    weights = add_accessor(model, floats([1.0, 0.0, 0.0, 0.0] * 3), 5126, 3, "VEC4")
    primitive = model["meshes"][0]["primitives"][0]
    primitive["attributes"].update({"JOINTS_0": joints, "WEIGHTS_0": weights})
    primitive["targets"] = [{"POSITION": target}]
    model["meshes"][0]["weights"] = [1.0]
    # The skinned node's own transform is ignored (glTF); the joint is node 1.
    model["nodes"] = [{"mesh": 0, "skin": 0, "translation": [50.0, 0.0, 0.0]}, {}]
    model["scenes"][0]["nodes"] = [0, 1]
    model["skins"] = [{"joints": [1]}]
    times = add_accessor(model, floats([0.0, 1.0]), 5126, 2, "SCALAR")
    half = math.sqrt(0.5)
    rotations = add_accessor(model, floats([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, half, half]), 5126, 2, "VEC4")
    translations = add_accessor(model, floats([0.0, 0.0, 0.0, 0.0, 1.0, 0.0]), 5126, 2, "VEC3")
    model["animations"] = [{
        "samplers": [{"input": times, "output": rotations}, {"input": times, "output": translations}],
        "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                     {"sampler": 1, "target": {"node": 1, "path": "translation"}}],
    }]
    return model


def conformance_files():
    """issue 14 item 6: versions, required extensions, quantization, images."""
    # A glTF 1.0 file (objects keyed by id instead of arrays).
    gltf1 = {
        "asset": {"version": "1.0"},
        "scene": "defaultScene",
        "scenes": {"defaultScene": {"nodes": ["node0"]}},
        "nodes": {"node0": {"meshes": ["mesh0"]}},
        "meshes": {"mesh0": {"primitives": [{"attributes": {"POSITION": "accessor0"}, "mode": 4}]}},
        "accessors": {"accessor0": {"bufferView": "view0", "byteOffset": 0, "componentType": 5126, "count": 3,
                                    "type": "VEC3"}},
        "bufferViews": {"view0": {"buffer": "buffer0", "byteOffset": 0, "byteLength": 36}},
        "buffers": {"buffer0": {"byteLength": 36, "uri": data_uri(floats([0, 0, 0, 1, 0, 0, 0, 1, 0]))}},
    }
    write("bad_version_1.gltf", gltf1)
    for name, asset in [("bad_version_3.gltf", {"version": "3.0"}),
                        ("bad_version_text.gltf", {"version": "two"}),
                        ("bad_min_version.gltf", {"version": "2.1", "minVersion": "2.1"}),
                        ("version_2_1.gltf", {"version": "2.1"})]:
        model = triangle_model()
        model["asset"] = asset
        write(name, model)
    data = bytearray(glb(triangle_model()))
    struct.pack_into("<I", data, 4, 1)
    with open("bad_glb_version_1.glb", "wb") as out:
        out.write(bytes(data))

    model = triangle_model()
    model["extensionsUsed"] = ["KHR_draco_mesh_compression"]
    model["extensionsRequired"] = ["KHR_draco_mesh_compression"]
    model["meshes"][0]["primitives"][0]["extensions"] = {
        "KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}
    write("bad_required_draco.gltf", model)
    model = triangle_model()
    model["extensionsUsed"] = ["EXT_blurcull_unknown"]
    write("unknown_extension_used.gltf", model)
    # Names from the file stay on one line: a newline shows as '?', a long
    # name is cut.
    model = triangle_model()
    model["extensionsUsed"] = ["EXT_line\nbreak", "EXT_" + "x" * 300]
    write("extension_names_odd.gltf", model)
    model = triangle_model()
    model["extensionsRequired"] = ["EXT_line\nbreak"]
    write("bad_required_newline.gltf", model)

    write("quantized.gltf", quantized_model())

    # A base colour texture whose image file is missing: warning, factor kept.
    model = triangle_model()
    model["images"] = [{"uri": "missing_texture.png"}]
    model["textures"] = [{"source": 0}]
    model["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    write("missing_texture.gltf", model)
    # An image file of 0 bytes (a truncated download): the same fallback.
    with open("empty_texture.png", "wb"):
        pass
    model["images"] = [{"uri": "empty_texture.png"}]
    write("empty_texture.gltf", model)


def morph_files():
    """issue 14 item 5: morph target animation as motion."""
    # Weights over keys 0, 1, 2 s: (0, 0) -> (1, 0.5) -> (1, 1), LINEAR.
    write("morph_animated.gltf",
          add_weights_animation(morph_model(), 0, [0.0, 1.0, 2.0], [[0.0, 0.0], [1.0, 0.5], [1.0, 1.0]]))
    # No animation: node 0 has its own weights (0, 1), node 1 uses the mesh's (0.5, 0).
    model = morph_model()
    model["nodes"] = [{"mesh": 0, "weights": [0.0, 1.0]}, {"mesh": 0, "translation": [5.0, 0.0, 0.0]}]
    model["scenes"][0]["nodes"] = [0, 1]
    write("morph_defaults.gltf", model)
    write("morph_skinned.gltf", morph_skinned_model())
    # The same weights with the node scaled 2x and translated 0 -> 10 x over
    # 2 s by a second channel of the same animation: morph, then the node.
    model = add_weights_animation(morph_model(), 0, [0.0, 1.0, 2.0], [[0.0, 0.0], [1.0, 0.5], [1.0, 1.0]])
    model["nodes"][0]["scale"] = [2.0, 2.0, 2.0]
    times = add_accessor(model, floats([0.0, 2.0]), 5126, 2, "SCALAR")
    moves = add_accessor(model, floats([0.0, 0.0, 0.0, 10.0, 0.0, 0.0]), 5126, 2, "VEC3")
    animation = model["animations"][0]
    animation["samplers"].append({"input": times, "output": moves})
    animation["channels"].append({"sampler": 1, "target": {"node": 0, "path": "translation"}})
    write("morph_node_animated.gltf", model)

    model = morph_model()
    model["nodes"][0]["weights"] = [1.0, 0.0, 0.0]
    write("bad_morph_node_weights.gltf", model)
    write("bad_morph_channel.gltf", add_weights_animation(morph_model(), 0, [0.0, 1.0], [[0.0], [1.0]]))
    model = morph_model()
    model["accessors"][2]["count"] = 2
    model["bufferViews"][2]["byteLength"] = 24
    write("bad_morph_target_count.gltf", model)
    model = morph_model()
    model["meshes"][0]["primitives"].append({"attributes": {"POSITION": 0}})
    write("bad_morph_primitives.gltf", model)


def main():
    # --- valid files ---
    write("triangle.gltf", triangle_model())
    write("triangle_animated.gltf",
          add_animation(triangle_model(), [0.0, 1.0], [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0)]))
    with open("triangle.glb", "wb") as out:
        out.write(glb(triangle_model()))

    # Strip (4 vertices -> 2 triangles), fan (5 -> 3), non-indexed triangles
    # with uint8 indices elsewhere, and a points primitive that is skipped.
    model = triangle_model()
    strip = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
    fan = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (-1, 1, 1)]
    extra = floats([c for p in strip + fan for c in p]) + struct.pack("<4B", 0, 1, 2, 0)
    model["buffers"].append({"byteLength": len(extra), "uri": data_uri(extra)})
    model["bufferViews"] += [
        {"buffer": 1, "byteOffset": 0, "byteLength": 12 * len(strip)},
        {"buffer": 1, "byteOffset": 12 * len(strip), "byteLength": 12 * len(fan)},
        {"buffer": 1, "byteOffset": 12 * (len(strip) + len(fan)), "byteLength": 3},
    ]
    model["accessors"] += [
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 3, "componentType": 5126, "count": 5, "type": "VEC3"},
        {"bufferView": 4, "componentType": 5121, "count": 3, "type": "SCALAR"},
    ]
    model["meshes"][0]["primitives"] += [
        {"attributes": {"POSITION": 2}, "mode": 5},
        {"attributes": {"POSITION": 3}, "mode": 6},
        {"attributes": {"POSITION": 3}, "indices": 4},
        {"attributes": {"POSITION": 3}, "mode": 0},
    ]
    write("modes.gltf", model)

    # A primitive with a NaN position is skipped with a warning; the other loads.
    model = triangle_model()
    bad = floats([0.0, 0.0, 0.0, float("nan"), 0.0, 0.0, 0.0, 1.0, 0.0])
    model["buffers"].append({"byteLength": len(bad), "uri": data_uri(bad)})
    model["bufferViews"].append({"buffer": 1, "byteOffset": 0, "byteLength": len(bad)})
    model["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"})
    model["meshes"][0]["primitives"].append({"attributes": {"POSITION": 2}})
    write("nan_position.gltf", model)

    # --- malformed files, one broken rule each ---
    text = json.dumps(triangle_model(), indent=1)
    with open("bad_json.gltf", "w", encoding="ascii") as out:
        out.write(text[: len(text) // 2])

    model = triangle_model()
    model["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7
    write("bad_accessor_index.gltf", model)

    model = triangle_model()
    model["accessors"][0]["count"] = 30
    write("bad_accessor_past_end.gltf", model)

    model = triangle_model()
    model["bufferViews"][1]["byteLength"] = 4000
    write("bad_buffer_view_past_end.gltf", model)

    write("bad_index_value.gltf", triangle_model(indices=(0, 1, 5)))

    write("bad_camera_yfov.gltf", add_camera(triangle_model(), 0.0))
    write("bad_camera_znear.gltf", add_camera(triangle_model(), 0.8, znear=0.0))

    model = triangle_model()
    model["nodes"] = [{"mesh": 0}, {"children": [2]}, {"children": [3]}, {"children": [1]}]
    write("bad_node_cycle.gltf", model)

    model = triangle_model()
    model["nodes"] = [{"mesh": 0, "children": [2]}, {"children": [2]}, {}]
    model["scenes"][0]["nodes"] = [0, 1]
    write("bad_node_two_parents.gltf", model)

    model = triangle_model()
    model["nodes"] = [{"children": [i + 1]} for i in range(1100)] + [{"mesh": 0}]
    write("bad_node_depth.gltf", model)

    write("bad_keyframes_order.gltf",
          add_animation(triangle_model(), [0.0, 1.0, 0.5],
                        [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0)]))
    write("bad_keyframes_nan.gltf",
          add_animation(triangle_model(), [0.0, math.nan], [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)]))

    model = triangle_model()
    model["buffers"][0]["uri"] = "does_not_exist.bin"
    write("bad_missing_buffer.gltf", model)

    with open("bad_truncated.glb", "wb") as out:
        out.write(glb(triangle_model())[:200])

    # --- robustness corpus (docs/robustness.md lists each file and its message) ---
    # +Inf positions: skipped with a warning like NaN; the good primitive loads.
    model = triangle_model()
    bad = floats([0.0, 0.0, 0.0, float("inf"), 0.0, 0.0, 0.0, -float("inf"), 0.0])
    model["buffers"].append({"byteLength": len(bad), "uri": data_uri(bad)})
    model["bufferViews"].append({"buffer": 1, "byteOffset": 0, "byteLength": len(bad)})
    model["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"})
    model["meshes"][0]["primitives"].append({"attributes": {"POSITION": 2}})
    write("inf_position.gltf", model)

    # Only a non-finite primitive: nothing is left to render.
    model = triangle_model(positions=[(0.0, 0.0, 0.0), (float("inf"), 0.0, 0.0), (0.0, 1.0, 0.0)])
    del model["accessors"][0]["min"], model["accessors"][0]["max"]
    write("bad_all_inf.gltf", model)

    # Only lines: skipped with a warning, then nothing to render.
    model = triangle_model()
    model["meshes"][0]["primitives"][0]["mode"] = 1
    write("bad_lines_only.gltf", model)

    model = triangle_model()
    model["meshes"][0]["primitives"][0]["mode"] = 9
    write("bad_mode.gltf", model)

    model = triangle_model()
    model["accessors"][0]["bufferView"] = 9
    write("bad_buffer_view_index.gltf", model)

    # The index accessor claims more indices than its buffer view holds.
    model = triangle_model()
    model["accessors"][1]["count"] = 300
    write("bad_index_count_past_end.gltf", model)

    # Counts whose byte size overflows 64 bits: count * stride wraps around.
    model = triangle_model()
    model["accessors"][0]["count"] = 2 ** 62 + 1
    write("bad_count_overflow.gltf", model)

    # No buffer view (all zeros in glTF) and an absurd count: must not allocate.
    model = triangle_model()
    del model["accessors"][0]["bufferView"]
    model["accessors"][0]["count"] = 2 ** 60
    write("bad_count_no_view.gltf", model)

    model = triangle_model()
    model["bufferViews"][0]["byteStride"] = 4
    write("bad_stride_small.gltf", model)

    model = triangle_model()
    model["bufferViews"][0]["byteStride"] = 1000
    write("bad_stride_huge.gltf", model)

    model = triangle_model()
    model["bufferViews"][0]["byteStride"] = -12
    write("bad_stride_negative.gltf", model)

    write("bad_camera_yfov_negative.gltf", add_camera(triangle_model(), -0.5))
    model = add_camera(triangle_model(), 0.8, znear=1.0)
    model["cameras"][0]["perspective"]["zfar"] = 0.5
    write("bad_camera_zfar.gltf", model)

    # A GLB whose JSON chunk claims more bytes than the file has.
    data = bytearray(glb(triangle_model()))
    struct.pack_into("<I", data, 12, len(data) * 4)
    with open("bad_glb_chunk.glb", "wb") as out:
        out.write(bytes(data))

    model = triangle_model()
    model["nodes"] = [{"mesh": 0, "children": [0]}]
    write("bad_node_self_child.gltf", model)

    conformance_files()
    morph_files()


if __name__ == "__main__":
    main()
