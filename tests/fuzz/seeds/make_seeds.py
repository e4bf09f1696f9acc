#!/usr/bin/env python3
"""Writes the small hand-made glTF/GLB seeds of the fuzz corpus (tests/fuzz/seeds/{gltf,glb}/): two
cells joined by a portal, a lamp material, a camera, a strip, u16 indices, a PNG texture. Small seeds
keep libFuzzer fast; run.sh adds the large seed scenes made by `cpgi generate`."""
import base64, json, os, struct, zlib

here = os.path.dirname(os.path.abspath(__file__))


def png_1x1(r, g, b):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = zlib.compress(bytes([0, r, g, b]))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)) + \
        chunk(b"IDAT", raw) + chunk(b"IEND", b"")


def scene():
    bin_ = bytearray()
    views, accessors = [], []

    def view(data):
        while len(bin_) % 4:
            bin_.append(0)
        views.append({"buffer": 0, "byteOffset": len(bin_), "byteLength": len(data)})
        bin_.extend(data)
        return len(views) - 1

    def vec3(values):
        accessors.append({"bufferView": view(struct.pack("<%df" % len(values), *values)), "componentType": 5126,
                          "count": len(values) // 3, "type": "VEC3"})
        return len(accessors) - 1

    def indices(values):
        accessors.append({"bufferView": view(struct.pack("<%dH" % len(values), *values)), "componentType": 5123,
                          "count": len(values), "type": "SCALAR"})
        return len(accessors) - 1

    floor_a = vec3([0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0])
    floor_b = vec3([1, 0, 0, 1, 0, 1, 2, 0, 1, 2, 0, 0])
    quad = indices([0, 1, 2, 0, 2, 3])
    portal = vec3([1, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1])
    strip = vec3([0, 1, 0, 1, 1, 0, 0, 1, 1, 1, 1, 1])
    image_view = view(png_1x1(200, 100, 50))
    doc = {
        "asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 4]}],
        "nodes": [
            {"name": "cell:A", "mesh": 0, "children": [3]},
            {"name": "cell:B", "mesh": 1, "translation": [0, 0, 0], "scale": [1, 1, 1]},
            {"name": "portal:A:B", "mesh": 2},
            {"name": "lamp", "mesh": 3, "rotation": [0, 0, 0, 1]},
            {"name": "eye", "camera": 0, "translation": [1, 0.5, 3]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": floor_a}, "indices": quad, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": floor_b}, "indices": quad, "material": 1}]},
            {"primitives": [{"attributes": {"POSITION": portal}, "indices": quad}]},
            {"primitives": [{"attributes": {"POSITION": strip}, "mode": 5, "material": 2}]},
        ],
        "materials": [
            {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.7, 0.6, 1]}},
            {"name": "textured", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
            {"name": "lamp", "emissiveFactor": [1, 1, 1],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 50}}},
        ],
        "textures": [{"source": 0}],
        "images": [{"bufferView": image_view, "mimeType": "image/png"}],
        "accessors": accessors, "bufferViews": views,
        "extensionsUsed": ["KHR_materials_emissive_strength"],
    }
    while len(bin_) % 4:
        bin_.append(0)
    return doc, bytes(bin_)


doc, bin_ = scene()
gltf = dict(doc, buffers=[{"byteLength": len(bin_),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()}])
with open(os.path.join(here, "gltf", "rooms.gltf"), "w") as f:
    json.dump(gltf, f)
text = json.dumps(dict(doc, buffers=[{"byteLength": len(bin_)}])).encode()
while len(text) % 4:
    text += b" "
glb = b"glTF" + struct.pack("<II", 2, 12 + 8 + len(text) + 8 + len(bin_))
glb += struct.pack("<I", len(text)) + b"JSON" + text + struct.pack("<I", len(bin_)) + b"BIN\x00" + bin_
with open(os.path.join(here, "glb", "rooms.glb"), "wb") as f:
    f.write(glb)
