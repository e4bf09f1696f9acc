// The files every lightmap producer writes (design.md §3), in one place so that `cpgi bake` and
// `cpgi reference` stay comparable file for file: lightmap.exr, lightmap.png, the engine's lightmap
// (lightmap_irradiance.exr, lightmap_irradiance_rgbm.png), baked.glb, preview.glb and the view pictures.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/image_io.h"
#include "core/output_dir.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/views.h"

namespace cpgi {

/// Where the engine's lightmap lies (`--uv`): cpgi's own atlas, the scene's TEXCOORD_1 (an artist's
/// lightmap coordinates; the light resampled into them), or the scene's when they pass the checks of
/// radiosity/lightmap/scene_uv.h, else cpgi's own with a warning naming the meshes.
enum class UvSource { Own, Scene, Auto };

/// How the files for engines are written.
struct EngineOutputParams {
  bool keepHelpers = false;  ///< baked.glb keeps portal: quads, cellvolume: meshes and punctual lamps
  UvSource uv = UvSource::Auto;
  /// Also the directional lightmap (directional_lightmap.h): lightmap_sh_l0.exr, _l1y, _l1z, _l1x. Off by
  /// default: its gather costs about as much as the lamps' first shot (bench/RESULTS.md, "Directional
  /// lightmaps") and 12 floats a texel.
  bool directional = false;
  int directionalRays = 256;  ///< directions per texel of its gather (GatherParams::rays)
  /// Also light probes through the rooms (radiosity/bake/light_probes.h): probes.json and baked.glb's
  /// extras.cpgi_lightmap.probes. Off by default.
  bool probes = false;
  float probeSpacing = 1.0f;  ///< metres between probes (ProbeParams::spacing)
  /// A lightmap per object (radiosity/lightmap/object_lightmaps.h) as well: lightmap-OBJECT.exr and .png
  /// (RGBM), and baked.glb's TEXCOORD_1 and materials on them. The scene's lightmap_irradiance files then
  /// stay on cpgi's own atlas (preview.glb's TEXCOORD_1).
  bool perObject = false;
};

struct LightmapOutputs {
  float exposure = 1.0f;                  ///< used for the glb's texture (viewExposure)
  std::vector<std::string> views;         ///< camera names, files view-NAME.exr / .png
  std::vector<std::string> skippedViews;  ///< cameras not rendered: the deadline came first
  /// Outputs left out because the deadline came during their gather ("directional"): a part of one would
  /// light some surfaces with directions and others without.
  std::vector<std::string> skippedOutputs;
  nlohmann::json engine;  ///< report.json's "engine_lightmap": the engine files and ranges
};

/// Dilates `radiosity` (per atlas texel, W/m², padding ignored) and stages through `out`:
///  - lightmap.exr: R, G, B = radiosity B; channel "area" (m² per texel, 0 on padding) and any `extra`;
///  - lightmap.png: the lightmap as radiance B/π at `exposure`, as preview.glb shows it;
///  - lightmap_irradiance.exr (half float) and lightmap_irradiance_rgbm.png: the light arriving, E =
///    (B − Le)/ρ in W/m² (radiosity/lightmap/engine_lightmap.h), on the atlas `engine.uv` chooses;
///  - with engine.directional, lightmap_sh_l0.exr, lightmap_sh_l1y.exr, lightmap_sh_l1z.exr and
///    lightmap_sh_l1x.exr (half float): the L1 SH coefficients L00, L1−1, L10, L11 of the light arriving
///    (directional_lightmap.h), on the same atlas as the irradiance;
///  - baked.glb, for engines: the scene's own materials, textures and TEXCOORD_0, the irradiance on
///    TEXCOORD_1 (core/scene_io.h, GltfWriteOptions::forEngines), no helpers or lamps unless kept;
///  - with `probes` (lightProbesJson, not null), baked.glb's extras.cpgi_lightmap.probes holds them;
///  - preview.glb, for viewers: the scene (with `cells` and their portals, when there are any) with the
///    atlas as TEXCOORD_1 and the lightmap (B/π at `exposure`) as an unlit texture;
///  - with engine.perObject, lightmap-OBJECT.exr (half float) and lightmap-OBJECT.png (RGBM at the scene's
///    range) per object, and lightmap-OBJECT-sh_l0.exr … _l1x.exr with engine.directional; baked.glb
///    then references each object's own;
///  - view-NAME.exr / .png for every camera (renderViews), those `viewsDeadline` leaves time for and the
///    first `leastViews` whatever it says. The
///    directional gather stops at `viewsDeadline` too, and its files are then not written (said in one
///    warning and in skippedOutputs).
/// Nothing appears in the folder before out.commit(). Throws InputError for `--uv scene` on a scene whose
/// TEXCOORD_1 fails its checks.
LightmapOutputs writeLightmapOutputs(
    OutputDir& out, const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
    std::vector<glm::vec3> radiosity, const std::vector<ExrChannel>& extra, Context& ctx,
    const ViewParams& viewParams = {},
    std::chrono::steady_clock::time_point viewsDeadline = std::chrono::steady_clock::time_point::max(),
    const EngineOutputParams& engine = {}, const nlohmann::json& probes = {}, size_t leastViews = 0);

/// With UvSource::Scene, throws InputError("--uv scene", ...) naming the meshes when the scene's TEXCOORD_1
/// fails the checks of scene_uv.h (or there is none): called before the solve, so a refusal costs no bake.
/// `perObject`: each object's TEXCOORD_1 is checked as a square of its own (object_lightmaps.h).
void requireSceneUVs(const Scene& scene, const LightmapAtlas& atlas, UvSource uv, bool perObject = false);

/// The glb a bake or reference folder shows its light with on cpgi's atlas (TEXCOORD_1) and cells:
/// DIR/preview.glb, or DIR/baked.glb in a folder written before baked.glb became the engine's (one
/// without lightmap_irradiance.exr).
std::filesystem::path previewGlb(const std::filesystem::path& dir);

}  // namespace cpgi
