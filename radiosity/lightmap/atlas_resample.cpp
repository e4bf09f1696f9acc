#include "radiosity/lightmap/atlas_resample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

AtlasMapping mapAtlas(const LightmapAtlas& fine, const LightmapAtlas& coarse) {
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
