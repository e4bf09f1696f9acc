#!/usr/bin/env python3
"""Writes the small hand-made seeds of the fuzz corpus: glTF/GLB (tests/fuzz/seeds/{gltf,glb}/): two
cells joined by a portal, a lamp material, a camera, a strip, u16 indices, a PNG texture; GLBs with a
texture of every kind (PNG of every colour type, bit depth and interlacing, baseline JPEG in grey and
colour, and the formats a glTF may not hold: a 16-bit PGM, a truncated run-length HDR); the same images
alone (seeds/texture/) and small OpenEXR lightmaps (seeds/exr/). Small seeds keep libFuzzer fast;
run.sh adds the large seed scenes made by `cpgi generate`."""
import base64, json, os, struct, zlib

here = os.path.dirname(os.path.abspath(__file__))


def png_1x1(r, g, b):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = zlib.compress(bytes([0, r, g, b]))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)) + \
        chunk(b"IDAT", raw) + chunk(b"IEND", b"")


def png(width, height, depth, colour_type, rows, interlaced=False, chunks=()):
    """rows: the filtered-free scanlines' bytes (filter byte 0 is added); interlaced images are given as
    the concatenated scanlines of their Adam7 passes."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0,
                                                            1 if interlaced else 0))
    for kind, data in chunks:
        out += chunk(kind, data)
    return out + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def jpeg_flat(components):
    """A baseline JPEG of one flat 8x8 block (mid grey): one quantisation table, a DC and an AC Huffman
    table of one code each, every block coded as DC difference 0 then end-of-block."""
    def segment(marker, data):
        return b"\xff" + bytes([marker]) + struct.pack(">H", len(data) + 2) + data
    dqt = segment(0xDB, b"\x00" + bytes([1] * 64))
    sof = segment(0xC0, struct.pack(">BHHB", 8, 8, 8, components) +
                  b"".join(bytes([i + 1, 0x11, 0]) for i in range(components)))
    one_code = bytes([1] + [0] * 15)  # one code of length 1
    dht = segment(0xC4, b"\x00" + one_code + b"\x00") + segment(0xC4, b"\x10" + one_code + b"\x00")
    sos = segment(0xDA, bytes([components]) + b"".join(bytes([i + 1, 0x00]) for i in range(components)) +
                  b"\x00\x3f\x00")
    bits = "00" * components
    bits += "1" * (-len(bits) % 8)
    data = bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))
    return b"\xff\xd8" + dqt + sof + dht + sos + data + b"\xff\xd9"


def textures():
    """Every kind of texture image a scene may hold, by name."""
    rgb = [bytes([255, 0, 0, 0, 255, 0]), bytes([0, 0, 255, 128, 128, 128])]
    return {
        "png-rgb8": png(2, 2, 8, 2, rgb),
        "png-rgba8": png(2, 1, 8, 6, [bytes([255, 0, 0, 128, 0, 0, 255, 255])]),
        "png-grey1": png(8, 2, 1, 0, [b"\xa5", b"\x5a"]),
        "png-grey-alpha16": png(1, 1, 16, 4, [bytes([0x80, 0, 0xff, 0xff])]),
        "png-rgb16": png(1, 2, 16, 2, [bytes([255, 255, 0, 0, 0, 0]), bytes([0, 0, 0, 0, 255, 255])]),
        "png-palette-trns": png(2, 1, 8, 3, [b"\x00\x01"],
                                chunks=[(b"PLTE", bytes([255, 0, 0, 0, 0, 255])), (b"tRNS", b"\x80")]),
        # 1x1 Adam7: only the first pass holds a pixel.
        "png-adam7": png(1, 1, 8, 2, [bytes([10, 20, 30])], interlaced=True),
        "jpeg-grey": jpeg_flat(1),
        "jpeg-ycbcr": jpeg_flat(3),
        "pgm16": b"P5 4 4 65535\n" + bytes(32),
        "hdr-rle-truncated": b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 64\n\x02\x02\x00\x40\x80",
    }


def exr(width, height, channels):
    """An uncompressed scanline OpenEXR of float channels (name -> row-major values)."""
    def attribute(name, kind, data):
        return name.encode() + b"\x00" + kind.encode() + b"\x00" + struct.pack("<i", len(data)) + data
    names = sorted(channels)
    chlist = b"".join(n.encode() + b"\x00" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names) + b"\x00"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = b"\x76\x2f\x31\x01" + struct.pack("<I", 2)
    header += attribute("channels", "chlist", chlist) + attribute("compression", "compression", b"\x00")
    header += attribute("dataWindow", "box2i", box) + attribute("displayWindow", "box2i", box)
    header += attribute("lineOrder", "lineOrder", b"\x00") + attribute("pixelAspectRatio", "float", struct.pack("<f", 1))
    header += attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
    header += attribute("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\x00"
    blocks, offset = [], len(header) + 8 * height
    for y in range(height):
        pixels = b"".join(struct.pack("<%df" % width, *channels[n][y * width:(y + 1) * width]) for n in names)
        blocks.append(struct.pack("<ii", y, len(pixels)) + pixels)
    table = b""
    for block in blocks:
        table += struct.pack("<Q", offset)
        offset += len(block)
    return header + table + b"".join(blocks)


def scene(image=None):
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
    image_view = view(image if image is not None else png_1x1(200, 100, 50))
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


def glb_of(doc, bin_):
    text = json.dumps(dict(doc, buffers=[{"byteLength": len(bin_)}])).encode()
    while len(text) % 4:
        text += b" "
    out = b"glTF" + struct.pack("<II", 2, 12 + 8 + len(text) + 8 + len(bin_))
    return out + struct.pack("<I", len(text)) + b"JSON" + text + struct.pack("<I", len(bin_)) + b"BIN\x00" + bin_


os.makedirs(os.path.join(here, "texture"), exist_ok=True)
for name, image in textures().items():
    with open(os.path.join(here, "glb", "texture-" + name + ".glb"), "wb") as f:
        f.write(glb_of(*scene(image)))
    with open(os.path.join(here, "texture", name), "wb") as f:
        f.write(image)

os.makedirs(os.path.join(here, "exr"), exist_ok=True)
with open(os.path.join(here, "exr", "lightmap-4x3.exr"), "wb") as f:
    f.write(exr(4, 3, {"R": [0.5] * 12, "G": [0.25] * 12, "B": [1.0] * 12, "area": [0.01] * 12,
                       "cell": [0, 0, 1, 1] * 3}))
with open(os.path.join(here, "exr", "view-2x2.exr"), "wb") as f:
    f.write(exr(2, 2, {"R": [1, 2, 3, 4], "G": [0] * 4, "B": [0.5] * 4}))
