#!/usr/bin/env python3
"""Issue 49's hostile round, regenerated from the issue's text and run one input at a time.

Writes about 170 hostile inputs (glTF, GLB and OBJ that are truncated, empty, NaN-laden, non-manifold,
enormous or lying about their sizes; images of every kind a texture may claim to be; names made of HTML,
invalid UTF-8 and control bytes; FIFOs, folders, symlinks to devices; the earlier rounds' hostile files)
and runs each through `cpgi info`, `cpgi decompose` and `cpgi bake` with short limits. Each run must:
  - end by exit 0 or 1, never by a signal (a crash, an abort, a sanitizer report);
  - on exit 1, say so in one `cpgi: ...` line that names the input file (or, for a limit refused up front,
    the option that sets it);
  - stay inside the CPU-second bound and the peak-RSS bound (a wall bound kills a hang);
  - on exit 1, leave the output folder as it found it (absent, or holding only the user's own file).
Prints one row per failing run and a summary, and writes every run (input, command, exit, CPU s, wall s,
peak RSS MB, problems) to WORK/runs.tsv; exit status 1 when any run failed.

  bench/hostile_round.py CPGI [--work DIR] [--cpu-seconds 20] [--wall-seconds 120] [--rss-mb 2048]
                         [--only SUBSTRING] [--commands info,decompose,bake] [--list]

CPGI is the binary to attack: a Release build for the time and memory bounds, an ASan + UBSan build for
the crash check (its memory bound is loose: the sanitizer's shadow counts in the RSS)."""
import argparse, base64, copy, json, os, shutil, signal, stat, struct, subprocess, sys, time, zlib

# ---------------------------------------------------------------------------------------------- scenes

LAMP = {"name": "lamp", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {
    "emissiveStrength": 50}}, "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}}
WALL = {"name": "wall", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1]}}


def box_triangles(x0, y0, z0, x1, y1, z1):
    """A closed box's 12 triangles, wound to face inward, as (positions, indices)."""
    p = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (x0, y0, z1), (x1, y0, z1), (x1, y1, z1),
         (x0, y1, z1)]
    quads = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (3, 2, 6, 7), (0, 3, 7, 4), (1, 5, 6, 2)]
    idx = []
    for a, b, c, d in quads:
        idx += [a, b, c, a, c, d]
    return [v for q in p for v in q], idx


def lamp_quad(y=2.9):
    return [1.5, y, 1.5, 2.5, y, 1.5, 2.5, y, 2.5, 1.5, y, 2.5], [0, 2, 1, 0, 3, 2]


class Gltf:
    """A glTF document with one binary buffer, built a primitive at a time."""

    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}], "nodes": [],
                    "meshes": [], "materials": [copy.deepcopy(WALL), copy.deepcopy(LAMP)], "accessors": [], "bufferViews": [],
                    "buffers": []}

    def view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.doc["bufferViews"].append(v)
        self.bin.extend(data)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, data, fmt, count, kind, component, minmax=None):
        a = {"bufferView": self.view(struct.pack("<%d%s" % (len(data), fmt), *data)), "componentType": component,
             "count": count, "type": kind}
        if minmax:
            a["min"], a["max"] = minmax
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def mesh(self, positions, indices, material=0, name=None, node_name=None, mode=None):
        finite = [v for v in positions if v == v and abs(v) != float("inf")] or [0.0]
        lo = [min(finite[i::3] or [0]) for i in range(3)]
        hi = [max(finite[i::3] or [0]) for i in range(3)]
        pos = self.accessor(positions, "f", len(positions) // 3, "VEC3", 5126, (lo, hi))
        prim = {"attributes": {"POSITION": pos}, "material": material}
        if indices is not None:
            prim["indices"] = self.accessor(indices, "I", len(indices), "SCALAR", 5125)
        if mode is not None:
            prim["mode"] = mode
        self.doc["meshes"].append({"primitives": [prim], **({"name": name} if name else {})})
        self.doc["nodes"].append({"mesh": len(self.doc["meshes"]) - 1, **({"name": node_name} if node_name else {})})
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1

    def room(self):
        self.mesh(*box_triangles(0, 0, 0, 4, 3, 4), 0, "room", "room")
        self.mesh(*lamp_quad(), 1, "lamp", "lamp")
        return self

    def glb(self):
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        js = json.dumps(self.doc).encode()
        js += b" " * (-len(js) % 4)
        b = bytes(self.bin) + b"\x00" * (-len(self.bin) % 4)
        body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(b), 0x004E4942) + b
        return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body

    def gltf(self):
        self.doc["buffers"] = [{"byteLength": len(self.bin), "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.bin)).decode()}]
        return json.dumps(self.doc).encode()


def room():
    return Gltf().room()


def doc_edit(edit, fmt="glb"):
    """A room scene with EDIT(doc, gltf) applied to its JSON before it is written."""
    g = Gltf().room()
    edit(g.doc, g)
    return g.glb() if fmt == "glb" else g.gltf()


# ---------------------------------------------------------------------------------------------- images

def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(width, height, depth=8, colour=2, raw=None, interlace=0, extra=()):
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}.get(colour, 3)
    if raw is None:
        row = b"\x00" + b"\x80" * ((width * channels * depth + 7) // 8)
        raw = row * height
    out = b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0,
                                                                 interlace))
    for kind, data in extra:
        out += png_chunk(kind, data)
    return out + png_chunk(b"IDAT", zlib.compress(raw)) + png_chunk(b"IEND", b"")


def jpeg(width=8, height=8, components=3, truncate=False):
    def seg(marker, data):
        return b"\xff" + bytes([marker]) + struct.pack(">H", len(data) + 2) + data
    dqt = seg(0xDB, b"\x00" + bytes([1] * 64))
    sof = seg(0xC0, struct.pack(">BHHB", 8, height, width, components) +
              b"".join(bytes([i + 1, 0x11, 0]) for i in range(components)))
    one = bytes([1] + [0] * 15)
    dht = seg(0xC4, b"\x00" + one + b"\x00") + seg(0xC4, b"\x10" + one + b"\x00")
    sos = seg(0xDA, bytes([components]) + b"".join(bytes([i + 1, 0]) for i in range(components)) + b"\x00\x3f\x00")
    blocks = ((width + 7) // 8) * ((height + 7) // 8)
    bits = "00" * components * min(blocks, 64)
    bits += "1" * (-len(bits) % 8)
    data = bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))
    out = b"\xff\xd8" + dqt + sof + dht + sos + data
    return out if truncate else out + b"\xff\xd9"


def images():
    """Texture images by name: every kind a scene may hold, and ones that lie about themselves."""
    ok = png(4, 4)
    return {
        "png-rgb8": ok,
        "png-rgba8": png(2, 2, 8, 6),
        "png-grey1": png(8, 2, 1, 0),
        "png-grey-alpha16": png(1, 1, 16, 4),
        "png-rgb16": png(2, 2, 16, 2),
        "png-palette": png(2, 1, 8, 3, extra=[(b"PLTE", bytes([255, 0, 0, 0, 0, 255])), (b"tRNS", b"\x80")]),
        "png-palette-missing": png(2, 1, 8, 3),
        "png-adam7": png(3, 3, 8, 2, interlace=1, raw=zlib.decompress(zlib.compress(bytes(64)))),
        "png-says-100000-square": png(100000, 100000, raw=b"\x00\x80\x80\x80"),
        "png-says-1x1-holds-more": png(1, 1, raw=b"\x00" + b"\x80" * 3 * 4096),
        "png-says-4096-holds-1-row": png(4096, 4096, raw=b"\x00" + b"\x80" * 3 * 4096),
        "png-zero-width": png(0, 4, raw=b"\x00" * 4),
        "png-truncated": ok[:len(ok) // 2],
        "png-bad-crc": ok[:-5] + b"\x00" + ok[-4:],
        "png-no-idat": ok[:33] + png_chunk(b"IEND", b""),
        "png-bad-depth": png(2, 2, 7, 2),
        "png-bad-colour-type": png(2, 2, 8, 5),
        "png-zlib-bomb": png(8192, 8192, 8, 0, raw=bytes(8193 * 8192)),
        "jpeg-ycbcr": jpeg(),
        "jpeg-grey": jpeg(components=1),
        "jpeg-says-65500-square": jpeg(65500, 65500),
        "jpeg-truncated": jpeg(truncate=True)[:-6],
        "jpeg-four-components": jpeg(components=4),
        "jpeg-zero-height": jpeg(8, 0),
        "pgm16": b"P5 64 64 65535\n" + bytes(64 * 64 * 2),
        "hdr-rle-truncated": b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 64\n\x02\x02\x00\x40\x80",
        "gif": b"GIF89a\x01\x00\x01\x00\x80\x00\x00\xff\xff\xff\x00\x00\x00!\xf9\x04\x01\x00\x00\x00\x00,"
               b"\x00\x00\x00\x00\x01\x00\x01\x00\x00\x02\x02D\x01\x00;",
        "bmp": b"BM" + struct.pack("<IHHIIiiHHIIiiII", 58, 0, 0, 54, 40, 1, 1, 1, 24, 0, 4, 0, 0, 0, 0) + b"\x80" * 4,
        "psd": b"8BPS\x00\x01" + bytes(6) + struct.pack(">HIIHH", 3, 1, 1, 8, 3) + bytes(16),
        "tga-like": bytes([0, 0, 2]) + bytes(9) + struct.pack("<HHBB", 1, 1, 24, 0) + b"\x80\x80\x80",
        "ktx2": b"\xabKTX 20\xbb\r\n\x1a\n" + bytes(64),
        "webp": b"RIFF" + struct.pack("<I", 30) + b"WEBPVP8 " + bytes(22),
        "empty": b"",
        "one-byte": b"\x89",
        "random": bytes((i * 131 + 7) % 256 for i in range(4096)),
    }


def textured(image, uri=None, mime="image/png", materials=1):
    """A room whose walls carry IMAGE (bytes in the GLB, or a uri) as base colour, on MATERIALS materials."""
    g = Gltf()
    positions, indices = box_triangles(0, 0, 0, 4, 3, 4)
    g.mesh(positions, indices, 0, "room", "room")
    uv = g.accessor([0.0, 0.0] * 8, "f", 8, "VEC2", 5126)
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv
    g.mesh(*lamp_quad(), 1, "lamp", "lamp")
    if uri is None:
        g.doc["images"] = [{"bufferView": g.view(image), "mimeType": mime}]
    else:
        g.doc["images"] = [{"uri": uri}]
    g.doc["textures"] = [{"source": 0}]
    for m in range(materials):
        mat = {"name": "wall%d" % m, "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}
        if m == 0:
            g.doc["materials"][0] = mat
        else:
            g.doc["materials"].append(mat)
            g.mesh([0, 0.01 * m, 0, 0.1, 0.01 * m, 0, 0, 0.01 * m, 0.1], [0, 1, 2], len(g.doc["materials"]) - 1)
            g.doc["meshes"][-1]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv
    return g.glb()


# ---------------------------------------------------------------------------------------------- OBJ

OBJ_ROOM = "".join("v %g %g %g\n" % v for v in [(0, 0, 0), (4, 0, 0), (4, 3, 0), (0, 3, 0), (0, 0, 4), (4, 0, 4),
                                                 (4, 3, 4), (0, 3, 4)]) + \
    "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n"
OBJ_LAMP = "usemtl lamp\nv 1.5 2.9 1.5\nv 2.5 2.9 1.5\nv 2.5 2.9 2.5\nv 1.5 2.9 2.5\nf -4 -2 -3\nf -4 -1 -2\n"


# ---------------------------------------------------------------------------------------------- the round

def earlier_hostile_files():
    """The earlier rounds' hostile glTFs (tests/core/hostile_gltf_test.cpp and hostile_numbers_test.cpp)."""
    out = {}

    def wrap_view(d, g):
        d["bufferViews"][0]["byteLength"] = 2 ** 64 - 8
    out["earlier-view-length-wraps.glb"] = doc_edit(wrap_view)

    def wrap_accessor(d, g):
        d["accessors"][0]["byteOffset"] = 2 ** 64 - 4
    out["earlier-accessor-offset-wraps.glb"] = doc_edit(wrap_accessor)

    def view_past(d, g):
        d["bufferViews"][0]["byteOffset"] = 10 ** 6
    out["earlier-view-offset-past-buffer.glb"] = doc_edit(view_past)

    def nested(depth):
        def edit(d, g):
            base = len(d["nodes"])
            for i in range(depth):
                d["nodes"].append({"children": [base + i + 1]} if i + 1 < depth else {"mesh": 0})
            d["scenes"][0]["nodes"].append(base)
        return edit
    out["earlier-10000-nested-nodes.glb"] = doc_edit(nested(10000))
    out["earlier-200-nested-nodes.glb"] = doc_edit(nested(200))

    def long_paths(d, g):
        base = len(d["nodes"])
        for i in range(3000):
            d["nodes"].append({"name": "n" * 200 + str(i), "children": [base + i + 1]} if i + 1 < 3000 else {"mesh": 0})
        d["scenes"][0]["nodes"].append(base)
    out["earlier-long-node-paths.glb"] = doc_edit(long_paths)
    out["earlier-deeply-nested-json.gltf"] = b'{"asset":{"version":"2.0"},"extras":' + b"[" * 100000 + b"]" * 100000 + b"}"
    out["earlier-brackets-in-strings.gltf"] = doc_edit(lambda d, g: d["nodes"][0].update(name="[" * 5000), "gltf")

    def zeros(d, g):
        d["accessors"].append({"componentType": 5126, "count": 2 ** 31, "type": "VEC3"})
        d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = len(d["accessors"]) - 1
    out["earlier-accessor-without-view-2e31.glb"] = doc_edit(zeros)

    def unused_image(d, g):
        d["images"] = [{"bufferView": g.view(b"not an image at all")}]
    out["earlier-unused-image.glb"] = doc_edit(unused_image)

    def image_past(d, g):
        d["images"] = [{"bufferView": len(d["bufferViews"]), "mimeType": "image/png"}]
        d["bufferViews"].append({"buffer": 0, "byteOffset": 0, "byteLength": 10 ** 7})
        d["textures"] = [{"source": 0}]
        d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    out["earlier-image-view-past-buffer.glb"] = doc_edit(image_past)

    def instancing(d, g):
        d["nodes"] += [{"mesh": 0, "translation": [0, 0, 0.001 * i]} for i in range(200000)]
        d["scenes"][0]["nodes"] += list(range(len(d["nodes"]) - 200000, len(d["nodes"])))
    out["earlier-200000-instances.glb"] = doc_edit(instancing)
    out["earlier-far-coordinates.glb"] = doc_edit(lambda d, g: d["nodes"][0].update(scale=[1e7, 1e7, 1e7]))

    def big_portal(d, g):
        n = 100
        import math
        pos = []
        for i in range(n):
            a = 2 * math.pi * i / n
            pos += [2 + math.cos(a), 1.5 + math.sin(a), 2.0]
        idx = []
        for i in range(1, n - 1):
            idx += [0, i, i + 1]
        g.mesh(pos, idx, 0, "portal", "portal:big")
    out["earlier-100-vertex-portal.glb"] = doc_edit(big_portal)
    return out


def truncations(name, data, cuts):
    return {"%s-cut-%d%s" % (name.rsplit(".", 1)[0], c, "." + name.rsplit(".", 1)[1]): data[:c] for c in cuts}


def numeric_inputs():
    out = {}
    nan, inf = float("nan"), float("inf")
    for label, value in [("nan", nan), ("inf", inf), ("minus-inf", -inf), ("1e38", 1e38), ("1e8", 1e8),
                         ("1e-40", 1e-40), ("minus-0", -0.0)]:
        g = Gltf()
        p, i = box_triangles(0, 0, 0, 4, 3, 4)
        p[3] = value
        g.mesh(p, i, 0, "room", "room")
        g.mesh(*lamp_quad(), 1)
        out["vertex-%s.glb" % label] = g.glb()
    for label, edit in [
        ("translation-1e300", lambda d, g: d["nodes"][0].update(translation=[1e300, 0, 0])),
        ("scale-zero", lambda d, g: d["nodes"][0].update(scale=[0, 0, 0])),
        ("scale-negative", lambda d, g: d["nodes"][0].update(scale=[-1, 1, 1])),
        ("scale-1e-12", lambda d, g: d["nodes"][0].update(scale=[1e-12] * 3)),
        ("scale-1e30", lambda d, g: [n.update(scale=[1e30] * 3) for n in d["nodes"]]),
        ("rotation-zero-quaternion", lambda d, g: d["nodes"][0].update(rotation=[0, 0, 0, 0])),
        ("rotation-1e308", lambda d, g: d["nodes"][0].update(rotation=[1e308, 0, 0, 1])),
        ("matrix-singular", lambda d, g: d["nodes"][0].update(matrix=[0] * 16)),
        ("matrix-projective", lambda d, g: d["nodes"][0].update(matrix=[1, 0, 0, 5, 0, 1, 0, 5, 0, 0, 1, 5, 0, 0, 0, 0])),
        ("matrix-short", lambda d, g: d["nodes"][0].update(matrix=[1, 0, 0])),
        ("emissive-1e30", lambda d, g: d["materials"][1]["extensions"]["KHR_materials_emissive_strength"].update(
            emissiveStrength=1e30)),
        ("emissive-negative", lambda d, g: d["materials"][1].update(emissiveFactor=[-1, -1, -1])),
        ("emissive-1e-30", lambda d, g: d["materials"][1]["extensions"]["KHR_materials_emissive_strength"].update(
            emissiveStrength=1e-30)),
        ("albedo-negative", lambda d, g: d["materials"][0]["pbrMetallicRoughness"].update(baseColorFactor=[-1, 2, 0.5, 1])),
        ("albedo-above-1", lambda d, g: d["materials"][0]["pbrMetallicRoughness"].update(baseColorFactor=[5, 5, 5, 1])),
        ("albedo-short", lambda d, g: d["materials"][0]["pbrMetallicRoughness"].update(baseColorFactor=[0.5])),
        ("camera-aspect-0.001", lambda d, g: camera(d, {"yfov": 1.0, "aspectRatio": 0.001, "znear": 0.01})),
        ("camera-aspect-1e6", lambda d, g: camera(d, {"yfov": 1.0, "aspectRatio": 1e6, "znear": 0.01})),
        ("camera-yfov-0", lambda d, g: camera(d, {"yfov": 0, "znear": 0.01})),
        ("camera-yfov-pi", lambda d, g: camera(d, {"yfov": 3.14159265, "znear": 0.01})),
        ("camera-znear-0", lambda d, g: camera(d, {"yfov": 1.0, "znear": 0})),
        ("camera-zfar-before-znear", lambda d, g: camera(d, {"yfov": 1.0, "znear": 1, "zfar": 0.5})),
        ("camera-orthographic-zero", lambda d, g: camera(d, None, {"xmag": 0, "ymag": 0, "znear": 0, "zfar": 1})),
        ("light-point-negative", lambda d, g: light(d, {"type": "point", "intensity": -5})),
        ("light-point-1e30", lambda d, g: light(d, {"type": "point", "intensity": 1e30})),
        ("light-spot-cones-swapped", lambda d, g: light(d, {"type": "spot", "intensity": 100, "spot": {
            "innerConeAngle": 1.0, "outerConeAngle": 0.5}})),
        ("light-directional-only", lambda d, g: light(d, {"type": "directional", "intensity": 1000})),
        ("light-unknown-type", lambda d, g: light(d, {"type": "area", "intensity": 100})),
        ("light-range-zero", lambda d, g: light(d, {"type": "point", "intensity": 100, "range": 0})),
        ("light-index-past-end", lambda d, g: light(d, {"type": "point", "intensity": 100}, index=7)),
    ]:
        out["%s.glb" % label] = doc_edit(edit)
    return out


def camera(d, perspective, orthographic=None):
    cam = {"type": "perspective", "perspective": perspective} if perspective else \
        {"type": "orthographic", "orthographic": orthographic}
    d["cameras"] = [cam]
    d["nodes"].append({"camera": 0, "translation": [2, 1.5, 2], "name": "cam"})
    d["scenes"][0]["nodes"].append(len(d["nodes"]) - 1)


def light(d, spec, index=0):
    d.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
    d["extensions"] = {"KHR_lights_punctual": {"lights": [spec]}}
    d["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": index}}, "translation": [2, 2, 2]})
    d["scenes"][0]["nodes"].append(len(d["nodes"]) - 1)


def structural_inputs():
    out = {}
    edits = [
        ("no-scenes", lambda d, g: (d.pop("scenes"), d.pop("scene"))),
        ("scene-index-past-end", lambda d, g: d.update(scene=9)),
        ("node-cycle", lambda d, g: (d["nodes"][0].update(children=[1]), d["nodes"][1].update(children=[0]))),
        ("node-self-child", lambda d, g: d["nodes"][0].update(children=[0])),
        ("node-two-parents", lambda d, g: d["nodes"].append({"children": [0]}) or d["scenes"][0]["nodes"].append(2)),
        ("mesh-index-past-end", lambda d, g: d["nodes"][0].update(mesh=99)),
        ("mesh-index-negative", lambda d, g: d["nodes"][0].update(mesh=-1)),
        ("material-past-end", lambda d, g: d["meshes"][0]["primitives"][0].update(material=99)),
        ("indices-past-vertices", lambda d, g: g.doc["accessors"][1].update(bufferView=g.view(struct.pack(
            "<3I", 0, 1, 0xFFFFFFFF)), count=3)),
        ("index-count-not-triple", lambda d, g: d["accessors"][1].update(count=35)),
        ("accessor-count-2e31", lambda d, g: d["accessors"][0].update(count=2 ** 31)),
        ("accessor-count-negative", lambda d, g: d["accessors"][0].update(count=-3)),
        ("accessor-stride-huge", lambda d, g: d["bufferViews"][0].update(byteStride=252)),
        ("accessor-stride-1e9", lambda d, g: d["bufferViews"][0].update(byteStride=10 ** 9)),
        ("accessor-type-wrong", lambda d, g: d["accessors"][0].update(type="MAT4")),
        ("accessor-component-double", lambda d, g: d["accessors"][0].update(componentType=5130)),
        ("accessor-sparse", lambda d, g: d["accessors"][0].update(sparse={"count": 2 ** 30, "indices": {
            "bufferView": 0, "componentType": 5125}, "values": {"bufferView": 0}})),
        ("position-normalized-bytes", lambda d, g: d["accessors"][0].update(componentType=5121, normalized=True)),
        ("buffer-uri-missing-file", lambda d, g: d.update(buffers=[{"byteLength": 10, "uri": "nothere.bin"}])),
        ("mode-points", lambda d, g: d["meshes"][0]["primitives"][0].update(mode=0)),
        ("mode-lines", lambda d, g: d["meshes"][0]["primitives"][0].update(mode=1)),
        ("mode-strip", lambda d, g: d["meshes"][0]["primitives"][0].update(mode=5)),
        ("mode-fan", lambda d, g: d["meshes"][0]["primitives"][0].update(mode=6)),
        ("mode-99", lambda d, g: d["meshes"][0]["primitives"][0].update(mode=99)),
        ("no-position", lambda d, g: d["meshes"][0]["primitives"][0]["attributes"].pop("POSITION")),
        ("extension-required-unknown", lambda d, g: d.update(extensionsRequired=["KHR_draco_mesh_compression"])),
        ("asset-version-1", lambda d, g: d.update(asset={"version": "1.0"})),
        ("no-lamp", lambda d, g: d["materials"].__setitem__(1, copy.deepcopy(WALL))),
        ("texture-index-past-end", lambda d, g: d["materials"][0]["pbrMetallicRoughness"].update(
            baseColorTexture={"index": 5})),
        ("image-uri-etc-passwd", lambda d, g: image_uri(d, "/etc/passwd")),
        ("image-uri-parent", lambda d, g: image_uri(d, "../../../../etc/hostname")),
        ("image-uri-dev-zero", lambda d, g: image_uri(d, "/dev/zero")),
        ("image-data-uri-bad-base64", lambda d, g: image_uri(d, "data:image/png;base64,!!!notbase64")),
        ("image-data-uri-empty", lambda d, g: image_uri(d, "data:image/png;base64,")),
        ("buffer-uri-etc-passwd", lambda d, g: d.update(buffers=[{"byteLength": 10, "uri": "/etc/passwd"}])),
    ]
    for label, edit in edits:
        out["%s.glb" % label] = doc_edit(edit)
    out["buffer-uri-etc-passwd.gltf"] = json.dumps({"asset": {"version": "2.0"}, "buffers": [
        {"byteLength": 100, "uri": "/etc/passwd"}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}]}).encode()
    out["buffer-data-uri-short.gltf"] = doc_edit(lambda d, g: None, "gltf").replace(b";base64,", b";base64,AAAA", 1)[:-200] + b"\"}]}"
    return out


def image_uri(d, uri):
    d["images"] = [{"uri": uri}]
    d["textures"] = [{"source": 0}]
    d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}


def empty_and_degenerate():
    out = {"empty.glb": b"", "empty.gltf": b"", "empty.obj": b"", "braces.gltf": b"{}",
           "null.gltf": b"null", "array.gltf": b"[]", "header-only.glb": struct.pack("<4sII", b"glTF", 2, 12),
           "glb-version-1.glb": struct.pack("<4sII", b"glTF", 1, 12),
           "glb-length-4g.glb": struct.pack("<4sII", b"glTF", 2, 0xFFFFFFFF) + struct.pack("<II", 2, 0x4E4F534A) + b"{}",
           "glb-chunk-length-4g.glb": struct.pack("<4sII", b"glTF", 2, 28) + struct.pack("<II", 0xFFFFFFF0,
                                                                                        0x4E4F534A) + b"{}  ",
           "glb-json-not-json.glb": None, "gltf-utf16.gltf": '{"asset":{"version":"2.0"}}'.encode("utf-16"),
           "gltf-bom.gltf": b"\xef\xbb\xbf" + doc_edit(lambda d, g: None, "gltf"),
           "obj-comments-only.obj": b"# nothing\n# here\n", "obj-vertices-only.obj": OBJ_ROOM.split("f ")[0].encode(),
           "obj-binary-junk.obj": bytes(range(256)) * 64}
    body = b'{"asset":'
    out["glb-json-not-json.glb"] = struct.pack("<4sII", b"glTF", 2, 20 + 12) + struct.pack("<II", 12, 0x4E4F534A) + \
        body + b"   "
    g = Gltf()
    g.mesh([0, 0, 0, 1, 1, 1, 2, 2, 2] * 4, list(range(12)), 0)
    g.mesh(*lamp_quad(), 1)
    out["all-degenerate.glb"] = g.glb()
    g = Gltf()
    g.mesh(*box_triangles(0, 0, 0, 4, 3, 4), 0)
    out["room-without-lamp.glb"] = g.glb()
    p, i = box_triangles(0, 0, 0, 4, 3, 4)
    g = Gltf()
    g.mesh(p, i * 50, 0)
    g.mesh(*lamp_quad(), 1)
    out["duplicate-triangles-x50.glb"] = g.glb()
    g = Gltf()
    g.mesh(p, i[:30], 0)
    g.mesh(*lamp_quad(), 1)
    out["open-box.glb"] = g.glb()
    g = Gltf()
    g.mesh([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 2], 1)
    out["one-triangle-lamp.glb"] = g.glb()
    g = Gltf()
    g.mesh(p, [i[k ^ 1] if k % 3 == 1 else i[k] for k in range(len(i))], 0)
    g.mesh(*lamp_quad(), 1)
    out["room-inside-out.glb"] = g.glb()
    g = Gltf()
    g.mesh(p, i, 0)
    g.mesh(*box_triangles(1, 1, 1, 2, 2, 2), 0)
    g.mesh(*box_triangles(1.5, 0.5, 1.5, 2.5, 2.5, 2.5), 0)
    g.mesh(*lamp_quad(), 1)
    out["intersecting-boxes.glb"] = g.glb()
    g = Gltf()
    tp, ti = [], []
    for k in range(2000):  # a fan of needles: T-junctions and slivers
        tp += [0, 0, 0, 4, 0.0001 * k, 4, 4, 0.0001 * (k + 1), 4]
        ti += [3 * k, 3 * k + 1, 3 * k + 2]
    g.mesh(p, i, 0)
    g.mesh(tp, ti, 0)
    g.mesh(*lamp_quad(), 1)
    out["sliver-fan.glb"] = g.glb()
    for label, (x1, y1, z1) in [("tiny-1e-6-m", (1e-6, 1e-6, 1e-6)), ("huge-1e5-m", (1e5, 3, 1e5)),
                                ("flat-zero-height", (4, 0, 4)), ("needle-1000x0.01", (1000, 0.01, 0.01))]:
        g = Gltf()
        g.mesh(*box_triangles(0, 0, 0, x1, y1, z1), 0)
        g.mesh([v * x1 / 4 if k % 3 == 0 else v for k, v in enumerate(lamp_quad(y1 * 0.9)[0])], lamp_quad()[1], 1)
        out["room-%s.glb" % label] = g.glb()
    return out


def enormous_inputs():
    out = {}
    g = Gltf()
    p, i = box_triangles(0, 0, 0, 4, 3, 4)
    g.mesh(p, i, 0)
    n = 300
    grid = [v for y in range(n) for x in range(n) for v in (0.5 + 3 * x / n, 0.01, 0.5 + 3 * y / n)]
    tri = [k for y in range(n - 1) for x in range(n - 1) for k in (y * n + x, y * n + x + 1, (y + 1) * n + x,
                                                                 y * n + x + 1, (y + 1) * n + x + 1, (y + 1) * n + x)]
    g.mesh(grid, tri, 0)
    g.mesh(*lamp_quad(), 1)
    out["carpet-180k-triangles.glb"] = g.glb()
    out["materials-20000.glb"] = doc_edit(lambda d, g: d["materials"].extend(
        [{"name": "m%d" % k} for k in range(20000)]))
    out["names-1mb.glb"] = doc_edit(lambda d, g: d["nodes"][0].update(name="x" * (1 << 20)))
    out["extras-10mb-string.gltf"] = doc_edit(lambda d, g: d.update(extras="y" * (10 << 20)), "gltf")
    out["texture-8192-png-100-materials.glb"] = textured(png(8192, 8192, 8, 2, raw=(b"\x00" + bytes(8192 * 3)) * 8192),
                                                         materials=100)
    obj_lines = ["v %d %d 0" % (k % 2, k // 2) for k in range(20000)]
    out["obj-face-20000-vertices.obj"] = ("\n".join(obj_lines) + "\nf " + " ".join(str(k + 1) for k in range(20000))
                                          + "\n").encode()
    out["obj-index-2e31.obj"] = (OBJ_ROOM + "f 1 2 2147483647\n").encode()
    out["obj-index-negative-huge.obj"] = (OBJ_ROOM + "f 1 2 -99999999999\n").encode()
    out["obj-index-zero.obj"] = (OBJ_ROOM + "f 0 1 2\n").encode()
    out["obj-vertex-nan.obj"] = OBJ_ROOM.replace("v 0 0 0", "v nan 0 0").encode()
    out["obj-vertex-inf.obj"] = OBJ_ROOM.replace("v 0 0 0", "v inf 0 0").encode()
    out["obj-vertex-1e300.obj"] = OBJ_ROOM.replace("v 0 0 0", "v 1e300 0 0").encode()
    out["obj-vertex-1e400.obj"] = OBJ_ROOM.replace("v 0 0 0", "v 1e400 0 0").encode()
    out["obj-vertex-hex.obj"] = OBJ_ROOM.replace("v 0 0 0", "v 0x1p9 0 0").encode()
    out["obj-line-10mb.obj"] = (OBJ_ROOM + "# " + "z" * (10 << 20) + "\n").encode()
    out["obj-no-newline-at-end.obj"] = OBJ_ROOM.rstrip("\n").encode()
    out["obj-crlf.obj"] = OBJ_ROOM.replace("\n", "\r\n").encode()
    out["obj-nul-bytes.obj"] = OBJ_ROOM.replace("f 1 2 3 4", "f 1\x00 2 3 4").encode()
    out["obj-texcoord-refs-missing.obj"] = OBJ_ROOM.replace("f 1 2 3 4", "f 1/9/9 2/9/9 3/9/9").encode()
    out["obj-usemtl-unknown.obj"] = ("usemtl nowhere\n" + OBJ_ROOM).encode()
    out["obj-mtllib-missing.obj"] = ("mtllib nothere.mtl\n" + OBJ_ROOM).encode()
    out["obj-mtllib-dot.obj"] = ("mtllib .\n" + OBJ_ROOM).encode()
    out["obj-mtllib-etc-passwd.obj"] = ("mtllib /etc/passwd\n" + OBJ_ROOM).encode()
    out["obj-mtllib-parent.obj"] = ("mtllib ../../../../etc/hostname\n" + OBJ_ROOM).encode()
    return out


def name_inputs():
    """Names a scene can carry (node, mesh, material, cell, portal, camera) made of HTML and bad bytes."""
    out = {}
    hostile = {
        "img-onerror": "<img src=x onerror=alert(1)>",
        "comment-script": "<!--<script>",
        "close-script": "</script><script>alert(1)</script>",
        "quotes": "\"'`${alert(1)}`",
        "ansi-escape": "\x1b[2J\x1b[31mred",
        "newlines": "a\nb\rc\u2028d",
        "nul": "a\u0000b",
        "rtl-override": "\u202egnp.exe",
        "emoji": "\U0001F525" * 50,
        "long-4096": "L" * 4096,
    }
    for label, name in hostile.items():
        def edit(d, g, name=name):
            d["nodes"][0]["name"] = "cell:" + name
            d["nodes"][1]["name"] = name
            d["meshes"][0]["name"] = name
            d["materials"][0]["name"] = name + "wall"
            d["materials"][1]["name"] = name + "lamp"
            camera(d, {"yfov": 1.0, "znear": 0.01})
            d["nodes"][-1]["name"] = name
            d["cameras"][0]["name"] = name
        out["names-%s.glb" % label] = doc_edit(edit)
    # Invalid UTF-8 cannot pass through json.dumps: patch the bytes in after.
    for label, raw in [("invalid-utf8", b"\xff\xfe"), ("overlong-utf8", b"\xc0\xaf"), ("lone-surrogate", b"\xed\xa0\x80")]:
        data = doc_edit(lambda d, g: d["nodes"][0].update(name="cell:QQ"))
        out["names-%s.glb" % label] = data.replace(b"QQ", raw)
    out["names-html-file-<b>.glb"] = room().glb()
    out["names-space and 'quote'.glb"] = room().glb()
    return out


def image_inputs():
    out = {}
    for label, data in images().items():
        mime = "image/jpeg" if label.startswith("jpeg") else "image/png"
        out["texture-%s.glb" % label] = textured(data, mime=mime)
    out["texture-png-mime-says-jpeg.glb"] = textured(png(4, 4), mime="image/jpeg")
    return out


def all_inputs(cpgi, work):
    """name -> bytes, or name -> callable(path) for inputs that are not plain files."""
    inputs = {}
    inputs.update(earlier_hostile_files())
    seed = os.path.join(work, "seed1.glb")
    if not os.path.exists(seed):
        subprocess.run([cpgi, "generate", "seed1", "-o", seed], check=True, capture_output=True)
    with open(seed, "rb") as f:
        seed1 = f.read()
    inputs["seed1.glb"] = seed1
    inputs.update(truncations("seed1.glb", seed1, [1, 11, 12, 19, 20, 28, 200, len(seed1) // 2, len(seed1) - 1]))
    room_gltf = Gltf().room().gltf()
    inputs.update(truncations("room.gltf", room_gltf, [1, 30, len(room_gltf) // 2, len(room_gltf) - 2]))
    inputs.update(truncations("room.obj", OBJ_ROOM.encode(), [5, 50, 120]))
    inputs["room.obj"] = (OBJ_ROOM + OBJ_LAMP).encode()
    inputs.update(numeric_inputs())
    inputs.update(structural_inputs())
    inputs.update(empty_and_degenerate())
    inputs.update(enormous_inputs())
    inputs.update(name_inputs())
    inputs.update(image_inputs())
    inputs.update(special_files())
    return inputs


def special_files():
    """Inputs that are not regular files, or that point at ones the scene may not read."""
    def fifo(path):
        os.mkfifo(path)

    def directory(path):
        os.mkdir(path)

    def unreadable(path):
        with open(path, "wb") as f:
            f.write(room().glb())
        os.chmod(path, 0)

    def symlink_to(target):
        return lambda path: os.symlink(target, path)

    def missing(path):
        pass

    def beside(files, main):
        """PATH gets MAIN, and the files beside it (name -> bytes or a callable) are made too."""
        def make(path):
            folder = os.path.dirname(path)
            for name, data in files.items():
                other = os.path.join(folder, name)
                if callable(data):
                    data(other)
                else:
                    with open(other, "wb") as f:
                        f.write(data)
            with open(path, "wb") as f:
                f.write(main)
        return make

    mtl = b"newmtl lamp\nKe 50 50 50\nKd 0.8 0.8 0.8\n"
    obj_with = (("mtllib room.mtl\n" + OBJ_ROOM + OBJ_LAMP).encode())
    return {
        "fifo.glb": fifo, "fifo.obj": fifo, "directory.glb": directory, "directory.gltf": directory,
        "unreadable.glb": unreadable, "symlink-dev-zero.glb": symlink_to("/dev/zero"),
        "symlink-dev-null.gltf": symlink_to("/dev/null"), "symlink-loop.glb": lambda p: os.symlink(p, p),
        "symlink-dangling.glb": symlink_to("/nonexistent/x.glb"), "missing.glb": missing,
        "no-extension": lambda p: open(p, "wb").write(room().glb()),
        "obj-inside.glb": lambda p: open(p, "wb").write((OBJ_ROOM + OBJ_LAMP).encode()),
        "glb-inside.obj": lambda p: open(p, "wb").write(room().glb()),
        "obj-with-mtl.obj": beside({"room.mtl": mtl}, obj_with),
        "obj-mtl-fifo.obj": beside({"room.mtl": fifo}, obj_with),
        "obj-mtl-directory.obj": beside({"room.mtl": directory}, obj_with),
        "obj-mtl-symlink-dev-zero.obj": beside({"room.mtl": symlink_to("/dev/zero")}, obj_with),
        "obj-mtl-binary.obj": beside({"room.mtl": bytes(range(256)) * 100}, obj_with),
        "obj-mtl-map-kd-fifo.obj": beside({"room.mtl": b"newmtl lamp\nKe 5 5 5\nmap_Kd tex.png\n", "tex.png": fifo},
                                          obj_with),
        "gltf-buffer-fifo.gltf": beside({"buf.bin": fifo}, json.dumps({"asset": {"version": "2.0"}, "buffers": [
            {"byteLength": 36, "uri": "buf.bin"}]}).encode()),
        "gltf-image-fifo.glb": beside({"tex.png": fifo}, textured(None, uri="tex.png")),
        "gltf-image-directory.glb": beside({"tex.png": directory}, textured(None, uri="tex.png")),
        "gltf-image-symlink-dev-zero.glb": beside({"tex.png": symlink_to("/dev/zero")}, textured(None, uri="tex.png")),
        "gltf-image-uri-percent.glb": beside({"a b.png": png(2, 2)}, textured(None, uri="a%20b.png")),
        "gltf-image-uri-percent-bad.glb": textured(None, uri="a%zzb.png"),
    }


# ---------------------------------------------------------------------------------------------- running

def run_one(cpgi, command, scene, out_dir, limits):
    """Runs one command; returns (exit status or minus the signal, killed for a hang, CPU seconds, wall
    seconds, peak RSS in MB, stderr)."""
    if command == "info":
        argv = [cpgi, "info", scene]
    elif command == "decompose":
        argv = [cpgi, "decompose", scene, "-o", out_dir, "--max-memory", "2G"]
    else:
        argv = [cpgi, "bake", scene, "-o", out_dir, "--time-limit", "10", "--texels-per-quad", "2", "--unshot",
                "0.3", "--max-memory", "2G", "--max-shots", "200"]
    with open(os.path.join(os.path.dirname(out_dir), "stderr-" + command), "w+b") as err_file:
        start = time.monotonic()
        proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err_file,
                                start_new_session=True)
        killed = False
        while True:  # wait4 gives this child's own CPU time and peak RSS
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - start > limits.wall_seconds and not killed:
                os.killpg(proc.pid, signal.SIGKILL)
                killed = True
            time.sleep(0.02)
        proc.returncode = 0  # reaped above; keeps Popen from waiting again
        wall = time.monotonic() - start
        err_file.seek(0)
        err = err_file.read().decode("utf-8", "backslashreplace")
    code = -os.WTERMSIG(status) if os.WIFSIGNALED(status) else os.WEXITSTATUS(status)
    return code, killed, usage.ru_utime + usage.ru_stime, wall, usage.ru_maxrss / 1024, err


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cpgi")
    parser.add_argument("--work", default="/tmp/hostile_round")
    parser.add_argument("--cpu-seconds", type=float, default=20)
    parser.add_argument("--wall-seconds", type=float, default=120)
    parser.add_argument("--rss-mb", type=float, default=2048)
    parser.add_argument("--only", default="")
    parser.add_argument("--commands", default="info,decompose,bake")
    parser.add_argument("--list", action="store_true")
    limits = parser.parse_args()
    cpgi = os.path.abspath(limits.cpgi)
    shutil.rmtree(limits.work, ignore_errors=True)
    os.makedirs(limits.work)
    inputs = all_inputs(cpgi, limits.work)
    if limits.list:
        print("\n".join(sorted(inputs)))
        print("%d inputs" % len(inputs), file=sys.stderr)
        return 0
    rows, failures = 0, 0
    totals, worst, peaks = {}, {}, {}
    for name in sorted(inputs):
        if limits.only not in name:
            continue
        folder = os.path.join(limits.work, "in-%d" % rows)
        os.makedirs(folder)
        scene = os.path.join(folder, name)
        data = inputs[name]
        if callable(data):
            data(scene)
        else:
            with open(scene, "wb") as f:
                f.write(data)
        rows += 1
        for command in limits.commands.split(","):
            out_dir = os.path.join(folder, "out-" + command)
            # Item 10: a file of the user's in the output folder must stay, whatever the run does.
            os.makedirs(out_dir)
            with open(os.path.join(out_dir, "view-holiday.png"), "wb") as f:
                f.write(b"the user's own")
            status, killed, cpu, wall, rss_mb, err = run_one(cpgi, command, scene, out_dir, limits)
            problems = check(status, killed, cpu, rss_mb, err, name, out_dir, limits)
            with open(os.path.join(limits.work, "runs.tsv"), "a") as table:
                table.write("%s\t%s\t%s\t%.2f\t%.2f\t%.0f\t%s\n" % (name, command, "killed" if killed else status, cpu,
                                                               wall, rss_mb, "; ".join(problems)))
            key = (command, "killed" if killed else str(status))
            totals[key] = totals.get(key, 0) + 1
            peaks[command] = max(peaks.get(command, 0), rss_mb)
            worst[command] = max(worst.get(command, (0, 0, 0, "")), (cpu, wall, rss_mb, name))
            if problems:
                failures += 1
                line = err.strip().splitlines()[-1] if err.strip() else ""
                print("FAIL %-44s %-9s exit %-4s %5.1f s cpu %5.1f s wall  %s | %s" % (
                    name, command, status, cpu, wall, "; ".join(problems), line[:200]), flush=True)
    print("%d inputs, %d runs, %d failed checks" % (rows, rows * len(limits.commands.split(",")), failures))
    for (command, status), count in sorted(totals.items()):
        print("  %-9s exit %-6s %d runs" % (command, status, count))
    for command, (cpu, wall, rss, name) in worst.items():
        print("  %-9s most CPU: %.1f s (%.1f s wall, %.0f MB): %s" % (command, cpu, wall, rss, name))
    for command in limits.commands.split(","):
        print("  %-9s largest peak RSS: %.0f MB" % (command, peaks.get(command, 0)))
    return 1 if failures else 0


def check(status, killed, cpu, rss_mb, err, name, out_dir, limits):
    problems = []
    if killed:
        problems.append("killed after %g s wall (a hang)" % limits.wall_seconds)
    elif status < 0:
        problems.append("ended by signal %d" % -status)
    elif status not in (0, 1):
        problems.append("exit status %d" % status)
    if "AddressSanitizer" in err or "runtime error:" in err or "LeakSanitizer" in err:
        problems.append("sanitizer report")
    if cpu > limits.cpu_seconds:
        problems.append("%.1f CPU s > %g" % (cpu, limits.cpu_seconds))
    if rss_mb > limits.rss_mb:
        problems.append("peak RSS %.0f MB > %g" % (rss_mb, limits.rss_mb))
    if status == 1:
        # The error is the last line; decompose prints the loader's warnings as `cpgi: FILE: ...` lines too.
        lines = [l for l in err.splitlines() if l.strip() and not l.startswith("progress:")]
        error = lines[-1] if lines else ""
        base = os.path.basename(name)
        if not error.startswith("cpgi: "):
            problems.append("no 'cpgi: ' error line at the end")
        elif error.startswith("cpgi: --"):
            pass  # a limit refused up front names the option that sets it (--max-memory, --voxel)
        elif base not in error and base.encode("unicode_escape").decode() not in error:
            problems.append("the error line does not name the input")
        left = sorted(os.listdir(out_dir))
        if left != ["view-holiday.png"]:
            problems.append("output folder holds %s" % ", ".join(left[:5]))
    if not os.path.exists(os.path.join(out_dir, "view-holiday.png")):
        problems.append("the user's view-holiday.png was deleted")
    return problems


if __name__ == "__main__":
    sys.exit(main())
