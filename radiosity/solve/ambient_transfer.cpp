#include "radiosity/solve/ambient_transfer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "radiosity/solve/emission_bins.h"

namespace cpgi {

namespace {

uint64_t mix64(uint64_t x) {  // splitmix64's finaliser
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double fraction(double x) {
  return x - std::floor(x);
}

// A cosine-distributed direction about unit n from two numbers in [0, 1) (frame: Duff et al. 2017).
glm::vec3 cosineDirection(const glm::vec3& n, double u1, double u2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  const glm::vec3 t1(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), t2(b, sign + n.y * n.y * a, -n.y);
  const float phi = float(2.0 * std::numbers::pi * u1), r = float(std::sqrt(u2));
  return glm::normalize(r * std::cos(phi) * t1 + r * std::sin(phi) * t2 + float(std::sqrt(1.0 - u2)) * n);
}

}  // namespace

AmbientTransfer measureAmbientTransfer(const LightmapAtlas& atlas, const RayScene& rays,
                                       std::span<const float> texelCell, size_t cells, int raysPerCell,
                                       uint64_t seed) {
  const size_t n = atlas.texelCount();
  if (texelCell.size() != n)
    throw std::invalid_argument("measureAmbientTransfer: not one cell per atlas texel");
  const size_t count = cells + 1;
  auto cellOf = [&](size_t t) {
    const float c = texelCell[t];
    return c >= 0.0f && size_t(c) < cells ? size_t(c) : cells;
  };
  // Per cell, its texels and their running area: the points a ray leaves from, by area.
  std::vector<std::vector<uint32_t>> texels(count);
  std::vector<std::vector<double>> running(count);
  for (size_t t = 0; t < n; ++t) {
    if (atlas.patch[t] < 0 || !(atlas.area[t] > 0.0f)) continue;
    const size_t c = cellOf(t);
    texels[c].push_back(uint32_t(t));
    running[c].push_back((running[c].empty() ? 0.0 : running[c].back()) + atlas.area[t]);
  }
  AmbientTransfer out;
  out.raysPerCell = std::max(raysPerCell, 1);
  out.share.assign(count, std::vector<double>(count, 0.0));
  const float offset = std::max(1e-5f * rays.diagonal(), 1e-6f);
  tbb::parallel_for(size_t(0), count, [&](size_t c) {
    std::vector<double>& row = out.share[c];
    if (texels[c].empty()) {
      row[c] = 1.0;
      return;
    }
    const uint64_t h = mix64(seed ^ mix64(c));
    const double shift0 = double(h >> 40) * 0x1p-24, shift1 = double((h >> 16) & 0xffffff) * 0x1p-24;
    const double shift2 = double(mix64(h) >> 40) * 0x1p-24;
    // The point stratified over the cell's area; the direction by Roberts' R3 sequence, shifted per cell.
    constexpr double g = 1.2207440846057594754;  // x^4 = x + 1
    const double total = running[c].back();
    std::vector<double> landed(count, 0.0);
    for (int k = 0; k < out.raysPerCell; ++k) {
      const double at = total * fraction(shift0 + (k + 0.5) / out.raysPerCell);
      const size_t i =
          std::min(size_t(std::upper_bound(running[c].begin(), running[c].end(), at) - running[c].begin()),
                   texels[c].size() - 1);
      const size_t t = texels[c][i];
      const glm::vec3 dir =
          cosineDirection(atlas.normal[t], fraction(shift1 + k / g), fraction(shift2 + k / (g * g)));
      const RayScene::Hit hit = rays.intersect(atlas.position[t] + atlas.normal[t] * offset, dir, offset);
      if (!hit) continue;  // left the scene
      const int64_t texel = texelAtHit(atlas, hit.triangle, hit.u, hit.v);
      landed[texel >= 0 ? cellOf(size_t(texel)) : cells] += 1.0;
    }
    for (size_t d = 0; d < count; ++d) row[d] = landed[d] / out.raysPerCell;
  });
  return out;
}

}  // namespace cpgi
