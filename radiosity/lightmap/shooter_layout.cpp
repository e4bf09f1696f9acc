#include "radiosity/lightmap/shooter_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cpgi {
namespace {

// Möller–Trumbore; the distance along `d` (unit) to the triangle, or +inf.
float hitDistance(const glm::vec3& o, const glm::vec3& d, const Triangle& t) {
  const glm::vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
  const glm::vec3 p = glm::cross(d, e2);
  const float det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12f) return std::numeric_limits<float>::infinity();
  const float inv = 1.0f / det;
  const glm::vec3 s = o - t.p[0];
  const float u = glm::dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return std::numeric_limits<float>::infinity();
  const glm::vec3 q = glm::cross(s, e1);
  const float v = glm::dot(d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return std::numeric_limits<float>::infinity();
  const float dist = glm::dot(e2, q) * inv;
  return dist > 0.0f ? dist : std::numeric_limits<float>::infinity();
}

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  void add(const glm::vec3& q) { lo = glm::min(lo, q), hi = glm::max(hi, q); }
  bool overlaps(const Box& o) const { return glm::all(glm::lessThanEqual(lo, o.hi)) && glm::all(glm::lessThanEqual(o.lo, hi)); }
};

}  // namespace

std::vector<ShooterLayout> layoutShooters(const Scene& scene, const LightmapAtlas& atlas, const LayoutParams& params) {
  std::vector<Box> triangleBoxes(scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    for (const glm::vec3& q : scene.triangles[i].p) triangleBoxes[i].add(q);

  std::vector<ShooterLayout> layouts;
  layouts.reserve(atlas.patches.size());
  for (size_t pi = 0; pi < atlas.patches.size(); ++pi) {
    const Patch& p = atlas.patches[pi];
    std::vector<int32_t> own = p.triangles;  // the patch's own triangles never block its probes
    std::sort(own.begin(), own.end());
    ShooterLayout l;
    l.normal = p.normal;
    const glm::vec3 u = p.texelU - glm::dot(p.texelU, p.normal) * p.normal;
    l.tangent = glm::normalize(glm::length(u) > 0.0f ? u : glm::cross(glm::vec3(0.6f, 0.8f, 0.0f), p.normal));
    l.bitangent = glm::cross(l.normal, l.tangent);
    l.texelRadius = 0.5f * std::max(glm::length(p.texelU + p.texelV), glm::length(p.texelU - p.texelV));
    auto regionsAlong = [&](float length, int texels) {
      const int n = static_cast<int>(std::ceil(length / params.regionSize - 1e-3f));
      return std::clamp(n, 1, std::min(params.maxRegions, texels));
    };
    l.regions = {regionsAlong(glm::length(p.texelU) * p.w, p.w), regionsAlong(glm::length(p.texelV) * p.h, p.h)};
    // Probe directions: the normal and four 60° tilts.
    const float c = 0.5f, s = 0.8660254f;
    const glm::vec3 rays[5] = {l.normal, c * l.normal + s * l.tangent, c * l.normal - s * l.tangent,
                               c * l.normal + s * l.bitangent, c * l.normal - s * l.bitangent};
    for (int ry = 0; ry < l.regions.y; ++ry)
      for (int rx = 0; rx < l.regions.x; ++rx) {
        const int x0 = p.w * rx / l.regions.x, x1 = p.w * (rx + 1) / l.regions.x;
        const int y0 = p.h * ry / l.regions.y, y1 = p.h * (ry + 1) / l.regions.y;
        l.rects.push_back({x0, y0, x1, y1});
        auto texelAt = [&](int x, int y) { return size_t(p.y + y) * atlas.width + p.x + x; };
        // Candidates: the centre texel first, then a 3×3 grid; only valid texels of this patch.
        std::vector<glm::vec3> candidates;
        auto consider = [&](int x, int y) {
          const size_t t = texelAt(std::clamp(x, x0, x1 - 1), std::clamp(y, y0, y1 - 1));
          if (atlas.patch[t] == int(pi)) candidates.push_back(atlas.position[t]);
        };
        consider((x0 + x1) / 2, (y0 + y1) / 2);
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) consider(x0 + (x1 - x0) * (2 * i + 1) / 6, y0 + (y1 - y0) * (2 * j + 1) / 6);
        if (candidates.empty()) {  // a loose triangle's region without valid texels: never shoots
          l.eyes.push_back(p.origin);
          continue;
        }
        // The triangles that could block a probe: near the region, in front of it.
        const float reach = std::max(glm::length(p.texelU) * float(x1 - x0), glm::length(p.texelV) * float(y1 - y0));
        Box region;
        for (const glm::vec3& q : candidates) region.add(q), region.add(q + reach * l.normal);
        region.lo -= glm::vec3(reach), region.hi += glm::vec3(reach);
        std::vector<uint32_t> near;
        for (size_t t = 0; t < scene.triangles.size(); ++t)
          if (triangleBoxes[t].overlaps(region) && !std::binary_search(own.begin(), own.end(), int32_t(t)))
            near.push_back(uint32_t(t));
        float bestScore = -1.0f;
        glm::vec3 best = candidates.front();
        for (const glm::vec3& q : candidates) {
          const glm::vec3 origin = q + 1e-4f * reach * l.normal;
          float score = reach;
          for (const glm::vec3& d : rays)
            for (uint32_t t : near) score = std::min(score, hitDistance(origin, d, scene.triangles[t]));
          if (score > bestScore * 1.0001f) bestScore = score, best = q;  // strictly better: keeps the centre on ties
        }
        l.eyes.push_back(best);
      }
    layouts.push_back(std::move(l));
  }
  return layouts;
}

}  // namespace cpgi
