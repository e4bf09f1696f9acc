// renderViews lives apart from the pure rendering in views.cpp: it is the only part that writes files.
#include <algorithm>
#include <cctype>
#include <set>
#include <string>

#include "core/image_io.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/views.h"

namespace cpgi {
namespace {

// The exposure of one picture from what its camera sees: its pixels' 90th percentile of radiance (the
// largest of R, G, B, over pixels that see a lit surface) to 0.8, as viewExposure does for the whole
// lightmap. A view from a dim room is then as readable as one from the lit room; the EXR keeps the
// radiance as it is. `fallback` for a black picture.
float pictureExposure(const ImageRGB& image, float fallback) {
  std::vector<float> radiance;
  radiance.reserve(image.pixels.size());
  for (const glm::vec3& p : image.pixels) {
    const float r = std::max({p.x, p.y, p.z});
    if (r > 0.0f) radiance.push_back(r);
  }
  if (radiance.empty()) return fallback;
  const auto at = radiance.begin() + std::ptrdiff_t(0.9 * double(radiance.size() - 1));
  std::nth_element(radiance.begin(), at, radiance.end());
  return *at > 0.0f ? 0.8f / *at : fallback;
}

}  // namespace

std::vector<Camera> viewCameras(const RayScene& rays, const Scene& scene, const CellGraph& cells) {
  return scene.cameras.empty() ? defaultCameras(rays, scene, cells) : scene.cameras;
}

std::vector<std::string> renderCameraViews(const RayScene& rays, const Scene& scene,
                                           std::span<const Camera> cameras, const LightmapAtlas& atlas,
                                           std::span<const glm::vec3> lightmap, OutputDir& out, Context& ctx,
                                           const ViewParams& params) {
  const float lightmapExposure = viewExposure(atlas, lightmap);
  std::vector<std::string> names;
  std::set<std::string> used;
  for (size_t c = 0; c < cameras.size(); ++c) {
    std::string name;
    for (char ch : cameras[c].name)
      name += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_') ? ch : '_';
    // (append rather than string operator+: GCC 12 warns falsely on the latter, PR 105329)
    if (name.empty()) name.append("camera").append(std::to_string(c));
    while (!used.insert(name).second) name.append("_").append(std::to_string(c));
    const ImageRGB image = renderView(rays, scene, atlas, lightmap, cameras[c], params);
    writeExr(out.file("view-" + name + ".exr").string(), image);
    const float exposure =
        params.exposure > 0.0f ? params.exposure : pictureExposure(image, lightmapExposure);
    writePng(out.file("view-" + name + ".png").string(), image, exposure);
    names.push_back(name);
    ctx.progress("views", double(c + 1) / double(cameras.size()), name);
  }
  return names;
}

std::vector<std::string> renderViews(const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
                                     std::span<const glm::vec3> lightmap, OutputDir& out, Context& ctx,
                                     const ViewParams& params) {
  auto timer = ctx.time("views");
  const RayScene rays(scene);
  const std::vector<Camera> cameras = viewCameras(rays, scene, cells);
  return renderCameraViews(rays, scene, cameras, atlas, lightmap, out, ctx, params);
}

}  // namespace cpgi
