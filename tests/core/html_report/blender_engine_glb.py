# blender -b --factory-startup --python-exit-code 1 --python blender_engine_glb.py -- ATLAS_DIR PER_OBJECT_DIR
#
# The engine glb of a bake in Blender, as docs/engines.md tells a Blender user: its glTF add-on imports
# ATLAS_DIR/baked.glb (one lightmap for the scene) and PER_OBJECT_DIR/baked.glb (the same scene baked with
# --per-object), then light_with_lightmaps() below, which docs/engines.md prints, wires each material's
# lightmap EXR on the second UV map. Checks, one line each on stderr when failed (exit 1):
#  - every mesh object has two UV maps, the second the glb's TEXCOORD_1, named as the recipe reads it;
#  - every material emits base colour x its lightmap read on that UV map: the scene's
#    lightmap_irradiance.exr, or with --per-object the EXR its object's `cpgi_lightmap` names, one lightmap
#    per object and no two objects sharing one;
#  - each polygon's irradiance read as Blender reads it (its UV map's v as imported, the EXR's pixels as
#    loaded) is positive, and the same in the per-object bake as in the atlas bake (the two layouts differ,
#    so a v read the wrong way round could not agree in both).
# Prints a JSON line of the figures.
import json
import math
import os
import sys

import numpy as np

if not hasattr(np, "bool"):  # Debian 12's Blender 3.4 glTF add-on with numpy 1.24
    np.bool = bool
import bpy  # noqa: E402

LIGHTMAP_UV = "UVMap.001"  # the add-on's name for TEXCOORD_1


def light_with_lightmaps(folder):
    """Every material emits base colour x E / pi, E its lightmap on the second UV map (docs/engines.md)."""
    images = {}

    def lightmap(name):  # one image per file, linear (the EXR holds irradiance in W/m2)
        if name not in images:
            images[name] = bpy.data.images.load(os.path.join(folder, name + ".exr"))
            images[name].colorspace_settings.name = "Non-Color"
        return images[name]

    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        bsdf = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
        out = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
        if not bsdf or not out:
            continue
        uv = nodes.new("ShaderNodeUVMap")
        uv.uv_map = LIGHTMAP_UV
        tex = nodes.new("ShaderNodeTexImage")
        # --per-object: the material's glTF extras name its object's lightmap; else the scene's
        tex.image = lightmap(mat.get("cpgi_lightmap", "lightmap_irradiance"))
        tex.extension = "EXTEND"
        links.new(uv.outputs["UV"], tex.inputs["Vector"])
        mul = nodes.new("ShaderNodeVectorMath")
        mul.operation = "MULTIPLY"
        base = bsdf.inputs["Base Color"]
        if base.is_linked:
            links.new(base.links[0].from_socket, mul.inputs[0])
        else:
            mul.inputs[0].default_value = base.default_value[:3]
        links.new(tex.outputs["Color"], mul.inputs[1])
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Strength"].default_value = 1 / math.pi
        links.new(mul.outputs["Vector"], emit.inputs["Color"])
        links.new(emit.outputs["Emission"], out.inputs["Surface"])


failures = []


def check(ok, message):
    if not ok:
        failures.append(message)


def object_key(obj):
    """An object's path of names from the root: the same in both imports of one scene."""
    names = []
    while obj:
        names.append(obj.name)
        obj = obj.parent
    return "/".join(reversed(names))


def wired_image(mat):
    """The image a material's surface emits through, checked to be read on LIGHTMAP_UV; None if not."""
    out = next((n for n in mat.node_tree.nodes if n.type == "OUTPUT_MATERIAL"), None)
    emit = out.inputs["Surface"].links[0].from_node if out and out.inputs["Surface"].is_linked else None
    if not emit or emit.type != "EMISSION" or not emit.inputs["Color"].is_linked:
        return None
    mul = emit.inputs["Color"].links[0].from_node
    tex = next((l.from_node for s in mul.inputs for l in s.links if l.from_node.type == "TEX_IMAGE"), None)
    if not tex or not tex.inputs["Vector"].is_linked:
        return None
    uv = tex.inputs["Vector"].links[0].from_node
    return tex.image if uv.type == "UVMAP" and uv.uv_map == LIGHTMAP_UV else None


def bilinear(pixels, u, v):
    """pixels[y][x][c] read at (u, v) as Blender's Image Texture node reads it (Linear, Extend)."""
    h, w = pixels.shape[:2]
    x, y = u * w - 0.5, v * h - 0.5
    x0, y0 = math.floor(x), math.floor(y)
    fx, fy = x - x0, y - y0
    at = lambda i, j: pixels[min(max(j, 0), h - 1), min(max(i, 0), w - 1), :3]  # noqa: E731
    return ((1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) + (1 - fx) * fy * at(x0, y0 + 1)
            + fx * fy * at(x0 + 1, y0 + 1))


def import_and_read(folder, label):
    """Imports folder/baked.glb, lights it, checks the wiring; the irradiance at each polygon's centre on
    LIGHTMAP_UV, by (object, polygon), and the lightmap image of each object."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.join(folder, "baked.glb"))
    light_with_lightmaps(folder)
    pixels, irradiance, lightmap_of = {}, {}, {}
    for obj in (o for o in bpy.data.objects if o.type == "MESH"):
        key, mesh = object_key(obj), obj.data
        layers = [layer.name for layer in mesh.uv_layers]
        check(len(layers) == 2 and layers[1] == LIGHTMAP_UV, f"{label}: {key}: UV maps {layers}")
        if len(layers) < 2:
            continue
        uvs = np.zeros(2 * len(mesh.loops))
        mesh.uv_layers[LIGHTMAP_UV].data.foreach_get("uv", uvs)
        uvs = uvs.reshape(-1, 2)
        for poly in mesh.polygons:
            image = wired_image(mesh.materials[poly.material_index])
            check(image is not None, f"{label}: {key}: material {mesh.materials[poly.material_index].name} "
                  f"does not emit a lightmap read on {LIGHTMAP_UV}")
            if image is None:
                continue
            lightmap_of.setdefault(key, set()).add(os.path.basename(image.filepath))
            if image.name not in pixels:
                data = np.zeros(image.size[0] * image.size[1] * 4, dtype=np.float32)
                image.pixels.foreach_get(data)
                pixels[image.name] = data.reshape(image.size[1], image.size[0], 4)
            u, v = uvs[list(poly.loop_indices)].mean(axis=0)
            irradiance[(key, poly.index)] = bilinear(pixels[image.name], u, v)
    return irradiance, lightmap_of


def main():
    atlas_dir, per_object_dir = sys.argv[sys.argv.index("--") + 1:][:2]
    atlas, atlas_maps = import_and_read(atlas_dir, "atlas")
    objects, object_maps = import_and_read(per_object_dir, "per-object")
    check(all(m == {"lightmap_irradiance.exr"} for m in atlas_maps.values()),
          f"atlas: objects read {sorted(set().union(*atlas_maps.values()))}, not lightmap_irradiance.exr alone")
    for key, maps in object_maps.items():
        check(len(maps) == 1 and next(iter(maps)).startswith("lightmap-"), f"per-object: {key} reads {sorted(maps)}")
    names = [next(iter(m)) for m in object_maps.values()]
    check(len(set(names)) == len(names), "per-object: two objects read the same lightmap")
    check(atlas.keys() == objects.keys(), "the two imports have different objects or polygons")
    worst, dark = 0.0, []
    for key in atlas.keys() & objects.keys():
        a, b = atlas[key], objects[key]
        if not (a.min() > 0 and b.min() > 0):
            dark.append(f"{key[0]}#{key[1]}")
        worst = max(worst, float(np.max(np.abs(a - b) / (np.abs(a) + 1e-3))))
    check(not dark, f"polygons reading no light (a lightmap read outside its charts): {dark[:5]}")
    check(worst < 0.01, f"per-object and atlas irradiance differ by {100 * worst:.2f} % at some polygon")
    print(json.dumps({"objects": len(object_maps), "polygons": len(atlas),
                      "per_object_lightmaps": len(set(names)), "worst_relative_difference": worst}))
    for f in failures:
        print("blender engine glb: " + f, file=sys.stderr)
    sys.exit(1 if failures else 0)


main()
