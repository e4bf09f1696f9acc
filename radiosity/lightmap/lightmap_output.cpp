#include "radiosity/lightmap/lightmap_output.h"

#include <filesystem>
#include <numbers>

#include "core/scene_io.h"

namespace cpgi {

LightmapOutputs writeLightmapOutputs(OutputDir& out, const Scene& scene, const CellGraph& cells,
                                     const LightmapAtlas& atlas, std::vector<glm::vec3> radiosity,
                                     const std::vector<ExrChannel>& extra, Context& ctx,
                                     const ViewParams& viewParams,
                                     std::chrono::steady_clock::time_point viewsDeadline) {
  dilate(atlas, radiosity);
  const ImageRGB image{atlas.width, atlas.height, radiosity};
  std::vector<ExrChannel> channels{{"area", atlas.area}};
  channels.insert(channels.end(), extra.begin(), extra.end());
  writeExr(out.file("lightmap.exr").string(), image, channels);

  LightmapOutputs result;
  result.exposure = viewParams.exposure > 0.0f ? viewParams.exposure : viewExposure(atlas, radiosity);
  GltfWriteOptions gltf;
  gltf.lightmapUVs = &atlas.triangleUV;
  // Keep the cells and portals, so the baked file still loads with its graph.
  gltf.cells = cells.empty() ? nullptr : &cells;
  gltf.lightmapPng = encodePng(image, result.exposure / std::numbers::pi_v<float>);
  writeFileAtomically(out.file("lightmap.png"), gltf.lightmapPng);
  // A staged name keeps its extension, by which writeGltf picks the format; a write error names the file
  // as the user knows it (DIR/baked.glb).
  writeGltf(out.file("baked.glb").string(), scene, gltf);

  RenderedViews views = renderViews(scene, cells, atlas, radiosity, out, ctx, viewParams, viewsDeadline);
  result.views = std::move(views.written);
  result.skippedViews = std::move(views.skipped);
  return result;
}

}  // namespace cpgi
