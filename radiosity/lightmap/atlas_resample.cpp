#include "radiosity/lightmap/atlas_resample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cpgi {

namespace {

// The valid texel of coarse chart `cp` whose centre is nearest chart point `at` (−1 if it has none): for
// the few points of a loose triangle whose rasterized texels miss them.
int64_t nearestValidTexel(const LightmapAtlas& coarse, int32_t cp, glm::vec2 at) {
  const Patch& c = coarse.patches[size_t(cp)];
  int64_t best = -1;
  float bestDistance = 0.0f;
  for (int j = 0; j < c.h; ++j)
    for (int i = 0; i < c.w; ++i) {
      const int64_t ct = int64_t(c.y + j) * coarse.width + (c.x + i);
      if (coarse.patch[size_t(ct)] != cp) continue;
      const glm::vec2 d = glm::vec2(float(i) + 0.5f, float(j) + 0.5f) - at;
      if (best < 0 || glm::dot(d, d) < bestDistance) best = ct, bestDistance = glm::dot(d, d);
    }
  return best;
}

// The texel of chart `cp` that chart point `at` falls in; a point just off the chart (float rounding, a
// loose triangle's edge) goes to the nearest valid texel of it.
int64_t texelUnder(const LightmapAtlas& atlas, int32_t cp, glm::vec2 at) {
  const Patch& c = atlas.patches[size_t(cp)];
  const int ci = std::clamp(int(std::floor(at.x)), 0, c.w - 1),
            cj = std::clamp(int(std::floor(at.y)), 0, c.h - 1);
  const int64_t ct = int64_t(c.y + cj) * atlas.width + (c.x + ci);
  return atlas.patch[size_t(ct)] == cp ? ct : nearestValidTexel(atlas, cp, at);
}

// Off the surface by this share of the fine texel's smaller edge: under a solid whose faces end on the
// surface's plane.
constexpr float kSideLift = 1e-3f;
// Below this share of the bilinear weight left on the fine texel's side, the nearest coarse texel it sees
// stands for it instead.
constexpr double kLeastSideWeight = 0.25;
// Coarse texels of the chart tried, nearest first, for that one.
constexpr int kSideCandidates = 8;

// A fine texel's sample point lifted off its surface, and what it sees along that surface.
struct SidePoint {
  glm::vec3 at{0.0f};
  float lift = 0.0f;
  bool sees(const RayScene& rays, const LightmapAtlas& coarse, int64_t c) const {
    const glm::vec3 to = coarse.position[size_t(c)] + lift * coarse.normal[size_t(c)];
    const float length = glm::length(to - at);
    return !(length > 0.0f) || !rays.occluded(at, (to - at) / length, 0.0f, length);
  }
};

SidePoint sidePoint(const LightmapAtlas& fine, size_t t) {
  const Patch& p = fine.patches[size_t(fine.patch[t])];
  const float lift = kSideLift * std::min(glm::length(p.texelU), glm::length(p.texelV));
  return {fine.position[t] + lift * fine.normal[t], lift};
}

// Taps without those across a solid (bit k of `hidden` for taps.texel[k]), renormalised; where too little
// weight is left, the nearest coarse texel of the chart the point sees, or none.
BilinearTaps tapsOnItsSide(const BilinearTaps& taps, uint8_t hidden, const SidePoint& point,
                           const LightmapAtlas& coarse, int32_t cp, glm::vec2 at, const RayScene& rays) {
  BilinearTaps kept;
  double weight = 0.0;
  for (int k = 0; k < taps.count; ++k)
    if (!(hidden >> k & 1)) {
      kept.texel[size_t(kept.count)] = taps.texel[size_t(k)];
      kept.weight[size_t(kept.count)] = taps.weight[size_t(k)];
      weight += taps.weight[size_t(k)];
      ++kept.count;
    }
  if (weight >= kLeastSideWeight) {
    for (int k = 0; k < kept.count; ++k) kept.weight[size_t(k)] /= weight;
    return kept;
  }
  const Patch& c = coarse.patches[size_t(cp)];
  std::vector<std::pair<float, int64_t>> near;
  for (int j = 0; j < c.h; ++j)
    for (int i = 0; i < c.w; ++i) {
      const int64_t ct = int64_t(c.y + j) * coarse.width + (c.x + i);
      const glm::vec2 d = glm::vec2(float(i) + 0.5f, float(j) + 0.5f) - at;
      if (coarse.patch[size_t(ct)] == cp) near.emplace_back(glm::dot(d, d), ct);
    }
  const size_t tried = std::min(near.size(), size_t(kSideCandidates));
  std::partial_sort(near.begin(), near.begin() + std::ptrdiff_t(tried), near.end());
  kept = BilinearTaps{};
  for (size_t k = 0; k < tried; ++k)
    if (point.sees(rays, coarse, near[k].second)) {
      kept.texel[0] = near[k].second, kept.weight[0] = 1.0, kept.count = 1;
      break;
    }
  return kept;
}

// Fills m.sideTaps: per fine texel, the bilinear taps whose sample points a solid hides from its own.
void keepTapsOnTheirSide(AtlasMapping& m, const LightmapAtlas& fine, const LightmapAtlas& coarse,
                         const RayScene& rays) {
  std::vector<uint8_t> hidden(fine.texelCount(), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, fine.texelCount(), 1024),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t t = r.begin(); t < r.end(); ++t) {
                        const BilinearTaps taps = bilinearTaps(m, coarse, t);
                        if (taps.count == 0) continue;
                        const SidePoint point = sidePoint(fine, t);
                        for (int k = 0; k < taps.count; ++k)
                          if (!point.sees(rays, coarse, taps.texel[size_t(k)])) hidden[t] |= uint8_t(1u << k);
                      }
                    });
  m.sideTapsOf.assign(fine.texelCount(), -1);
  for (size_t t = 0; t < fine.texelCount(); ++t) {
    if (hidden[t] == 0) continue;
    const BilinearTaps side = tapsOnItsSide(bilinearTaps(m, coarse, t), hidden[t], sidePoint(fine, t), coarse,
                                            m.coarsePatch[t], m.chartPoint[t], rays);
    m.sideTapsOf[t] = int32_t(m.sideTaps.size());
    m.sideTaps.push_back(side);
  }
}

}  // namespace

glm::vec2 chartCoordinates(const Patch& p, const glm::vec3& x) {
  const glm::vec3 d = x - p.origin;
  const float uu = glm::dot(p.texelU, p.texelU), vv = glm::dot(p.texelV, p.texelV),
              uv = glm::dot(p.texelU, p.texelV);
  const float du = glm::dot(d, p.texelU), dv = glm::dot(d, p.texelV);
  const float det = uu * vv - uv * uv;
  if (!(det > 0.0f)) return glm::vec2(0.0f);
  return glm::vec2(du * vv - dv * uv, dv * uu - du * uv) / det;
}

AtlasMapping mapAtlas(const LightmapAtlas& fine, const LightmapAtlas& coarse, const RayScene* solids) {
  if (fine.triangleUV.size() != coarse.triangleUV.size())
    throw std::invalid_argument("mapAtlas: the atlases are of different scenes");
  std::vector<int32_t> coarsePatchOf(coarse.triangleUV.size(), -1);
  for (size_t p = 0; p < coarse.patches.size(); ++p)
    for (int32_t t : coarse.patches[p].triangles) coarsePatchOf[size_t(t)] = int32_t(p);
  AtlasMapping m;
  m.coarsePatch.assign(fine.texelCount(), -1);
  m.chartPoint.assign(fine.texelCount(), glm::vec2(0.0f));
  m.coarseTexel.assign(fine.texelCount(), -1);
  for (const Patch& p : fine.patches)
    for (int j = 0; j < p.h; ++j)
      for (int i = 0; i < p.w; ++i) {
        const size_t t = size_t(p.y + j) * size_t(fine.width) + size_t(p.x + i);
        if (fine.patch[t] < 0 || &fine.patches[size_t(fine.patch[t])] != &p) continue;
        const int32_t tri = texelTriangle(p, i, j);
        const int32_t cp = tri >= 0 ? coarsePatchOf[size_t(tri)] : -1;
        if (cp < 0) continue;
        const Patch& c = coarse.patches[size_t(cp)];
        const glm::vec2 at = chartCoordinates(c, fine.position[t]);
        m.coarsePatch[t] = cp;
        m.chartPoint[t] = at;
        m.coarseTexel[t] = texelUnder(coarse, cp, at);
      }
  if (solids) keepTapsOnTheirSide(m, fine, coarse, *solids);
  return m;
}

std::vector<glm::vec3> downsample(const AtlasMapping& m, const LightmapAtlas& fine,
                                  const LightmapAtlas& coarse, std::span<const glm::vec3> values) {
  std::vector<glm::dvec3> sum(coarse.texelCount(), glm::dvec3(0.0));
  std::vector<double> area(coarse.texelCount(), 0.0);
  std::vector<glm::dvec3> patchPower(coarse.patches.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < fine.texelCount(); ++t) {
    const int64_t c = m.coarseTexel[t];
    if (c < 0) continue;
    const glm::dvec3 power = glm::dvec3(values[t]) * double(fine.area[t]);
    sum[size_t(c)] += power;
    area[size_t(c)] += fine.area[t];
    patchPower[size_t(m.coarsePatch[t])] += power;
  }
  std::vector<glm::vec3> out(coarse.texelCount(), glm::vec3(0.0f));
  std::vector<glm::dvec3> coarsePower(coarse.patches.size(), glm::dvec3(0.0));
  for (size_t c = 0; c < out.size(); ++c)
    if (area[c] > 0.0) {
      out[c] = glm::vec3(sum[c] / area[c]);
      coarsePower[size_t(coarse.patch[c])] += glm::dvec3(out[c]) * double(coarse.area[c]);
    }
  // A coarse texel's area is not exactly that of the fine texels whose centres fall in it (a loose
  // triangle's rasterized edge): each chart is scaled to hold the power its fine texels held.
  for (size_t c = 0; c < out.size(); ++c) {
    if (!(area[c] > 0.0)) continue;
    const size_t p = size_t(coarse.patch[c]);
    for (int k = 0; k < 3; ++k)
      if (coarsePower[p][k] > 0.0) out[c][k] = float(out[c][k] * (patchPower[p][k] / coarsePower[p][k]));
  }
  return out;
}

BilinearTaps chartTaps(const LightmapAtlas& atlas, int32_t patch, glm::vec2 at) {
  BilinearTaps taps;
  const Patch& c = atlas.patches[size_t(patch)];
  const glm::vec2 g = at - 0.5f;
  auto texelAt = [&](int i, int j) { return int64_t(c.y + j) * atlas.width + (c.x + i); };
  // The 2 × 2 centres around the point, moved inside the chart at its edges, so that the outer half
  // texel is extrapolated along the slope of the two nearest centres rather than held at the last one
  // (light falling steeply towards a corner near a lamp).
  {
    const int nx = std::min(c.w, 2), ny = std::min(c.h, 2);
    const int i0 = std::clamp(int(std::floor(g.x)), 0, c.w - nx),
              j0 = std::clamp(int(std::floor(g.y)), 0, c.h - ny);
    const double fx = std::clamp(double(g.x) - i0, -0.5, 1.5), fy = std::clamp(double(g.y) - j0, -0.5, 1.5);
    bool valid = true;
    for (int dj = 0; dj < ny; ++dj)
      for (int di = 0; di < nx; ++di) {
        const int64_t ct = texelAt(i0 + di, j0 + dj);
        valid = valid && atlas.patch[size_t(ct)] == patch;
        taps.texel[size_t(taps.count)] = ct;
        taps.weight[size_t(taps.count)] = (nx == 1 ? 1.0
                                           : di    ? fx
                                                   : 1.0 - fx) *
                                          (ny == 1 ? 1.0
                                           : dj    ? fy
                                                   : 1.0 - fy);
        ++taps.count;
      }
    if (valid) return taps;
    taps = BilinearTaps{};
  }
  // A loose triangle's chart, whose texels are valid where i + j + 1 < w: near its long edge the point is
  // interpolated (or extrapolated, by up to a texel and a half) affinely from the three valid centres
  // (i, j), (i+1, j), (i, j+1) nearest it, exact where the light is linear. Holding the nearest texels'
  // mean instead put a step at every seam between two triangles of one floor (a texel's worth of slope).
  if (c.quad < 0 && c.w >= 3) {
    int i = std::clamp(int(std::floor(g.x)), 0, c.w - 2), j = std::clamp(int(std::floor(g.y)), 0, c.h - 2);
    while (i + j > c.w - 3) (i > j ? i : j) -= 1;
    const double fx = double(g.x) - i, fy = double(g.y) - j;
    const std::array<int64_t, 3> corner = {texelAt(i, j), texelAt(i + 1, j), texelAt(i, j + 1)};
    if (std::all_of(corner.begin(), corner.end(),
                    [&](int64_t ct) { return atlas.patch[size_t(ct)] == patch; })) {
      taps.texel = {corner[0], corner[1], corner[2], 0};
      taps.weight = {1.0 - fx - fy, fx, fy, 0.0};
      taps.count = 3;
      return taps;
    }
  }
  // Else the four centres around the point clamped into the chart, those that are not valid dropped and
  // the others renormalised.
  const int i0 = int(std::floor(g.x)), j0 = int(std::floor(g.y));
  const float fx = std::clamp(g.x - float(i0), 0.0f, 1.0f), fy = std::clamp(g.y - float(j0), 0.0f, 1.0f);
  double weight = 0.0;
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const int64_t ct = texelAt(std::clamp(i0 + di, 0, c.w - 1), std::clamp(j0 + dj, 0, c.h - 1));
      if (atlas.patch[size_t(ct)] != patch) continue;
      const double w = double(di ? fx : 1.0f - fx) * double(dj ? fy : 1.0f - fy);
      taps.texel[size_t(taps.count)] = ct;
      taps.weight[size_t(taps.count)] = w;
      ++taps.count;
      weight += w;
    }
  if (weight > 0.0) {
    for (int k = 0; k < taps.count; ++k) taps.weight[size_t(k)] /= weight;
    return taps;
  }
  taps = BilinearTaps{};
  if (const int64_t under = texelUnder(atlas, patch, at); under >= 0) {
    taps.texel[0] = under;
    taps.weight[0] = 1.0;
    taps.count = 1;
  }
  return taps;
}

BilinearTaps bilinearTaps(const AtlasMapping& m, const LightmapAtlas& coarse, size_t t) {
  if (!m.sideTapsOf.empty() && m.sideTapsOf[t] >= 0) return m.sideTaps[size_t(m.sideTapsOf[t])];
  const int32_t cp = m.coarsePatch[t];
  return cp < 0 ? BilinearTaps{} : chartTaps(coarse, cp, m.chartPoint[t]);
}

std::vector<glm::vec3> upsample(const AtlasMapping& m, const LightmapAtlas& fine, const LightmapAtlas& coarse,
                                std::span<const glm::vec3> values) {
  std::vector<glm::vec3> out(fine.texelCount(), glm::vec3(0.0f));
  for (size_t t = 0; t < fine.texelCount(); ++t) {
    const BilinearTaps taps = bilinearTaps(m, coarse, t);
    glm::dvec3 sum(0.0);
    for (int k = 0; k < taps.count; ++k)
      sum += taps.weight[size_t(k)] * glm::dvec3(values[size_t(taps.texel[size_t(k)])]);
    out[t] = glm::max(glm::vec3(sum), glm::vec3(0.0f));  // extrapolated at an edge: never below 0
  }
  return out;
}

std::vector<uint8_t> texelsToRefine(const AtlasMapping& m, const LightmapAtlas& fine,
                                    const LightmapAtlas& coarse, std::span<const glm::vec3> values,
                                    std::span<const uint8_t> flags, float tolerance, float floor) {
  // Per coarse texel, whether interpolation next to it is off by more than the tolerance: linear
  // interpolation between centres h apart misses by f'' h² / 8 at most, and the second difference
  // along a chart axis is f'' h².
  auto sum = [&](size_t c) { return values[c].r + values[c].g + values[c].b; };
  std::vector<uint8_t> bent(coarse.texelCount(), 0);
  for (size_t p = 0; p < coarse.patches.size(); ++p) {
    const Patch& c = coarse.patches[p];
    auto at = [&](int i, int j) -> int64_t {
      if (i < 0 || j < 0 || i >= c.w || j >= c.h) return -1;
      const int64_t t = int64_t(c.y + j) * coarse.width + (c.x + i);
      return coarse.patch[size_t(t)] == int32_t(p) ? t : -1;
    };
    for (int j = 0; j < c.h; ++j)
      for (int i = 0; i < c.w; ++i) {
        const int64_t t = at(i, j);
        if (t < 0) continue;
        const float v = sum(size_t(t));
        float miss = 0.0f;
        for (const glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(0, 1)}) {
          const int64_t a = at(i - d.x, j - d.y), b = at(i + d.x, j + d.y);
          if (a >= 0 && b >= 0)
            miss = std::max(miss, std::abs(sum(size_t(a)) + sum(size_t(b)) - 2.0f * v) / 8.0f);
          // At a chart's edge the outer half texel is extrapolated from this centre and the next: the
          // same second difference, one texel in, tells how far it misses.
          else if (a >= 0 || b >= 0) {
            const glm::ivec2 in = a >= 0 ? -d : d;
            const int64_t next = at(i + in.x, j + in.y), beyond = at(i + 2 * in.x, j + 2 * in.y);
            if (beyond >= 0)
              miss = std::max(miss, std::abs(v + sum(size_t(beyond)) - 2.0f * sum(size_t(next))) / 8.0f);
          }
        }
        bent[size_t(t)] = miss > tolerance * (v + floor) || (!flags.empty() && flags[size_t(t)] != 0);
      }
  }
  std::vector<uint8_t> refine(fine.texelCount(), 0);
  for (size_t t = 0; t < fine.texelCount(); ++t) {
    const BilinearTaps taps = bilinearTaps(m, coarse, t);
    for (int k = 0; k < taps.count; ++k) refine[t] = refine[t] || bent[size_t(taps.texel[size_t(k)])];
  }
  return refine;
}

}  // namespace cpgi
