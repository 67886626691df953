#!/usr/bin/env python3
"""Writes the glTF files of tests/test_frontend_shading.cpp (run from this directory).

attributes.gltf: a front quad with COLOR_0 (alpha 1 on its left edge, 0 on its
right), NORMAL (tilted per vertex) and alphaMode MASK (cutoff 0.5), in front of
a textured back quad (a 4x4 PNG, MIRRORED_REPEAT, KHR_texture_transform scale 3, rotation 90 degrees,
emissive factor), a directional KHR_lights_punctual light and a camera.
mask_texture.gltf: a front quad whose MASK comes from its base colour
texture's alpha (a 4x4 PNG with holes and intermediate alphas, REPEAT in s and
CLAMP_TO_EDGE in t, KHR_texture_transform scale 2 and offset, nearest filters
that blurcull ignores: always bilinear), baseColorFactor alpha 0.9 and
COLOR_0 alphas from 1 to 0.8, cutoff 0.4, in front of a plain back quad that
shows through the holes.
bad_*.gltf: one textured quad each, with a broken texture or texture coordinates.
"""
import base64, json, math, struct, zlib

def png(width, height, rgba_rows, claimed=None):
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    w, h = claimed or (width, height)
    raw = b''.join(b'\x00' + bytes(row) for row in rgba_rows)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))

def checker():
    rows = []
    for y in range(4):
        row = []
        for x in range(4):
            row += [230, 40, 40, 255] if (x + y) % 2 == 0 else [40, 40 + 50 * x, 230, 255]
        rows.append(row)
    return png(4, 4, rows)

def data_uri(mime, data):
    return 'data:%s;base64,%s' % (mime, base64.b64encode(data).decode())

class Buffer:
    def __init__(self):
        self.data = b''
        self.views = []
        self.accessors = []
    def add(self, fmt, values, type_, component=5126, target=34962, minmax=False):
        while len(self.data) % 4: self.data += b'\x00'
        blob = b''.join(struct.pack('<' + fmt, *v) if isinstance(v, tuple) else struct.pack('<' + fmt, v) for v in values)
        self.views.append({'buffer': 0, 'byteOffset': len(self.data), 'byteLength': len(blob), 'target': target})
        self.data += blob
        acc = {'bufferView': len(self.views) - 1, 'componentType': component, 'count': len(values), 'type': type_}
        if minmax:
            acc['min'] = [min(v[k] for v in values) for k in range(3)]
            acc['max'] = [max(v[k] for v in values) for k in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

def quad(buf, corners, uv=None, colours=None, normals=None):
    attrs = {'POSITION': buf.add('fff', corners, 'VEC3', minmax=True)}
    if uv is not None: attrs['TEXCOORD_0'] = buf.add('ff', uv, 'VEC2')
    if colours is not None: attrs['COLOR_0'] = buf.add('ffff', colours, 'VEC4')
    if normals is not None: attrs['NORMAL'] = buf.add('fff', normals, 'VEC3')
    indices = buf.add('H', [0, 1, 2, 0, 2, 3], 'SCALAR', component=5123, target=34963)
    return {'attributes': attrs, 'indices': indices}

def write(name, gltf, buf):
    gltf['asset'] = {'version': '2.0', 'generator': 'blurcull tests/data/shading/make_shading_files.py'}
    gltf['buffers'] = [{'byteLength': len(buf.data), 'uri': data_uri('application/octet-stream', buf.data)}]
    gltf['bufferViews'] = buf.views
    gltf['accessors'] = buf.accessors
    with open(name, 'w') as f:
        json.dump(gltf, f, indent=1)

def attributes_file():
    buf = Buffer()
    front = quad(buf, [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
                 colours=[(1, 1, 0.2, 1), (0.2, 1, 1, 0), (0.2, 1, 1, 0), (1, 1, 0.2, 1)],
                 normals=[(-0.5, 0, 1), (0.5, 0, 1), (0.5, 0.5, 1), (-0.5, 0.5, 1)])
    front['material'] = 0
    back = quad(buf, [(-2, -2, -1), (2, -2, -1), (2, 2, -1), (-2, 2, -1)], uv=[(0, 1), (1, 1), (1, 0), (0, 0)])
    back['material'] = 1
    gltf = {
        'extensionsUsed': ['KHR_lights_punctual', 'KHR_texture_transform'],
        'scene': 0, 'scenes': [{'nodes': [0, 1, 2]}],
        'nodes': [{'mesh': 0}, {'camera': 0, 'translation': [0, 0, 4]},
                  {'extensions': {'KHR_lights_punctual': {'light': 0}},
                   'rotation': [-0.3826834, 0, 0, 0.9238795]}],
        'meshes': [{'primitives': [front, back]}],
        'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.9, 'znear': 0.1, 'aspectRatio': 1.333}}],
        'extensions': {'KHR_lights_punctual': {'lights': [{'type': 'directional', 'color': [1, 0.9, 0.8], 'intensity': 1.0}]}},
        'materials': [
            {'name': 'masked', 'alphaMode': 'MASK', 'alphaCutoff': 0.5,
             'pbrMetallicRoughness': {'baseColorFactor': [0.9, 0.9, 0.9, 1]}},
            {'name': 'textured', 'emissiveFactor': [0.05, 0.02, 0.0],
             'pbrMetallicRoughness': {'baseColorTexture': {'index': 0, 'extensions': {
                 'KHR_texture_transform': {'scale': [3, 3], 'offset': [0.25, 0], 'rotation': 1.5707963267948966}}}}}],
        'textures': [{'source': 0, 'sampler': 0}],
        'samplers': [{'wrapS': 33648, 'wrapT': 33648}],
        'images': [{'uri': data_uri('image/png', checker())}],
    }
    write('attributes.gltf', gltf, buf)

def holes():
    alphas = [[255, 0, 255, 120], [0, 255, 200, 0], [255, 60, 0, 255], [140, 255, 255, 0]]
    return png(4, 4, [sum(([200, 180 - 40 * x, 40 + 50 * y, alphas[y][x]] for x in range(4)), []) for y in range(4)])

def mask_texture_file():
    buf = Buffer()
    front = quad(buf, [(-1.2, -1, 0), (1.2, -1, 0), (1.2, 1, 0), (-1.2, 1, 0)],
                 uv=[(0, 1), (1, 1), (1, 0), (0, 0)],
                 colours=[(1, 1, 1, 1), (1, 1, 1, 0.8), (1, 1, 1, 0.8), (1, 1, 1, 1)])
    front['material'] = 0
    back = quad(buf, [(-2, -2, -1), (2, -2, -1), (2, 2, -1), (-2, 2, -1)])
    back['material'] = 1
    gltf = {
        'extensionsUsed': ['KHR_texture_transform'],
        'scene': 0, 'scenes': [{'nodes': [0, 1]}],
        'nodes': [{'mesh': 0}, {'camera': 0, 'translation': [0, 0, 4]}],
        'meshes': [{'primitives': [front, back]}],
        'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.8, 'znear': 0.1, 'aspectRatio': 1.333}}],
        'materials': [
            {'name': 'holes', 'alphaMode': 'MASK', 'alphaCutoff': 0.4,
             'pbrMetallicRoughness': {'baseColorFactor': [1, 1, 1, 0.9], 'baseColorTexture': {'index': 0, 'extensions': {
                 'KHR_texture_transform': {'scale': [2, 1.5], 'offset': [0.1, -0.2]}}}}},
            {'name': 'behind', 'pbrMetallicRoughness': {'baseColorFactor': [0.1, 0.7, 0.2, 1]}}],
        'textures': [{'source': 0, 'sampler': 0}],
        'samplers': [{'wrapS': 10497, 'wrapT': 33071, 'magFilter': 9728, 'minFilter': 9728}],
        'images': [{'uri': data_uri('image/png', holes())}],
    }
    write('mask_texture.gltf', gltf, buf)

def textured_quad(name, image, uv=None):
    buf = Buffer()
    prim = quad(buf, [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
                uv=uv or [(0, 1), (1, 1), (1, 0), (0, 0)])
    prim['material'] = 0
    gltf = {'scene': 0, 'scenes': [{'nodes': [0]}], 'nodes': [{'mesh': 0}],
            'meshes': [{'primitives': [prim]}],
            'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [0.2, 0.6, 0.3, 1],
                                                    'baseColorTexture': {'index': 0}}}],
            'textures': [{'source': 0}], 'images': [image]}
    write(name, gltf, buf)

attributes_file()
mask_texture_file()
textured_quad('bad_texture_missing.gltf', {'uri': 'no_such_texture.png'})
textured_quad('bad_texture_truncated.gltf', {'uri': data_uri('image/png', checker()[:45])})
textured_quad('bad_texture_format.gltf', {'uri': data_uri('image/bmp', b'BM' + bytes(60))})
textured_quad('bad_texture_huge.gltf', {'uri': data_uri('image/png', png(1, 1, [[0, 0, 0, 255]], claimed=(9000, 9000)))})
textured_quad('bad_texcoord_nan.gltf', {'uri': data_uri('image/png', checker())},
              uv=[(float('nan'), 1), (1, 1), (1, 0), (0, 0)])
textured_quad('bad_texcoord_far.gltf', {'uri': data_uri('image/png', checker())},
              uv=[(1e9, 1), (1, -3e9), (1, 0), (0, 0)])
