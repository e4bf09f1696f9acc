#include "radiosity/lightmap/lightmap_output.h"

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <optional>

#include "core/error.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/directional_lightmap.h"
#include "radiosity/lightmap/engine_lightmap.h"
#include "radiosity/lightmap/object_lightmaps.h"
#include "radiosity/lightmap/scene_uv.h"

namespace cpgi {
namespace {

// The engine lightmap's layout: cpgi's atlas, or the scene's TEXCOORD_1 with the light read into it.
struct EngineLayout {
  int width = 0, height = 0;
  std::vector<glm::vec3> irradiance;                 ///< dilated
  std::vector<std::array<glm::vec2, 3>> triangleUV;  ///< TEXCOORD_1 of baked.glb
  std::string source = "own";
};

// Lines of `problems` joined for one message (the first few, and how many more).
std::string joined(const std::vector<std::string>& problems) {
  std::string text;
  for (size_t i = 0; i < problems.size() && i < 4; ++i) text += (i ? "; " : "") + problems[i];
  if (problems.size() > 4) text += "; and " + std::to_string(problems.size() - 4) + " more";
  return text;
}

bool anySceneUV(const Scene& scene) {
  return std::any_of(scene.triangles.begin(), scene.triangles.end(), [&](const Triangle& t) {
    return t.uv < scene.looks.uvs.size() && scene.looks.uvs[t.uv].has(1);
  });
}

EngineLayout engineLayout(const Scene& scene, const LightmapAtlas& atlas, std::vector<glm::vec3> irradiance,
                          UvSource uv, Context& ctx) {
  EngineLayout own{atlas.width, atlas.height, std::move(irradiance), atlas.triangleUV, "own"};
  if (uv == UvSource::Own || !anySceneUV(scene)) return own;
  requireSceneUVs(scene, atlas, uv);
  const int size = sceneUvSize(scene, atlas.validTexels());
  const SceneUvCheck check = checkSceneUVs(scene, size);
  if (!check.usable()) {
    ctx.warn("engine lightmap: the scene's TEXCOORD_1 is not used, cpgi's own atlas is (" +
             joined(check.refusals) + "); --uv own says so without this warning");
    return own;
  }
  for (const std::string& w : check.warnings)
    ctx.warn("engine lightmap: " + w + " (the light there is blurred)");
  EngineLayout layout{size, size, {}, {}, "scene"};
  layout.irradiance = resampleToSceneUVs(scene, atlas, own.irradiance, size, layout.triangleUV);
  return layout;
}

// The per-object layout (`--per-object`): cpgi's charts copied, or each object's own TEXCOORD_1 square
// when `uv` takes the scene's and every object's passes the checks (else a warning, or a refusal with
// UvSource::Scene).
ObjectLightmaps objectLayout(const Scene& scene, const LightmapAtlas& atlas, UvSource uv, Context& ctx) {
  if (uv == UvSource::Own || !anySceneUV(scene)) return layOutObjectLightmaps(scene, atlas);
  std::vector<std::string> refusals, warnings;
  ObjectLightmaps layout = layOutObjectSceneUVs(scene, atlas, refusals, warnings);
  if (!refusals.empty()) {
    if (uv == UvSource::Scene)
      throw InputError("--uv scene", "an object's TEXCOORD_1 cannot hold its lightmap: " + joined(refusals));
    ctx.warn("engine lightmap: the objects' TEXCOORD_1 are not used, cpgi's own charts are (" +
             joined(refusals) + "); --uv own says so without this warning");
    return layOutObjectLightmaps(scene, atlas);
  }
  for (const std::string& w : warnings) ctx.warn("engine lightmap: " + w + " (the light there is blurred)");
  return layout;
}

// The directional lightmap's files, one half-float EXR per L1 SH coefficient on the engine lightmap's
// layout (and on each object's, with `objects`); returns report.json's "directional" entry. A gather the
// deadline stopped writes nothing: its entry says so, and `skipped` gets "directional".
const std::array<const char*, 4> kShFiles = {"lightmap_sh_l0.exr", "lightmap_sh_l1y.exr",
                                             "lightmap_sh_l1z.exr", "lightmap_sh_l1x.exr"};
const std::array<const char*, 4> kShSuffixes = {"-sh_l0.exr", "-sh_l1y.exr", "-sh_l1z.exr", "-sh_l1x.exr"};

nlohmann::json writeDirectionalFiles(OutputDir& out, const Scene& scene, const LightmapAtlas& atlas,
                                     const std::vector<glm::vec3>& radiosity,
                                     const std::vector<glm::vec3>& irradiance, const EngineLayout& layout,
                                     const ObjectLightmaps* objects, const EngineOutputParams& params,
                                     std::chrono::steady_clock::time_point deadline,
                                     std::vector<std::string>& skipped, Context& ctx) {
  GatherParams gather;
  gather.rays = params.directionalRays;
  DirectionalLightmap map =
      gatherDirectionalLightmap(scene, atlas, radiosity, irradiance, gather, ctx, deadline);
  nlohmann::json report = {{"rays_per_texel", gather.rays},
                           {"emitter_samples_per_texel", gather.emitterSamples},
                           {"texels", map.texels},
                           {"rays", map.rays},
                           {"seconds", map.seconds}};
  if (!map.complete) {
    const std::string why = "the time limit came after " + std::to_string(map.texels) + " of " +
                            std::to_string(atlas.validTexels()) + " texels of its gather";
    ctx.warn("directional lightmap: " + why +
             "; lightmap_sh_*.exr are not written (a part would light some "
             "surfaces with directions and the rest without)");
    skipped.push_back("directional");
    report["skipped"] = why;
    return report;
  }
  std::vector<nlohmann::json> objectFiles(objects ? objects->objects.size() : 0, nlohmann::json::array());
  for (size_t k = 0; k < 4; ++k) {
    std::vector<glm::vec3>& values = map.sh[k];
    dilate(atlas, values, 2, DilatedValues::Signed);
    for (size_t o = 0; o < objectFiles.size(); ++o) {
      const ObjectLightmap& object = objects->objects[o];
      const std::string file = object.fileStem + kShSuffixes[k];
      writeExr(out.file(file).string(),
               ImageRGB{object.width, object.height, objectImage(scene, atlas, *objects, o, values)}, {},
               ExrPrecision::Half);
      objectFiles[o].push_back(file);
    }
    if (layout.source == "scene") {
      std::vector<std::array<glm::vec2, 3>> uvs;
      values = resampleToSceneUVs(scene, atlas, values, layout.width, uvs);
    }
    writeExr(out.file(kShFiles[k]).string(), ImageRGB{layout.width, layout.height, values}, {},
             ExrPrecision::Half);
  }
  report["files"] = kShFiles;
  report["convention"] =
      "L1 SH of radiance, basis and order of Godot's LightmapGI and Unity's SphericalHarmonicsL2: L00, L1-1 "
      "(y), L10 (z), L11 (x), scene axes; (L11, L1-1, L10) / 0.488603 · n_surface = irradiance";
  report["undirected_channels"] = map.undirected;
  if (objects) report["object_files"] = objectFiles;
  return report;
}

// Each object's lightmap files (lightmap-OBJECT.exr, its RGBM .png at the scene's range) from the dilated
// irradiance on cpgi's atlas, and the PNGs baked.glb embeds (sRGB, 1 = range.ldrScale); returns
// report.json's "objects".
nlohmann::json writeObjectFiles(OutputDir& out, const Scene& scene, const LightmapAtlas& atlas,
                                const ObjectLightmaps& objects, const std::vector<glm::vec3>& irradiance,
                                const LightmapRange& range, float rgbmRange,
                                std::vector<std::string>& glbPngs, std::vector<std::string>& names) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t k = 0; k < objects.objects.size(); ++k) {
    const ObjectLightmap& o = objects.objects[k];
    const ImageRGB image{o.width, o.height, objectImage(scene, atlas, objects, k, irradiance)};
    writeExr(out.file(o.fileStem + ".exr").string(), image, {}, ExrPrecision::Half);
    const RgbmImage rgbm = encodeRgbm(image.width, image.height, image.pixels, rgbmRange);
    writeFileAtomically(out.file(o.fileStem + ".png"), encodePng8(rgbm.width, rgbm.height, 4, rgbm.rgba));
    glbPngs.push_back(encodePng(image, 1.0f / range.ldrScale));
    names.push_back(o.fileStem);  // unique, where two nodes share a path
    list.push_back({{"object", o.name},
                    {"lightmap", o.fileStem},
                    {"exr", o.fileStem + ".exr"},
                    {"rgbm_png", o.fileStem + ".png"},
                    {"width", o.width},
                    {"height", o.height},
                    {"texels", o.validTexels},
                    {"triangles", o.triangles.size()}});
  }
  return list;
}

// The engine's lightmap files (lightmap_irradiance.exr, its RGBM PNG, per object with params.perObject) and
// baked.glb; returns report.json's "engine_lightmap".
nlohmann::json writeEngineFiles(OutputDir& out, const Scene& scene, const CellGraph& cells,
                                const LightmapAtlas& atlas, const std::vector<glm::vec3>& radiosity,
                                const EngineOutputParams& params, const nlohmann::json& probes,
                                std::chrono::steady_clock::time_point deadline,
                                std::vector<std::string>& skipped, Context& ctx) {
  size_t unknown = 0;
  std::vector<glm::vec3> irradiance = irradianceFromRadiosity(atlas, radiosity, &unknown);
  const LightmapRange range = lightmapRange(atlas, irradiance);
  std::vector<glm::vec3> undilated = params.directional ? irradiance : std::vector<glm::vec3>{};
  dilate(atlas, irradiance);
  // Per object, the objects' files follow the scene's UVs and the scene's lightmap stays on cpgi's atlas.
  std::optional<ObjectLightmaps> objects;
  if (params.perObject) objects = objectLayout(scene, atlas, params.uv, ctx);
  const EngineLayout layout =
      engineLayout(scene, atlas, std::move(irradiance), params.perObject ? UvSource::Own : params.uv, ctx);
  const ImageRGB image{layout.width, layout.height, layout.irradiance};
  writeExr(out.file("lightmap_irradiance.exr").string(), image, {}, ExrPrecision::Half);
  const RgbmImage rgbm = encodeRgbm(image.width, image.height, image.pixels, range.rgbmRange);
  writeFileAtomically(out.file("lightmap_irradiance_rgbm.png"),
                      encodePng8(rgbm.width, rgbm.height, 4, rgbm.rgba));

  nlohmann::json report = {{"irradiance_exr", "lightmap_irradiance.exr"},
                           {"rgbm_png", "lightmap_irradiance_rgbm.png"},
                           {"rgbm_range", rgbm.range},
                           {"rgbm_clipped_area_fraction", range.rgbmClippedArea},
                           {"max_irradiance", range.max},
                           {"half_overflow", range.max > 65504.0f},
                           {"unknown_irradiance_texels", unknown},
                           {"glb", "baked.glb"},
                           {"glb_lightmap_intensity", range.ldrScale},
                           {"glb_clipped_area_fraction", range.clippedArea},
                           {"preview_glb", "preview.glb"},
                           {"helpers_kept", params.keepHelpers},
                           {"uv", layout.source},
                           {"width", layout.width},
                           {"height", layout.height}};
  nlohmann::json extras = {{"irradiance_exr", "lightmap_irradiance.exr"},
                           {"rgbm_png", "lightmap_irradiance_rgbm.png"},
                           {"rgbm_range", rgbm.range}};
  if (params.directional) {
    report["directional"] =
        writeDirectionalFiles(out, scene, atlas, radiosity, undilated, layout, objects ? &*objects : nullptr,
                              params, deadline, skipped, ctx);
    if (report["directional"].contains("files"))
      extras["directional_sh"] = {{"files", report["directional"]["files"]},
                                  {"convention", report["directional"]["convention"]}};
  }
  if (!probes.is_null()) extras["probes"] = probes;
  GltfWriteOptions gltf;
  gltf.forEngines = true;
  gltf.keepHelpers = params.keepHelpers;
  gltf.lightmapUVs = &layout.triangleUV;
  gltf.cells = cells.empty() ? nullptr : &cells;
  gltf.lightmapIntensity = range.ldrScale;
  if (objects) {
    report["objects"] = writeObjectFiles(out, scene, atlas, *objects, layout.irradiance, range, rgbm.range,
                                         gltf.objectLightmapPngs, gltf.objectLightmapNames);
    report["objects_uv"] = objects->sceneUVs ? "scene" : "own";
    extras["objects"] = report["objects"];
    gltf.lightmapUVs = &objects->triangleUV;
    gltf.lightmapOfTriangle = &objects->objectOfTriangle;
  } else {
    gltf.lightmapPng = encodePng(image, 1.0f / range.ldrScale);
  }
  gltf.lightmapExtrasJson = extras.dump();
  writeGltf(out.file("baked.glb").string(), scene, gltf);
  return report;
}

}  // namespace

void requireSceneUVs(const Scene& scene, const LightmapAtlas& atlas, UvSource uv, bool perObject) {
  if (uv != UvSource::Scene) return;
  if (!anySceneUV(scene)) throw InputError("--uv scene", "the scene has no TEXCOORD_1 on any triangle");
  if (perObject) {
    std::vector<std::string> refusals, warnings;
    layOutObjectSceneUVs(scene, atlas, refusals, warnings);
    if (!refusals.empty())
      throw InputError("--uv scene", "an object's TEXCOORD_1 cannot hold its lightmap: " + joined(refusals));
    return;
  }
  const SceneUvCheck check = checkSceneUVs(scene, sceneUvSize(scene, atlas.validTexels()));
  if (!check.usable())
    throw InputError("--uv scene",
                     "the scene's TEXCOORD_1 cannot hold a lightmap: " + joined(check.refusals));
}

std::filesystem::path previewGlb(const std::filesystem::path& dir) {
  // A folder from before has no engine files, and its baked.glb is the preview.
  std::error_code ec;
  const bool before = !std::filesystem::exists(dir / "lightmap_irradiance.exr", ec) &&
                      std::filesystem::exists(dir / "baked.glb", ec);
  return before ? dir / "baked.glb" : dir / "preview.glb";
}

LightmapOutputs writeLightmapOutputs(OutputDir& out, const Scene& scene, const CellGraph& cells,
                                     const LightmapAtlas& atlas, std::vector<glm::vec3> radiosity,
                                     const std::vector<ExrChannel>& extra, Context& ctx,
                                     const ViewParams& viewParams,
                                     std::chrono::steady_clock::time_point viewsDeadline,
                                     const EngineOutputParams& engine, const nlohmann::json& probes,
                                     size_t leastViews) {
  LightmapOutputs result;
  result.engine = writeEngineFiles(out, scene, cells, atlas, radiosity, engine, probes, viewsDeadline,
                                   result.skippedOutputs, ctx);
  dilate(atlas, radiosity);
  const ImageRGB image{atlas.width, atlas.height, radiosity};
  std::vector<ExrChannel> channels{{"area", atlas.area}};
  channels.insert(channels.end(), extra.begin(), extra.end());
  writeExr(out.file("lightmap.exr").string(), image, channels);

  result.exposure = viewParams.exposure > 0.0f ? viewParams.exposure : viewExposure(atlas, radiosity);
  GltfWriteOptions gltf;
  gltf.lightmapUVs = &atlas.triangleUV;
  // Keep the cells and portals, so the preview still loads with its graph (cpgi view, compare-light).
  gltf.cells = cells.empty() ? nullptr : &cells;
  gltf.lightmapPng = encodePng(image, result.exposure / std::numbers::pi_v<float>);
  writeFileAtomically(out.file("lightmap.png"), gltf.lightmapPng);
  // A staged name keeps its extension, by which writeGltf picks the format; a write error names the file
  // as the user knows it (DIR/preview.glb).
  writeGltf(out.file("preview.glb").string(), scene, gltf);

  RenderedViews views =
      renderViews(scene, cells, atlas, radiosity, out, ctx, viewParams, viewsDeadline, leastViews);
  result.views = std::move(views.written);
  result.skippedViews = std::move(views.skipped);
  return result;
}

}  // namespace cpgi
