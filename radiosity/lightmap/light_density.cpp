#include "radiosity/lightmap/light_density.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

namespace cpgi {

namespace {

float sum(const glm::vec3& v) { return v.r + v.g + v.b; }

// The area-weighted mean of the light over the texels it reaches.
double meanLitLight(const LightmapAtlas& pilot, std::span<const glm::vec3> light) {
  double weighted = 0.0, area = 0.0;
  for (size_t t = 0; t < pilot.texelCount(); ++t)
    if (pilot.patch[t] >= 0 && sum(light[t]) > 0.0f) {
      weighted += double(pilot.area[t]) * sum(light[t]);
      area += pilot.area[t];
    }
  return area > 0.0 ? weighted / area : 0.0;
}

// Per quad (or loose triangle) of a chart, what its texels hold: Σ a B''² and Σ a (B + floor)² over its
// texels, keyed by the first triangle (texelTriangle's).
struct QuadSums {
  double bend = 0.0, light = 0.0, area = 0.0;
};

// B'' along the chart's axes at each texel with both neighbours on the chart (the larger of the two),
// from the second difference over the texel spacing squared, summed per quad into `sums`.
void chartSums(const LightmapAtlas& pilot, int32_t index, std::span<const glm::vec3> light, float floor,
               std::vector<QuadSums>& sums) {
  const Patch& p = pilot.patches[size_t(index)];
  auto at = [&](int i, int j) -> size_t { return size_t(p.y + j) * size_t(pilot.width) + size_t(p.x + i); };
  auto valid = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < p.w && j < p.h && pilot.patch[at(i, j)] == index;
  };
  const float hu = glm::length(p.texelU), hv = glm::length(p.texelV);
  for (int j = 0; j < p.h; ++j)
    for (int i = 0; i < p.w; ++i) {
      if (!valid(i, j)) continue;
      const float v = sum(light[at(i, j)]);
      double bend = 0.0;
      if (hu > 0.0f && valid(i - 1, j) && valid(i + 1, j))
        bend = std::abs(sum(light[at(i - 1, j)]) - 2.0f * v + sum(light[at(i + 1, j)])) / (double(hu) * hu);
      if (hv > 0.0f && valid(i, j - 1) && valid(i, j + 1))
        bend = std::max(bend, std::abs(sum(light[at(i, j - 1)]) - 2.0f * v + sum(light[at(i, j + 1)])) /
                                  (double(hv) * hv));
      const int32_t triangle = texelTriangle(p, i, j);
      if (triangle < 0 || !std::isfinite(bend)) continue;
      QuadSums& q = sums[size_t(triangle)];
      const double a = pilot.area[at(i, j)];
      q.bend += a * bend * bend;
      q.light += a * (double(v) + floor) * (double(v) + floor);
      q.area += a;
    }
}

// The spacing h at which the quad's RMS miss h² B''/8 is `tolerance` of its RMS light: 1/h per metre.
float quadNeed(const QuadSums& q, float tolerance) {
  if (!(q.area > 0.0) || !(q.light > 0.0)) return 0.0f;
  return float(std::sqrt(std::sqrt(q.bend / q.area) / (8.0 * tolerance * std::sqrt(q.light / q.area))));
}

// Union-find over triangles, with path halving.
struct Surfaces {
  std::vector<uint32_t> parent;
  explicit Surfaces(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

// Whether two triangles lie in one plane (normals within 0.5°, each's corners within 1 mm of the
// other's plane) and share a material.
bool sameSurface(const Triangle& a, const Triangle& b) {
  if (a.material != b.material) return false;
  const glm::vec3 na = a.geometricNormal(), nb = b.geometricNormal();
  if (glm::dot(na, nb) < 0.99996f) return false;
  for (const glm::vec3& p : b.p)
    if (std::abs(glm::dot(p - a.p[0], na)) > 1e-3f) return false;
  return true;
}

}  // namespace

void evenOverSurfaces(const Scene& scene, std::vector<float>& density, double maxGrowth) {
  const size_t n = std::min(scene.triangles.size(), density.size());
  Surfaces surfaces(n);
  // Triangles meeting at a corner (positions to 0.1 mm) join when they lie on one surface.
  std::map<std::array<int64_t, 3>, std::vector<uint32_t>> atCorner;
  for (uint32_t t = 0; t < n; ++t) {
    if (!(density[t] > 0.0f)) continue;
    for (const glm::vec3& p : scene.triangles[t].p)
      atCorner[{std::llround(p.x * 1e4), std::llround(p.y * 1e4), std::llround(p.z * 1e4)}].push_back(t);
  }
  for (const auto& [corner, triangles] : atCorner)
    for (size_t i = 1; i < triangles.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (surfaces.find(triangles[i]) != surfaces.find(triangles[j]) &&
            sameSurface(scene.triangles[triangles[i]], scene.triangles[triangles[j]]))
          surfaces.join(triangles[i], triangles[j]);
  std::vector<float> most(n, 0.0f);
  for (uint32_t t = 0; t < n; ++t) most[surfaces.find(t)] = std::max(most[surfaces.find(t)], density[t]);
  // Texels a surface holds at its triangles' own densities and at its largest.
  std::vector<double> own(n, 0.0), even(n, 0.0);
  for (uint32_t t = 0; t < n; ++t) {
    if (!(density[t] > 0.0f)) continue;
    const uint32_t s = surfaces.find(t);
    const double a = scene.triangles[t].area();
    own[s] += a * double(density[t]) * density[t];
    even[s] += a * double(most[s]) * most[s];
  }
  for (uint32_t t = 0; t < n; ++t) {
    const uint32_t s = surfaces.find(t);
    if (density[t] > 0.0f && even[s] <= maxGrowth * own[s]) density[t] = most[s];
  }
}

std::vector<float> lightDensity(const LightmapAtlas& pilot, std::span<const glm::vec3> light, size_t triangleCount,
                                const LightDensityParams& params) {
  if (light.size() != pilot.texelCount()) throw std::invalid_argument("lightDensity: not one value per pilot texel");
  if (!(params.minDensity > 0.0f) || !(params.maxDensity >= params.minDensity) || !(params.tolerance > 0.0f))
    throw std::invalid_argument("lightDensity: densities or tolerance out of range");
  // A floor above 0 even in a black scene, so that no division is by 0.
  const float floor = std::max(float(params.floorShare * meanLitLight(pilot, light)), 1e-12f);
  std::vector<QuadSums> sums(triangleCount);
  for (size_t index = 0; index < pilot.patches.size(); ++index) chartSums(pilot, int32_t(index), light, floor, sums);
  // Per quad (texelTriangle names the first of its two) or loose triangle: its need within the limits.
  std::vector<float> density(triangleCount, 0.0f);
  for (const Patch& p : pilot.patches)
    for (size_t k = 0; k < p.triangles.size(); k += p.quad >= 0 ? 2 : 1) {
      const size_t first = size_t(p.triangles[k]);
      if (first >= triangleCount) continue;
      const float d = std::clamp(quadNeed(sums[first], params.tolerance), params.minDensity, params.maxDensity);
      density[first] = d;
      if (p.quad >= 0 && k + 1 < p.triangles.size() && size_t(p.triangles[k + 1]) < triangleCount)
        density[size_t(p.triangles[k + 1])] = d;
    }
  return density;
}

}  // namespace cpgi
