// Reading scenes (glTF 2.0 .glb/.gltf, OBJ+MTL) and writing them back as glTF. Every failure is an
// InputError naming the file and the problem; nothing here prints.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/contact_cuts.h"
#include "core/scene.h"

namespace cpgi {

struct LoadedScene {
  Scene scene;
  CellGraph cells;                    ///< hand-made cells when the file has `cell:`/`portal:` nodes
  std::vector<std::string> warnings;  ///< e.g. dropped zero-area or duplicate triangles
  /// Per scene triangle, the lightmap coordinates of its corners when every triangle of the file has a
  /// TEXCOORD_1 (a baked.glb: GltfWriteOptions::lightmapUVs read back); empty otherwise.
  std::vector<std::array<glm::vec2, 3>> lightmapUVs;
  ContactCuts contactCuts;  ///< what LoadOptions::cutContacts cut
};

/// A material's light or colour set by name instead of by the file (the CLI's --emit, --albedo): a raw
/// model has no emissive surfaces, and editing the file is not what a user lighting it wants to do.
struct MaterialOverride {
  std::string material;               ///< the material's name as the file gives it (every one of that name)
  std::optional<glm::vec3> emission;  ///< W/m² per channel, replaces the file's emission
  std::optional<glm::vec3> albedo;    ///< in [0, 1] per channel, replaces the file's albedo
};

struct LoadOptions {
  /// Metres per unit of the file (the CLI's --scale): every position (triangles, portals, cell volumes,
  /// cameras, lights and their range) is multiplied by it as the scene loads. A scene not in metres is
  /// told in one warning with the likely unit and its scale (core/units.h).
  double scale = 1.0;
  /// Zero-area and duplicate triangles (real exports have a few) are dropped with one warning in
  /// LoadedScene::warnings (their count and the first one's node); strict refuses the scene instead
  /// (the CLI's --strict).
  bool strict = false;
  /// Applied in order before the materials are checked; a name no material has is an InputError("emit"
  /// or "albedo", ...) naming the file.
  std::vector<MaterialOverride> overrides = {};
  /// Files a scene refers to (glTF buffers and images, OBJ mtllib) are read only inside the scene's own
  /// folder by default, so that a downloaded scene cannot pull /etc/passwd or ~/.ssh into a result
  /// (the CLI's --allow-outside-files lifts that).
  bool allowOutsideFiles = false;
  /// The largest scene or referenced file read, checked before reading (a .glb cannot exceed 4 GiB).
  uint64_t maxFileBytes = uint64_t(2) << 30;
  /// The most triangles a scene may place (about 80 bytes each, before the atlas): a small glTF whose
  /// thousands of nodes instance one large mesh would otherwise expand into gigabytes.
  size_t maxTriangles = 10'000'000;
  /// Past this instant (bake --time-limit) the reading stops between its steps (the file parsed, each mesh,
  /// each texture image decoded, the checks after them) with InputError("time limit", ...) naming the file
  /// and how far it came: a bake whose limit passed while it read has no time left for any result.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Faces cut where other geometry runs through them and the pieces inside solids dropped
  /// (core/contact_cuts.h), so that no lightmap chart runs across a solid (the CLI's --keep-contacts turns
  /// it off). Not done on a scene whose every triangle has its own lightmap coordinates (a baked.glb).
  bool cutContacts = true;
};

/// Loads by extension (.glb, .gltf, .obj). Throws InputError for a missing, truncated or invalid file,
/// NaN/inf positions, an unsupported primitive mode, bad cell naming, degenerate triangles (with
/// strict), bad KHR_lights_punctual lights, a scene with no triangles, or a referenced file outside the
/// scene's folder (see LoadOptions).
LoadedScene loadScene(const std::string& path, const LoadOptions& options = {});

struct GltfWriteOptions {
  /// When set, triangles are grouped under `cell:NAME` nodes and portals written as `portal:A:B` quads
  /// (design.md §3), so loadScene reads the same graph back.
  const CellGraph* cells = nullptr;
  /// Per triangle, the lightmap coordinates of its three corners (TEXCOORD_1, and TEXCOORD_0 too since
  /// the scene has no other); size = triangle count.
  const std::vector<std::array<glm::vec2, 3>>* lightmapUVs = nullptr;
  /// PNG bytes of the baked lightmap. With lightmapUVs, every material becomes unlit
  /// (KHR_materials_unlit) with this texture as base colour, so any viewer shows the baked light.
  std::string lightmapPng;
  /// The glb for engines instead (issue 48): the scene's own materials, textures and TEXCOORD_0
  /// (Scene::looks; coordinates (0, 0) on triangles the file gave none), lightmapUVs as TEXCOORD_1, and
  /// lightmapPng (the irradiance, sRGB-encoded, 1 = lightmapIntensity W/m²) referenced by every material
  /// as Mozilla Hubs's MOZ_lightmap {index, texCoord 1, intensity} (three.js: material.lightMap with
  /// channel 1 and lightMapIntensity) and by the root's extras.cpgi_lightmap.
  bool forEngines = false;
  float lightmapIntensity = 1.0f;
  /// Root extras.cpgi_lightmap's other keys (the HDR files beside the glb and their ranges).
  std::string lightmapExtrasJson;
  /// The helpers (portal: quads, cellvolume: meshes) and the KHR_lights_punctual lamps, which an engine
  /// would draw, or light the baked scene with a second time; `cell:` nodes stay as names either way.
  bool keepHelpers = true;
  /// The scene's seal (Scene::seal) as a `seal:solids` mesh: decompose's cells.glb keeps it, so that the file
  /// decomposes as its source did; a bake's glbs never, since viewers would draw it over the level.
  bool keepSeal = false;
  /// With forEngines, a lightmap per object instead of lightmapPng (bake --per-object): the PNG of each
  /// (sRGB, 1 = lightmapIntensity) and its unique name (its texture's, "lightmap-OBJECT"), and per
  /// triangle the one it lies on (−1: none); lightmapUVs are then coordinates in that lightmap. Each
  /// material is written once per lightmap using it, referencing that lightmap by MOZ_lightmap and naming
  /// it in extras.cpgi_lightmap; the root's extras.cpgi_lightmap.object_textures lists them.
  std::vector<std::string> objectLightmapPngs;
  std::vector<std::string> objectLightmapNames;
  const std::vector<int>* lightmapOfTriangle = nullptr;
};

/// Writes `.glb` (binary) or `.gltf` (embedded buffers) by the extension, atomically.
void writeGltf(const std::string& path, const Scene& scene, const GltfWriteOptions& options = {});

}  // namespace cpgi
