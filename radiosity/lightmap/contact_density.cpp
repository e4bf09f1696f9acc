#include "radiosity/lightmap/contact_density.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_for.h>

namespace cpgi {

namespace {
// Probe points (half a coarse texel apart: 4 to a coarse texel) that must find something close.
constexpr int kContactPoints = 4;
}  // namespace

std::vector<float> outputDensity(const LightmapAtlas& atlas, size_t triangleCount) {
  std::vector<float> density(triangleCount, 0.0f);
  for (const Patch& p : atlas.patches) {
    // The coarser axis: a long thin strip (a 12 m rail 2 cm deep) has the minimum of 2 texels across it,
    // 100 a metre, which asked of its whole length is 1 200 texels where the output has 120.
    const float edge = std::max(glm::length(p.texelU), glm::length(p.texelV));
    if (!(edge > 0.0f)) continue;
    for (int32_t t : p.triangles) density[size_t(t)] = 1.0f / edge;
  }
  return density;
}

std::vector<float> contactDensity(const Scene& scene, const RayScene& rays, float coarse,
                                  std::span<const float> fine,
                                  std::chrono::steady_clock::time_point deadline) {
  std::vector<float> density(scene.triangles.size(), coarse);
  for (size_t i = 0; i < density.size(); ++i)
    if (fine[i] > 0.0f && fine[i] < coarse) density[i] = fine[i];  // never finer than the output
  const float reach = 2.0f / coarse;             // gaps beyond this need no more than the coarse texels
  const float offset = 1e-5f * rays.diagonal();  // off the surface, as the reference's rays
  auto probe = [&](size_t i) {
    const Triangle& t = scene.triangles[i];
    const glm::vec3 n = t.geometricNormal();
    if (!(t.area() > 0.0f) || fine[i] <= coarse) return;
    float longest = 0.0f;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::length(t.p[(k + 1) % 3] - t.p[k]));
    // Points on a barycentric grid about half a coarse texel apart, inset from the edges (a point on an
    // edge shared with a wall standing on it would find that wall at once).
    const int steps = std::clamp(int(std::ceil(longest * 2.0f * coarse)), 1, 512);
    // The gap is the largest of the nearest kContactPoints hits: an occluder smaller than a coarse texel
    // (a chair's leg on a floor) shades less than the texel the coarse solve smears it over.
    std::array<float, kContactPoints> nearest;
    nearest.fill(reach);
    int points = 0, open = 0;  // probe points, and those that find nothing within reach
    for (int a = 0; a <= steps; ++a)
      for (int b = 0; a + b <= steps; ++b) {
        const float u = (float(a) + 1.0f / 3.0f) / float(steps + 1),
                    v = (float(b) + 1.0f / 3.0f) / float(steps + 1);
        if (u + v >= 1.0f) continue;
        const glm::vec3 p = (1.0f - u - v) * t.p[0] + u * t.p[1] + v * t.p[2];
        ++points;
        const RayScene::Hit hit = rays.intersect(p + offset * n, n, 0.0f, reach);
        if (!hit) {
          ++open;
        } else if (hit.t < nearest.back()) {
          nearest.back() = hit.t;
          std::sort(nearest.begin(), nearest.end());
        }
      }
    // A surface covered all over (a book's side against the next book, a wardrobe's back against the
    // wall, a cube's face on the floor) lies wholly in its contact's shade: its bounced light has no edge
    // to resolve but within about the gap of its rim, so it keeps the coarse texels.
    if (open == 0 && points >= kContactPoints) return;
    const float gap = nearest.back();
    if (gap < reach) density[i] = std::clamp(2.0f / std::max(gap, 1e-4f), coarse, fine[i]);
  };
  // Batches of triangles between deadline checks (a large triangle probes up to 131 000 points).
  constexpr size_t kBatch = 2048;
  for (size_t begin = 0; begin < density.size() && std::chrono::steady_clock::now() < deadline;
       begin += kBatch)
    tbb::parallel_for(begin, std::min(density.size(), begin + kBatch), probe);
  return density;
}

}  // namespace cpgi
