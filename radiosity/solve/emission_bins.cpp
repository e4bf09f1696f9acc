#include "radiosity/solve/emission_bins.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

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

// The square's radius of a direction at sin θ = r: θ / (π/2), rings of equal angle.
float squareRadius(float r) {
  return std::asin(std::min(r, 1.0f)) * (2.0f / kPi);
}

// Per bin, its share of the projected disk (area) and the integral of its bilinear tap weight times the
// projected solid angle (hat), each as a share of the whole: f reads back ∫ f cos θ dω / π = Σ f_b hat_b.
// By the midpoint rule over kSub × kSub points a cell: binDensity is smooth, and the shares are right to
// about 1e-5.
struct BinWeights {
  std::array<double, kArrivalBins> area{}, hat{};
};

const BinWeights& binWeights() {
  static const BinWeights weights = [] {
    constexpr int kSub = 24, n = kBinGrid * kSub;
    BinWeights w;
    double total = 0.0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec2 s((float(x) + 0.5f) / float(kSub), (float(y) + 0.5f) / float(kSub));
        const double d = binDensity(s);
        w.area[size_t((y / kSub) * kBinGrid + x / kSub)] += d;
        const glm::vec2 c = s - 0.5f, lo = glm::floor(c), t = c - lo;
        const glm::ivec2 i0 = glm::clamp(glm::ivec2(lo), 0, kBinGrid - 1),
                         i1 = glm::clamp(glm::ivec2(lo) + 1, 0, kBinGrid - 1);
        w.hat[size_t(i0.y * kBinGrid + i0.x)] += d * (1.0f - t.x) * (1.0f - t.y);
        w.hat[size_t(i0.y * kBinGrid + i1.x)] += d * t.x * (1.0f - t.y);
        w.hat[size_t(i1.y * kBinGrid + i0.x)] += d * (1.0f - t.x) * t.y;
        w.hat[size_t(i1.y * kBinGrid + i1.x)] += d * t.x * t.y;
        total += d;
      }
    for (double& a : w.area) a /= total;
    for (double& h : w.hat) h /= total;
    return w;
  }();
  return weights;
}

// Σ_b bins_b / area_b · hat_b per channel: what the bins' f read bilinearly integrates to, times π, before
// normalising.
glm::dvec3 binnedIntegral(const ArrivalBins& bins) {
  const BinWeights& w = binWeights();
  glm::dvec3 sum(0.0);
  for (size_t b = 0; b < bins.size(); ++b)
    sum += glm::dvec3(glm::max(bins[b], glm::vec3(0.0f))) * (w.hat[b] / w.area[b]);
  return sum;
}

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
  const float r = squareRadius(std::sqrt(a * a + b * b));
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

glm::vec3 binDirection(const BinFrame& frame, const glm::vec2& square) {
  // The concentric map (Shirley and Chiu), then the square's radius ρ as the angle θ = ρ π/2.
  const glm::vec2 xy = square * (2.0f / float(kBinGrid)) - 1.0f;
  float rho = 0.0f, phi = 0.0f;
  if (std::abs(xy.x) > std::abs(xy.y)) {
    rho = xy.x, phi = 0.25f * kPi * (xy.y / xy.x);
  } else if (xy.y != 0.0f) {
    rho = xy.y, phi = 0.5f * kPi - 0.25f * kPi * (xy.x / xy.y);
  }
  const float theta = 0.5f * kPi * std::abs(rho), sign = rho < 0.0f ? -1.0f : 1.0f;
  const float s = std::sin(theta) * sign;
  return glm::normalize(s * std::cos(phi) * frame.t1 + s * std::sin(phi) * frame.t2 +
                        std::cos(theta) * frame.n);
}

float binDensity(const glm::vec2& square) {
  // Projected disk area per square area, r r'(ρ) / ρ with r = sin(ρ π/2), over its mean π/4: (π/4) sin(πρ)/ρ.
  const glm::vec2 xy = square * (2.0f / float(kBinGrid)) - 1.0f;
  const float rho = std::max(std::abs(xy.x), std::abs(xy.y));
  return rho > 1e-6f ? 0.25f * kPi * std::sin(kPi * rho) / rho : 0.25f * kPi * kPi;
}

double binProjectedArea(int b) {
  return binWeights().area[size_t(b)];
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

BinnedEmitter binnedEmitter(const ArrivalBins& bins, const glm::vec3& normal) {
  return {&bins, binFrame(normal), binnedIntegral(bins)};
}

glm::vec3 binnedEmissionFactor(const BinnedEmitter& e, const glm::vec3& omega) {
  if (!(glm::dot(omega, e.frame.n) > 0.0f)) return glm::vec3(0.0f);
  const BinTaps taps = binTaps(e.frame, omega);
  const BinWeights& weights = binWeights();
  glm::dvec3 w(0.0);
  for (int k = 0; k < 4; ++k) {
    const size_t b = size_t(taps.bin[size_t(k)]);
    w += double(taps.weight[size_t(k)]) * glm::dvec3(glm::max((*e.bins)[b], glm::vec3(0.0f))) /
         weights.area[b];
  }
  glm::vec3 f(1.0f);
  for (int c = 0; c < 3; ++c)
    if (e.total[c] > 0.0) f[c] = float(w[c] / e.total[c]);
  return f;
}

glm::vec3 binnedEmissionFactor(const ArrivalBins& bins, const BinFrame& frame, const glm::vec3& omega) {
  if (!(glm::dot(omega, frame.n) > 0.0f)) return glm::vec3(0.0f);
  return binnedEmissionFactor(BinnedEmitter{&bins, frame, binnedIntegral(bins)}, omega);
}

EmissionBinSlot normalisedEmissionBins(const ArrivalBins& bins) {
  const glm::dvec3 total = binnedIntegral(bins);
  const BinWeights& w = binWeights();
  EmissionBinSlot f{};
  for (size_t b = 0; b < bins.size(); ++b)
    for (int c = 0; c < 3; ++c)
      f[4 * b + size_t(c)] =
          total[c] > 0.0 ? float(std::max(double(bins[b][c]), 0.0) / w.area[b] / total[c]) : 1.0f;
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

namespace {

// traceArrivalBins' rays in order: where each leaves the parallelogram ([0,1]² of its edges), its bin and
// its point of that bin's cell. Stratified over the point (√N × √N cells) and over the bins: as many rays
// through each bin when there are at least kArrivalBins of them, else bins drawn at random.
class ArrivalRays {
 public:
  struct Ray {
    float su, sv;
    int bin;
    glm::vec2 s;
  };
  ArrivalRays(int rayCount, uint32_t seed)
      : count_(rayCount),
        side_(std::max(1, int(std::sqrt(double(rayCount))))),
        perBin_(rayCount >= kArrivalBins),
        rng_{uint64_t(seed) * 0x2545F4914F6CDD1Dull + 1} {}
  Ray next(int k) {
    Ray r;
    const int cell = k % (side_ * side_);
    r.su = (float(cell % side_) + rng_.next()) / float(side_);
    r.sv = (float(cell / side_) + rng_.next()) / float(side_);
    r.bin = perBin_ ? k % kArrivalBins : std::min(int(rng_.next() * float(kArrivalBins)), kArrivalBins - 1);
    const glm::vec2 s(float(r.bin % kBinGrid) + rng_.next(), float(r.bin / kBinGrid) + rng_.next());
    r.s = s;
    return r;
  }
  // A ray through point s of the square estimates the irradiance as (1/N) M binDensity(s), M the exitance
  // met; through its own bin, of n_b rays, as binProjectedArea-weighted: M binDensity(s) / (kArrivalBins
  // n_b).
  float weight(int bin) const {
    const int raysInBin = perBin_ ? count_ / kArrivalBins + (bin < count_ % kArrivalBins ? 1 : 0) : 0;
    return perBin_ ? 1.0f / float(kArrivalBins * raysInBin) : 1.0f / float(count_);
  }

 private:
  int count_, side_;
  bool perBin_;
  SplitMix rng_;
};

}  // namespace

std::vector<int32_t> traceArrivalHits(const RayScene& rays, const LightmapAtlas& atlas,
                                      const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV,
                                      const glm::vec3& facing, int rayCount, uint32_t seed) {
  std::vector<int32_t> hits(size_t(std::max(rayCount, 0)), kNoArrivalTexel);
  const BinFrame far = binFrame(-facing);
  ArrivalRays arrival(rayCount, seed);
  const float offset = 1e-4f * rays.diagonal();
  for (int k = 0; k < rayCount; ++k) {
    const ArrivalRays::Ray r = arrival.next(k);
    const glm::vec3 y = origin + r.su * edgeU + r.sv * edgeV;
    const glm::vec3 omega =
        binDirection(far, r.s);  // the light travels from the hit towards the point, and on
    const RayScene::Hit hit = rays.intersect(y, -omega, offset);
    if (!hit) continue;
    const int64_t t = texelAtHit(atlas, hit.triangle, hit.u, hit.v);
    if (t >= 0) hits[size_t(k)] = int32_t(t);
  }
  return hits;
}

ArrivalBins arrivalBinsAlongHits(std::span<const int32_t> hits, const glm::vec3& facing, uint32_t seed,
                                 const ExitanceToward& exitance, std::span<const uint8_t> directional) {
  ArrivalBins bins;
  bins.fill(glm::vec3(0.0f));
  const int rayCount = int(hits.size());
  const BinFrame far = binFrame(-facing);
  ArrivalRays arrival(rayCount, seed);
  for (int k = 0; k < rayCount; ++k) {
    const ArrivalRays::Ray r = arrival.next(k);
    const int32_t t = hits[size_t(k)];
    if (t == kNoArrivalTexel) continue;
    const bool towards = directional.empty() || (size_t(t) < directional.size() && directional[size_t(t)]);
    const glm::vec3 omega = towards ? binDirection(far, r.s) : glm::vec3(0.0f);
    const glm::vec3 m = glm::max(exitance(size_t(t), omega), glm::vec3(0.0f));
    if (!(m.r + m.g + m.b > 0.0f)) continue;
    bins[size_t(r.bin)] += m * (binDensity(r.s) * arrival.weight(r.bin));
  }
  return bins;
}

ArrivalBins traceArrivalBins(const RayScene& rays, const LightmapAtlas& atlas, const glm::vec3& origin,
                             const glm::vec3& edgeU, const glm::vec3& edgeV, const glm::vec3& facing,
                             int rayCount, uint32_t seed, const ExitanceToward& exitance) {
  if (rayCount <= 0) {
    ArrivalBins none;
    none.fill(glm::vec3(0.0f));
    return none;
  }
  return arrivalBinsAlongHits(traceArrivalHits(rays, atlas, origin, edgeU, edgeV, facing, rayCount, seed),
                              facing, seed, exitance);
}

}  // namespace cpgi
