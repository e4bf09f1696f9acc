#include "radiosity/lightmap/views.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "radiosity/lightmap/lightmap_sampling.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

float viewExposure(const LightmapAtlas& atlas, std::span<const glm::vec3> lightmap) {
  std::vector<std::pair<float, float>> radianceArea;  // (luminance-ish radiance, area)
  double total = 0.0;
  for (size_t i = 0; i < atlas.texelCount() && i < lightmap.size(); ++i) {
    if (atlas.patch[i] < 0 || !(atlas.area[i] > 0.0f)) continue;
    const glm::vec3& b = lightmap[i];
    radianceArea.emplace_back(std::max({b.x, b.y, b.z}) / std::numbers::pi_v<float>, atlas.area[i]);
    total += atlas.area[i];
  }
  std::sort(radianceArea.begin(), radianceArea.end());
  double accumulated = 0.0;
  for (const auto& [radiance, area] : radianceArea) {
    accumulated += area;
    if (accumulated >= 0.9 * total) return radiance > 0.0f ? 0.8f / radiance : 1.0f;
  }
  return 1.0f;
}

ViewSize viewSize(const Camera& camera, const ViewParams& params) {
  ViewSize v;
  v.width = std::clamp(params.width, kMinViewEdge, kMaxViewEdge);
  if (params.height > 0) {
    v.height = std::clamp(params.height, kMinViewEdge, kMaxViewEdge);
    v.clamped = v.width != params.width || v.height != params.height;
    return v;
  }
  // The vertical field of view is the camera's; its aspect ratio gives the height. A height outside the
  // edges' range scales both edges, so that the picture keeps the camera's shape while the width can follow.
  const double aspect = std::isfinite(camera.aspect) && camera.aspect > 0.0f ? camera.aspect : 4.0 / 3.0;
  double w = v.width, h = w / aspect;
  if (h > kMaxViewEdge) w *= kMaxViewEdge / h, h = kMaxViewEdge;
  if (h < kMinViewEdge) w *= kMinViewEdge / h, h = kMinViewEdge;
  v.clamped = v.width != params.width || w != double(v.width);
  v.width = std::clamp(int(std::lround(w)), kMinViewEdge, kMaxViewEdge);
  v.height = std::clamp(int(std::lround(h)), kMinViewEdge, kMaxViewEdge);
  return v;
}

double viewBytes(const ViewSize& size) {
  // The radiance (12 bytes a pixel), the EXR's copy of it and the PNG's 8-bit pixels and deflated stream.
  constexpr double kBytesPerPixel = 32.0;
  return double(size.width) * double(size.height) * kBytesPerPixel;
}

ImageRGB renderView(const RayScene& rays, const Scene& scene, const LightmapAtlas& atlas,
                    std::span<const glm::vec3> lightmap, const Camera& camera, const ViewParams& params,
                    std::chrono::steady_clock::time_point deadline) {
  if (lightmap.size() != atlas.texelCount())
    throw std::invalid_argument("renderView: the lightmap must have one value per atlas texel");
  const ViewSize size = viewSize(camera, params);
  ImageRGB image;
  image.width = size.width;
  image.height = size.height;
  image.pixels.assign(size_t(image.width) * image.height, glm::vec3(0.0f));
  const int n = std::clamp(params.supersample, 1, 8);

  const glm::vec3 forward = glm::normalize(camera.forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanY = std::tan(0.5f * camera.yfov), tanX = tanY * float(image.width) / float(image.height);

  auto shade = [&](glm::vec3 dir) -> glm::vec3 {
    const RayScene::Hit hit = rays.intersect(camera.position, dir);
    if (!hit) return glm::vec3(0.0f);
    const auto t = size_t(hit.triangle);
    if (glm::dot(scene.triangles[t].geometricNormal(), dir) >= 0.0f) return glm::vec3(0.0f);
    if (t >= atlas.triangleUV.size()) return glm::vec3(0.0f);
    const auto& uv = atlas.triangleUV[t];
    if (uv[0] == uv[1] && uv[1] == uv[2]) return glm::vec3(0.0f);  // not in this atlas
    const glm::vec2 at = (1.0f - hit.u - hit.v) * uv[0] + hit.u * uv[1] + hit.v * uv[2];
    return sampleBilinear(atlas.width, atlas.height, lightmap, at) / std::numbers::pi_v<float>;
  };

  auto renderRows = [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < image.width; ++x) {
        glm::vec3 sum(0.0f);
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx) {
            const float px = (float(x) + (float(sx) + 0.5f) / float(n)) / float(image.width);
            const float py = (float(y) + (float(sy) + 0.5f) / float(n)) / float(image.height);
            const glm::vec3 dir =
                glm::normalize(forward + (2.0f * px - 1.0f) * tanX * right + (1.0f - 2.0f * py) * tanY * up);
            sum += shade(dir);
          }
        image.at(x, y) = sum / float(n * n);
      }
  };
  // Bands of rows, each a fraction of a second even at the widest picture, so that the deadline is seen.
  constexpr int kBandRows = 32;
  for (int y = 0; y < image.height; y += kBandRows) {
    if (std::chrono::steady_clock::now() >= deadline) {
      image.pixels.clear();
      return image;
    }
    tbb::parallel_for(tbb::blocked_range<int>(y, std::min(y + kBandRows, image.height), 1), renderRows);
  }
  return image;
}

}  // namespace cpgi
