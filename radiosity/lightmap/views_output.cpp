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

namespace {

// One warning for the cameras whose pictures viewSize clamped: an aspect ratio far from a screen's (a
// camera exported with 0.001) would otherwise ask for a picture of gigabytes.
void warnClampedViews(std::span<const Camera> cameras, const ViewParams& params, Context& ctx) {
  std::string clamped;
  for (const Camera& c : cameras)
    if (const ViewSize v = viewSize(c, params); v.clamped)
      clamped.append(clamped.empty() ? "" : ", ")
          .append(c.name)
          .append(" (aspect ratio ")
          .append(std::to_string(c.aspect))
          .append(": ")
          .append(std::to_string(v.width))
          .append("x")
          .append(std::to_string(v.height))
          .append(")");
  if (!clamped.empty())
    ctx.warn("views: pictures kept within " + std::to_string(kMinViewEdge) + " to " +
             std::to_string(kMaxViewEdge) + " pixels an edge for " + clamped);
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out.append(out.empty() ? "" : ", ").append(n);
  return out;
}

// A camera's name made file-safe and unique among `used`.
std::string viewName(const Camera& camera, size_t index, std::set<std::string>& used) {
  std::string name;
  for (char ch : camera.name)
    name += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_') ? ch : '_';
  // (append rather than string operator+: GCC 12 warns falsely on the latter, PR 105329)
  if (name.empty()) name.append("camera").append(std::to_string(index));
  while (!used.insert(name).second) name.append("_").append(std::to_string(index));
  return name;
}

}  // namespace

RenderedViews renderCameraViews(const RayScene& rays, const Scene& scene, std::span<const Camera> cameras,
                                const LightmapAtlas& atlas, std::span<const glm::vec3> lightmap,
                                OutputDir& out, Context& ctx, const ViewParams& params,
                                std::chrono::steady_clock::time_point deadline, size_t leastViews) {
  warnClampedViews(cameras, params, ctx);
  const float lightmapExposure = viewExposure(atlas, lightmap);
  RenderedViews views;
  std::set<std::string> used;
  for (size_t c = 0; c < cameras.size(); ++c) {
    const std::string name = viewName(cameras[c], c, used);
    // A view of a large scene takes seconds: say which one is being rendered.
    ctx.progress("views", double(c) / double(cameras.size()), "rendering " + name);
    const ImageRGB image =
        views.skipped.empty()
            ? renderView(rays, scene, atlas, lightmap, cameras[c], params,
                         c < leastViews ? std::chrono::steady_clock::time_point::max() : deadline)
            : ImageRGB{};
    if (image.pixels.empty()) {
      views.skipped.push_back(cameras[c].name);
      continue;
    }
    writeExr(out.file("view-" + name + ".exr").string(), image);
    const float exposure =
        params.exposure > 0.0f ? params.exposure : pictureExposure(image, lightmapExposure);
    writePng(out.file("view-" + name + ".png").string(), image, exposure);
    views.written.push_back(name);
    ctx.progress("views", double(c + 1) / double(cameras.size()), name + " written");
  }
  if (!views.skipped.empty())
    ctx.warn("views: the time limit came before " + std::to_string(views.skipped.size()) + " of " +
             std::to_string(cameras.size()) + " views; not rendered: " + joinNames(views.skipped));
  return views;
}

RenderedViews renderViews(const Scene& scene, const CellGraph& cells, const LightmapAtlas& atlas,
                          std::span<const glm::vec3> lightmap, OutputDir& out, Context& ctx,
                          const ViewParams& params, std::chrono::steady_clock::time_point deadline,
                          size_t leastViews) {
  auto timer = ctx.time("views");
  if (leastViews == 0 && std::chrono::steady_clock::now() >= deadline &&
      !(scene.cameras.empty() && cells.empty())) {
    // Past the deadline before the first: not even the ray scene (seconds for a large scene on a loaded
    // machine); the cameras named as defaultCameras names them, one per room but the outside.
    RenderedViews views;
    for (const Camera& c : scene.cameras) views.skipped.push_back(c.name);
    if (scene.cameras.empty())
      for (const Cell& c : cells.cells)
        if (c.name != "outside") views.skipped.push_back(c.name);
    if (!views.skipped.empty()) {
      ctx.warn("views: the time limit came before " + std::to_string(views.skipped.size()) + " of " +
               std::to_string(views.skipped.size()) + " views; not rendered: " + joinNames(views.skipped));
      return views;
    }
  }
  const RayScene rays(scene);
  const std::vector<Camera> cameras = viewCameras(rays, scene, cells);
  return renderCameraViews(rays, scene, cameras, atlas, lightmap, out, ctx, params, deadline, leastViews);
}

}  // namespace cpgi
