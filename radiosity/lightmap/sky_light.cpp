#include "radiosity/lightmap/sky_light.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cpgi {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

uint64_t mix64(uint64_t x) {  // splitmix64's finaliser: a texel's index → its sequence's shift
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

float fraction(double x) {
  return float(x - std::floor(x));
}

// The share of a texel's directions drawn by the cosine where it has openings to draw the others towards.
constexpr double kCosineShare = 0.5;

// A texel's directions k in [from, to) that leave the scene, their estimates of ∫ L cos θ dω summed into
// `sum` (the texel's irradiance after N directions is sum / N). Without openings, cosine-distributed
// directions, each estimating π L. With them (sky_openings.h), every even k a cosine direction and every
// odd one a direction through an opening, each weighted by the balance heuristic: L cos θ over the mixed
// density kCosineShare cos θ/π + (1 - kCosineShare) p_openings. The same directions in the same order
// whether gathered in one pass or several (the passes end on even counts).
void gatherAt(const Sky& sky, const RayScene& occluders, const std::vector<SkyOpening>& openings,
              const glm::vec3& origin, const glm::vec3& n, uint64_t texel, int from, int to, double& sum) {
  // An orthonormal frame about n (Duff et al. 2017).
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  const glm::vec3 t1(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), t2(b, sign + n.y * n.y * a, -n.y);
  const uint64_t h = mix64(texel);
  const double shift1 = double(h >> 40) * 0x1p-24, shift2 = double((h >> 16) & 0xffffff) * 0x1p-24;
  constexpr double g = 1.32471795724474602596;  // plastic number: Roberts' R2 sequence
  auto cosineDirection = [&](int k) {
    const float u1 = fraction(shift1 + double(k) / g), u2 = fraction(shift2 + double(k) / (g * g));
    const float phi = 2.0f * kPi * u1, r = std::sqrt(u2);
    return glm::normalize(r * std::cos(phi) * t1 + r * std::sin(phi) * t2 + std::sqrt(1.0f - u2) * n);
  };
  const std::optional<TexelOpenings> towards =
      openings.empty() ? std::nullopt : std::optional<TexelOpenings>(std::in_place, openings, origin, n);
  if (!towards || towards->empty()) {
    for (int k = from; k < to; ++k) {
      const glm::vec3 dir = cosineDirection(k);
      const float radiance = skyRadiance(sky, dir);
      if (radiance > 0.0f && !occluders.occluded(origin, dir, 0.0f, 3.0e38f)) sum += double(kPi) * radiance;
    }
    return;
  }
  // The openings' directions: Roberts' R3 sequence (its first coordinate picks the opening), shifted by
  // another hash of the texel.
  const uint64_t h3 = mix64(h);
  const double shift3[3] = {double(h3 >> 40) * 0x1p-24, double((h3 >> 16) & 0xffffff) * 0x1p-24,
                            double(h3 & 0xffff) * 0x1p-16};
  constexpr double g3 = 1.22074408460575947536;  // x⁴ = x + 1: Roberts' R3 sequence
  const glm::dvec3 normal(n);
  for (int k = from; k < to; ++k) {
    glm::dvec3 dir;
    if (k % 2 == 0) {
      dir = glm::dvec3(cosineDirection(k / 2));
    } else {
      const double i = double(k / 2);
      dir = towards->sample(double(fraction(shift3[0] + i / g3)), double(fraction(shift3[1] + i / (g3 * g3))),
                            double(fraction(shift3[2] + i / (g3 * g3 * g3))));
    }
    const double cosine = glm::dot(dir, normal);
    if (!(cosine > 0.0)) continue;
    const float radiance = skyRadiance(sky, glm::vec3(dir));
    if (!(radiance > 0.0f) || occluders.occluded(origin, glm::vec3(dir), 0.0f, 3.0e38f)) continue;
    const double density =
        kCosineShare * cosine / std::numbers::pi + (1.0 - kCosineShare) * towards->pdf(dir);
    sum += double(radiance) * cosine / density;
  }
}

// The passes' ray counts per texel: kFirstPassRays (or all of them when fewer), then doubling up to
// sky.gatherRays. Every texel has an estimate after the first pass's first chunk, whatever the deadline.
constexpr int kFirstPassRays = 8;
std::vector<int> passEnds(int rays) {
  std::vector<int> ends;
  for (int n = std::min(kFirstPassRays, rays); n < rays; n *= 2) ends.push_back(n);
  ends.push_back(rays);
  return ends;
}

// The order of the texels in every pass (`texels`, atlas order, as indices into it): first the seeds, each
// chart row's first texel and every kSeedStride-th after it, spread over the atlas (by their rank's bits
// reversed, so that the first seeds gathered lie all over it), then the others by a halving stride, so that
// a first pass cut short has gathered a texel every few along every row. seedOf: per texel, the seed at
// or before it in its row, whose estimate it takes when the first pass stops before reaching it.
constexpr size_t kSeedStride = 16;
struct PassOrder {
  std::vector<uint32_t> order;
  size_t seeds = 0;
  std::vector<uint32_t> seedOf;
};

// `items` in the order of their index's bits reversed (0, n/2, n/4, 3n/4, ... for n a power of two).
std::vector<uint32_t> spread(const std::vector<uint32_t>& items) {
  size_t domain = 1;
  int bits = 0;
  while (domain < items.size()) domain <<= 1, ++bits;
  std::vector<uint32_t> out;
  out.reserve(items.size());
  for (size_t r = 0; r < domain; ++r) {
    size_t rev = 0;
    for (int b = 0; b < bits; ++b)
      if (r & (size_t(1) << b)) rev |= size_t(1) << (bits - 1 - b);
    if (rev < items.size()) out.push_back(items[rev]);
  }
  return out;
}

PassOrder passOrder(const LightmapAtlas& atlas, const std::vector<size_t>& texels) {
  PassOrder o;
  o.seedOf.resize(texels.size());
  std::vector<uint8_t> phase(texels.size());  // position in its row mod kSeedStride
  size_t rowStart = 0;
  for (size_t j = 0; j < texels.size(); ++j) {
    if (j == 0 || texels[j] != texels[j - 1] + 1 || atlas.patch[texels[j]] != atlas.patch[texels[j - 1]])
      rowStart = j;
    phase[j] = uint8_t((j - rowStart) % kSeedStride);
    o.seedOf[j] = uint32_t(j - phase[j]);
  }
  // Phases by their bits reversed: 0, 8, 4, 12, 2, ...
  for (size_t k = 0; k < kSeedStride; ++k) {
    size_t want = 0;
    for (size_t bit = 1, rev = kSeedStride / 2; bit < kSeedStride; bit <<= 1, rev >>= 1)
      if (k & bit) want |= rev;
    for (size_t j = 0; j < texels.size(); ++j)
      if (phase[j] == want) o.order.push_back(uint32_t(j));
    if (k == 0) {
      o.seeds = o.order.size();
      o.order = spread(o.order);
    }
  }
  return o;
}

// The seeds a first pass cut short did not reach (`reached` unset) take the mean of those it reached on
// their chart, or of all it reached where their chart has none: an estimate for every texel, at the same
// rays, so that the sky's light is in every room however early the deadline came.
void fillUnreachedSeeds(const LightmapAtlas& atlas, const std::vector<size_t>& texels, const PassOrder& order,
                        const std::vector<uint8_t>& reached, std::vector<double>& sums) {
  std::unordered_map<int32_t, std::pair<double, size_t>> byChart;
  double all = 0.0;
  size_t count = 0;
  for (size_t k = 0; k < order.seeds; ++k) {
    const uint32_t j = order.order[k];
    if (!reached[j]) continue;
    auto& [sum, n] = byChart[atlas.patch[texels[j]]];
    sum += sums[j], ++n, all += sums[j], ++count;
  }
  for (size_t k = 0; k < order.seeds; ++k) {
    const uint32_t j = order.order[k];
    if (reached[j]) continue;
    const auto it = byChart.find(atlas.patch[texels[j]]);
    sums[j] = it != byChart.end() ? it->second.first / double(it->second.second)
                                  : (count > 0 ? all / double(count) : 0.0);
  }
}

// Texels of the first pass's first chunk, which runs whatever the deadline (every texel then has an
// estimate): 8 192 texels' 8 rays, a tenth of a second of one core, where a chunk of a later pass is up
// to a million rays.
constexpr size_t kFirstChunk = size_t(1) << 13;

}  // namespace

SkyGatherData addSkyLight(const Sky& sky, const RayScene& occluders, const LightmapAtlas& atlas,
                          DirectLight& direct, Context& ctx, std::chrono::steady_clock::time_point deadline,
                          const std::vector<SkyOpening>& openings) {
  SkyGatherData data{.requestedRays = sky.gatherRays, .rays = sky.gatherRays};
  if (!sky.lights()) return data;
  auto timer = ctx.time("sky light");
  direct.irradiance.resize(atlas.texelCount(), glm::vec3(0.0f));
  // The same offset off the surface as the punctual lights' shadow rays and the reference's paths.
  const float offset = std::max(1e-5f * occluders.diagonal(), 1e-6f);
  std::vector<size_t> texels;
  for (size_t i = 0; i < atlas.texelCount(); ++i)
    if (atlas.patch[i] >= 0) texels.push_back(i);
  std::vector<double> sums(texels.size(), 0.0);
  // In passes over every texel, so that a deadline leaves each texel with the same number of directions,
  // and in chunks of at most kChunk texels and about kChunkRays rays (a later pass has up to 128 rays a
  // texel to add), so that progress is reported and the deadline checked every second or two even on a
  // loaded machine.
  constexpr size_t kChunk = size_t(1) << 15, kChunkRays = size_t(1) << 20;
  const std::vector<int> ends = passEnds(sky.gatherRays);
  const double totalRays = double(texels.size()) * sky.gatherRays;
  const PassOrder order = passOrder(atlas, texels);
  int done = 0;          // directions every texel has
  size_t firstPass = 0;  // texels the first pass gathered itself, when a deadline cut it
  for (size_t p = 0; p < ends.size(); ++p) {
    const int from = done, to = ends[p];
    const size_t chunk = std::clamp(kChunkRays / size_t(to - from), size_t(1024), kChunk);
    std::vector<double> next = sums;
    bool stopped = false;
    for (size_t c = 0; c < texels.size();) {
      // Every chunk but the first pass's first stops at the deadline.
      if ((p > 0 || c > 0) && std::chrono::steady_clock::now() >= deadline) {
        stopped = true;
        break;
      }
      const size_t end =
          std::min(c + (p == 0 && c == 0 ? std::min(chunk, kFirstChunk) : chunk), texels.size());
      tbb::parallel_for(tbb::blocked_range<size_t>(c, end, 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
          const size_t j = order.order[k], i = texels[j];
          gatherAt(sky, occluders, openings, atlas.position[i] + offset * atlas.normal[i], atlas.normal[i], i,
                   from, to, next[j]);
        }
      });
      if (p == 0) firstPass = end;
      const double raysDone = double(texels.size()) * from + double(end) * (to - from);
      char status[64];
      std::snprintf(status, sizeof status, "%d of %d rays a texel, %zu texels", to, sky.gatherRays,
                    texels.size());
      ctx.progress("sky light", totalRays > 0.0 ? raysDone / totalRays : 1.0, status);
      c = end;
    }
    if (stopped && p == 0) {  // the texels not reached take their row's seed's estimate
      std::vector<uint8_t> reached(texels.size(), 0);
      for (size_t k = 0; k < firstPass; ++k) reached[order.order[k]] = 1;
      if (firstPass < order.seeds) fillUnreachedSeeds(atlas, texels, order, reached, next);
      for (size_t j = 0; j < texels.size(); ++j)
        if (!reached[j]) next[j] = next[order.seedOf[j]];
      sums.swap(next);
      done = to;
    }
    if (stopped) {
      data.timedOut = true;
      break;
    }
    sums.swap(next);
    done = to;
  }
  data.rays = done;
  // Summed in texel order: the same total whatever the thread count.
  double landed = 0.0;
  for (size_t j = 0; j < texels.size(); ++j) {
    const float irradiance = float(sums[j] / done);
    if (!(irradiance > 0.0f)) continue;
    direct.irradiance[texels[j]] += glm::vec3(irradiance);
    landed += 3.0 * double(irradiance) * atlas.area[texels[j]];
  }
  direct.landed += landed;
  direct.directionalLanded += landed;
  if (data.timedOut && firstPass < texels.size()) {
    char note[400];
    std::snprintf(
        note, sizeof note,
        "sky light: the deadline came in the first pass, after %zu of %zu texels had their %d rays; "
        "each other texel took the estimate of one up to %zu texels before it in its chart's row%s",
        firstPass, texels.size(), done, kSeedStride - 1,
        firstPass < order.seeds ? ", or where none was gathered its chart's mean" : "");
    ctx.warn(note);
  } else if (data.timedOut) {
    ctx.warn("sky light: the deadline came after " + std::to_string(done) + " of " +
             std::to_string(sky.gatherRays) + " rays a texel; the sky's light is their estimate");
  }
  return data;
}

DirectLight shootPunctualAndSky(const Scene& scene, const LightmapAtlas& atlas, Context& ctx,
                                std::chrono::steady_clock::time_point deadline,
                                const std::vector<SkyOpening>& openings) {
  const RayScene rays(scene);
  DirectLight direct = shootPunctualLights(scene.lights, rays, atlas, ctx);
  addSkyLight(scene.sky, rays, atlas, direct, ctx, deadline, openings);
  return direct;
}

}  // namespace cpgi
