#include "radiosity/lightmap/texel_validity.h"

#include <array>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cpgi {

namespace {

// The rays leave the plane by this share of the texel's smaller edge: off the texel's own face, under a
// solid whose faces end on that plane (a pane's edge against its reveal).
constexpr float kLift = 1e-3f;
// How far past the face seen from behind the point goes, as a share of the texel's smaller edge: well
// beyond the engines' own offsets off a surface (1e-5 of the scene's diagonal), so that no ray from the
// moved point starts inside the solid.
constexpr float kMargin = 1e-2f;

// Where texel `t`'s sample point belongs: its centre, or, when a ray along its plane meets a face from
// behind first, just past the nearest such face.
glm::vec3 openSamplePoint(const LightmapAtlas& atlas, const Scene& scene, const RayScene& rays, size_t t) {
  const Patch& p = atlas.patches[size_t(atlas.patch[t])];
  const glm::vec3 x = atlas.position[t], n = atlas.normal[t];
  const float size = std::min(glm::length(p.texelU), glm::length(p.texelV));
  if (!(size > 0.0f)) return x;
  const glm::vec3 base = x + kLift * size * n;
  const glm::vec3 u = p.texelU, v = p.texelV;
  // Along the chart's axes only: a diagonal through a box's vertical edge can graze it and meet the face
  // beyond from behind, moving a texel that lies in the open beside the box.
  const std::array<glm::vec3, 4> steps = {u, -u, v, -v};
  float nearest = std::numeric_limits<float>::max();
  glm::vec3 out = x;
  for (const glm::vec3& step : steps) {
    const float length = glm::length(step);
    if (!(length > 0.0f)) continue;
    const glm::vec3 d = step / length;
    const RayScene::Hit hit = rays.intersect(base, d, 0.0f, length);
    if (!hit || hit.t >= nearest) continue;
    if (glm::dot(scene.triangles[size_t(hit.triangle)].geometricNormal(), d) <= 0.0f) continue;  // front
    nearest = hit.t;
    out = x + (hit.t + kMargin * size) * d;
  }
  return out;
}

}  // namespace

size_t moveSamplePointsOutOfSolids(LightmapAtlas& atlas, const Scene& scene, const RayScene& rays) {
  std::vector<glm::vec3> moved(atlas.texelCount());
  std::vector<uint8_t> changed(atlas.texelCount(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, atlas.texelCount(), 1024),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t t = r.begin(); t < r.end(); ++t) {
                        if (atlas.patch[t] < 0) continue;
                        moved[t] = openSamplePoint(atlas, scene, rays, t);
                        changed[t] = moved[t] != atlas.position[t];
                      }
                    });
  size_t count = 0;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (changed[t]) atlas.position[t] = moved[t], ++count;
  return count;
}

}  // namespace cpgi
