#include "radiosity/solve/emission_bins.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cpgi {
namespace {

constexpr float kPi = std::numbers::pi_v<float>, kTwoPi = 2.0f * kPi;

// A small counter-based generator: the same rays for the same seed on every machine and thread.
struct SplitMix {
  uint64_t state;
  float next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return float(z >> 40) * (1.0f / 16777216.0f);
  }
};

}  // namespace

BinFrame binFrame(const glm::vec3& n) {
  const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 t1 = glm::normalize(glm::cross(helper, n));
  return {n, t1, glm::cross(n, t1)};
}

glm::vec2 binSquarePoint(const BinFrame& frame, const glm::vec3& omega) {
  // The inverse of the concentric map: the disk point at radius r and angle φ comes from the square's
  // boundary of half-width r, φ measured along it from the right edge's middle.
  const float a = glm::dot(omega, frame.t1), b = glm::dot(omega, frame.t2);
  const float r = std::min(std::sqrt(a * a + b * b), 1.0f);
  float phi = std::atan2(b, a);
  if (phi < -0.25f * kPi) phi += kTwoPi;
  glm::vec2 xy;
  if (phi < 0.25f * kPi)
    xy = {r, r * phi * (4.0f / kPi)};
  else if (phi < 0.75f * kPi)
    xy = {-r * (phi - 0.5f * kPi) * (4.0f / kPi), r};
  else if (phi < 1.25f * kPi)
    xy = {-r, -r * (phi - kPi) * (4.0f / kPi)};
  else
    xy = {r * (phi - 1.5f * kPi) * (4.0f / kPi), -r};
  return glm::clamp((xy + 1.0f) * (0.5f * float(kBinGrid)), 0.0f, float(kBinGrid));
}

int arrivalBin(const BinFrame& frame, const glm::vec3& omega) {
  const glm::ivec2 ij = glm::min(glm::ivec2(binSquarePoint(frame, omega)), kBinGrid - 1);
  return ij.y * kBinGrid + ij.x;
}

BinTaps binTaps(const BinFrame& frame, const glm::vec3& omega) {
  const glm::vec2 s = binSquarePoint(frame, omega) - 0.5f;
  const glm::vec2 lo = glm::floor(s), t = s - lo;
  const glm::ivec2 i0 = glm::clamp(glm::ivec2(lo), 0, kBinGrid - 1),
                   i1 = glm::clamp(glm::ivec2(lo) + 1, 0, kBinGrid - 1);
  return {{i0.y * kBinGrid + i0.x, i0.y * kBinGrid + i1.x, i1.y * kBinGrid + i0.x, i1.y * kBinGrid + i1.x},
          {(1.0f - t.x) * (1.0f - t.y), t.x * (1.0f - t.y), (1.0f - t.x) * t.y, t.x * t.y}};
}

glm::dvec3 binTotals(const ArrivalBins& bins) {
  glm::dvec3 total(0.0);
  for (const glm::vec3& w : bins) total += glm::dvec3(glm::max(w, glm::vec3(0.0f)));
  return total;
}

glm::vec3 binnedEmissionFactor(const ArrivalBins& bins, const BinFrame& frame, const glm::vec3& omega) {
  if (!(glm::dot(omega, frame.n) > 0.0f)) return glm::vec3(0.0f);
  const glm::dvec3 total = binTotals(bins);
  const BinTaps taps = binTaps(frame, omega);
  glm::vec3 w(0.0f);
  for (int k = 0; k < 4; ++k)
    w += taps.weight[size_t(k)] * glm::max(bins[size_t(taps.bin[size_t(k)])], glm::vec3(0.0f));
  glm::vec3 f(1.0f);
  for (int c = 0; c < 3; ++c)
    if (total[c] > 0.0) f[c] = float(double(w[c]) * double(kArrivalBins) / total[c]);
  return f;
}

EmissionBinSlot normalisedEmissionBins(const ArrivalBins& bins) {
  const glm::dvec3 total = binTotals(bins);
  EmissionBinSlot f{};
  for (size_t b = 0; b < bins.size(); ++b)
    for (int c = 0; c < 3; ++c)
      f[4 * b + size_t(c)] =
          total[c] > 0.0 ? float(std::max(double(bins[b][c]), 0.0) * double(kArrivalBins) / total[c]) : 1.0f;
  return f;
}

int64_t texelAtHit(const LightmapAtlas& atlas, int32_t triangle, float u, float v) {
  if (triangle < 0 || size_t(triangle) >= atlas.triangleUV.size()) return -1;
  const auto& uv = atlas.triangleUV[size_t(triangle)];
  if (uv[0] == glm::vec2(0.0f) && uv[1] == glm::vec2(0.0f) && uv[2] == glm::vec2(0.0f)) return -1;
  const glm::vec2 p = (1.0f - u - v) * uv[0] + u * uv[1] + v * uv[2];
  const int i = std::clamp(int(p.x * float(atlas.width)), 0, atlas.width - 1);
  const int j = std::clamp(int(p.y * float(atlas.height)), 0, atlas.height - 1);
  const size_t t = size_t(j) * size_t(atlas.width) + size_t(i);
  return atlas.patch[t] >= 0 ? int64_t(t) : -1;
}

ArrivalBins traceArrivalBins(const RayScene& rays, const LightmapAtlas& atlas, const glm::vec3& origin,
                             const glm::vec3& edgeU, const glm::vec3& edgeV, const glm::vec3& facing,
                             int rayCount, uint32_t seed, const ExitanceToward& exitance) {
  ArrivalBins bins;
  bins.fill(glm::vec3(0.0f));
  if (rayCount <= 0) return bins;
  const BinFrame far = binFrame(-facing);
  SplitMix rng{uint64_t(seed) * 0x2545F4914F6CDD1Dull + 1};
  // Stratified over the point (√N × √N cells) and, per ray, over the disk: cosine weighting makes the
  // estimate of the irradiance (1/N) Σ M, M the exitance met.
  const int side = std::max(1, int(std::sqrt(double(rayCount))));
  const float offset = 1e-4f * rays.diagonal();
  for (int k = 0; k < rayCount; ++k) {
    const int cell = k % (side * side);
    const float su = (float(cell % side) + rng.next()) / float(side);
    const float sv = (float(cell / side) + rng.next()) / float(side);
    const glm::vec3 y = origin + su * edgeU + sv * edgeV;
    const float r = std::sqrt(rng.next()), phi = kTwoPi * rng.next();
    const glm::vec3 d = glm::normalize(r * std::cos(phi) * far.t1 + r * std::sin(phi) * far.t2 +
                                       std::sqrt(std::max(0.0f, 1.0f - r * r)) * facing);
    const RayScene::Hit hit = rays.intersect(y, d, offset);
    if (!hit) continue;
    const int64_t t = texelAtHit(atlas, hit.triangle, hit.u, hit.v);
    if (t < 0) continue;
    const glm::vec3 omega = -d;  // the light travels from the hit towards the point, and on
    const glm::vec3 m = glm::max(exitance(size_t(t), omega), glm::vec3(0.0f));
    if (m.r + m.g + m.b > 0.0f) bins[size_t(arrivalBin(far, omega))] += m / float(rayCount);
  }
  return bins;
}

}  // namespace cpgi
