#include "apps/compare_light_resample.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/context.h"
#include "core/error.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/lightmap/lightmap_sampling.h"

namespace cpgi::cli {

namespace {

namespace fs = std::filesystem;

// The atlas options a bake or reference folder records: report.json's "atlas" (full outputs) or its top
// level (a sparse reference).
AtlasParams recordedAtlasParams(const std::string& dir) {
  const fs::path path = fs::path(dir) / "report.json";
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in, nullptr, false);
  if (!in.is_open() || report.is_discarded() || !report.is_object())
    throw InputError(path.string(), "missing or not JSON (not a bake or reference output folder?)");
  const nlohmann::json& atlas = report.contains("atlas") ? report["atlas"] : report;
  const nlohmann::json perQuad = atlas.value("texels_per_quad", nlohmann::json()),
                       density = atlas.value("density", nlohmann::json());
  if (density == "auto")
    throw InputError(path.string(),
                     "is a bake at --density auto, whose atlas cannot be rebuilt; give as B a "
                     "reference or bake at a fixed --density or --texels-per-quad");
  if (!perQuad.is_number() || !density.is_number())
    throw InputError(path.string(), "does not record its atlas (texels_per_quad, density)");
  AtlasParams params;
  params.texelsPerQuad = perQuad.get<int>();
  if (params.texelsPerQuad <= 0) params.density = density.get<float>();
  return params;
}

}  // namespace

LightmapAtlas rebuildReferenceAtlas(const Scene& scene, const std::string& scenePath, const std::string& bDir,
                                    const std::vector<float>& bArea, int bWidth, int bHeight) {
  Context ctx;
  LightmapAtlas atlas = buildAtlas(scene, findQuads(scene), recordedAtlasParams(bDir), ctx);
  bool same = atlas.width == bWidth && atlas.height == bHeight && atlas.area.size() == bArea.size();
  for (size_t i = 0; same && i < bArea.size(); ++i)
    same = std::abs(atlas.area[i] - bArea[i]) <= 1e-4f * std::max(atlas.area[i], bArea[i]);
  if (!same)
    throw InputError(scenePath, "does not give " + bDir +
                                    "'s atlas with the options its report.json records (another scene?)");
  return atlas;
}

ImageRGB sampleOnReferenceAtlas(const std::string& scenePath, const std::string& aDir, const ImageRGB& aImage,
                                const std::string& bDir, const std::vector<float>& bArea, int bWidth,
                                int bHeight, std::vector<char>* unreadTexels, const LoadOptions& load) {
  const LoadedScene scene = loadScene(scenePath, load);
  const LightmapAtlas atlas = rebuildReferenceAtlas(scene.scene, scenePath, bDir, bArea, bWidth, bHeight);

  const fs::path glb = previewGlb(aDir);
  if (!fs::is_regular_file(glb))
    throw InputError(glb.string(),
                     "no such file (A must be a bake or a full reference to be read at B's texels)");
  const LoadedScene baked = loadScene(glb.string(), load);
  if (baked.lightmapUVs.size() != baked.scene.triangles.size())
    throw InputError(glb.string(), "has no lightmap coordinates (TEXCOORD_1) on every triangle");
  const std::vector<int32_t> source = matchTriangles(scene.scene, baked.scene);
  size_t missing = 0;
  ImageRGB out{bWidth, bHeight, {}};
  out.pixels = sampleAtTexels(atlas, scene.scene, source, baked.lightmapUVs, aImage.width, aImage.height,
                              aImage.pixels, &missing);
  std::vector<char> unread;
  if (missing > 0)
    missing = sampleOnSplitPieces(
        atlas, scene.scene, source, matchSplitPieces(scene.scene, baked.scene, source), baked.scene,
        baked.lightmapUVs, aImage.width, aImage.height, aImage.pixels, out.pixels, unread);
  // A few texels on surfaces the automatic cells' bake does not hold at all (one face of a zero-thickness
  // wall the decomposition left out) are left out of the comparison; more is another scene.
  if (missing > 0 && unreadTexels && missing * 100 <= atlas.validTexels()) {
    *unreadTexels = std::move(unread);
    return out;
  }
  if (missing > 0)
    throw InputError(glb.string(), std::to_string(missing) + " of " + bDir +
                                       "'s texels lie on triangles it does not hold (not a bake of " +
                                       scenePath + "?)");
  return out;
}

}  // namespace cpgi::cli
