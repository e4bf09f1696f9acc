#include "radiosity/solve/ambient_transfer.h"

#include <algorithm>
#include <cmath>
#include <functional>
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

// A walk's random numbers: splitmix64 as a generator, one stream per walk.
struct WalkRandom {
  uint64_t state;
  double next() {
    state += 0x9E3779B97F4A7C15ull;
    return double(mix64(state) >> 11) * 0x1p-53;
  }
};

// Where a ray that left cell `from`'s surfaces landed on cell `to`'s: the texel, and whether it met the
// texel's front (a back face absorbs what reaches it, as the solve's receivers do).
struct Landing {
  size_t to;
  uint32_t texel;
  bool front;
};

// One arrival's walks (AmbientTransfer::Arrival): from landings on `to`, the light's bounces at each
// texel's albedo while they stay on `to`'s surfaces. Russian roulette once a walk carries under a quarter
// of what arrived keeps the walks short and the sums unbiased.
// Russian roulette ends a walk only once it carries under a quarter of its light; in a closed room of
// albedo 1 (a test box, a user's white material) that never comes, and a walk ran until a ray slipped out
// between two triangles (35 of a 36 CPU s bake). Past this many bounces, albedo 0.95 keeps 2e-6 of the
// light; the rest of a walk is left out.
constexpr int kMostBounces = 256;

AmbientTransfer::Arrival followArrival(const LightmapAtlas& atlas, const RayScene& rays,
                                       const std::function<size_t(int64_t)>& cellOfTexel, size_t count,
                                       size_t from, size_t to, const std::vector<Landing>& landings,
                                       int walks, float offset, uint64_t seed) {
  AmbientTransfer::Arrival a{
      .from = from, .to = to, .onward = std::vector<glm::dvec3>(count, glm::dvec3(0.0))};
  for (int k = 0; k < walks; ++k) {
    WalkRandom random{mix64(seed ^ mix64(uint64_t(k)))};
    const Landing& start = landings[size_t(k) * landings.size() / size_t(walks)];
    glm::dvec3 carried(1.0);
    a.landed += carried;
    bool front = start.front;
    size_t texel = start.texel;
    for (int bounce = 0; front && bounce < kMostBounces; ++bounce) {
      carried *= glm::dvec3(atlas.albedo[texel]);
      const double most = std::max({carried.r, carried.g, carried.b});
      if (most < 0.25) {
        const double keep = most / 0.25;
        if (random.next() >= keep) break;
        carried /= keep;
      }
      const glm::vec3& n = atlas.normal[texel];
      const glm::vec3 dir = cosineDirection(n, random.next(), random.next());
      const RayScene::Hit hit = rays.intersect(atlas.position[texel] + n * offset, dir, offset);
      if (!hit) break;  // left the scene
      const int64_t landedTexel = texelAtHit(atlas, hit.triangle, hit.u, hit.v);
      const size_t cell = cellOfTexel(landedTexel);
      if (cell != to || landedTexel < 0) {
        a.onward[cell] += carried;
        break;
      }
      a.landed += carried;
      texel = size_t(landedTexel);
      front = glm::dot(dir, atlas.normal[texel]) < 0.0f;
    }
  }
  a.landed /= double(walks);
  for (glm::dvec3& v : a.onward) v /= double(walks);
  return a;
}

}  // namespace

AmbientTransfer measureAmbientTransfer(const LightmapAtlas& atlas, const RayScene& rays,
                                       std::span<const float> texelCell, size_t cells, int raysPerCell,
                                       uint64_t seed, int walksPerArrival) {
  const size_t n = atlas.texelCount();
  if (texelCell.size() != n)
    throw std::invalid_argument("measureAmbientTransfer: not one cell per atlas texel");
  const size_t count = cells + 1;
  auto cellOf = [&](size_t t) {
    const float c = texelCell[t];
    return c >= 0.0f && size_t(c) < cells ? size_t(c) : cells;
  };
  const std::function<size_t(int64_t)> cellOfTexel = [&](int64_t t) {
    return t >= 0 ? cellOf(size_t(t)) : cells;
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
  std::vector<std::vector<Landing>> landings(count);  // per cell, where its rays landed on a texel
  out.rays.assign(count, {});
  out.sourceArea.assign(count, 0.0);
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
    out.sourceArea[c] = total;
    out.rays[c].resize(size_t(out.raysPerCell));
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
      out.rays[c][size_t(k)].texel = uint32_t(t);
      if (!hit) continue;  // left the scene
      const int64_t texel = texelAtHit(atlas, hit.triangle, hit.u, hit.v);
      const size_t to = cellOfTexel(texel);
      out.rays[c][size_t(k)].to = int32_t(to);
      landed[to] += 1.0;
      if (texel >= 0)
        landings[c].push_back(
            Landing{to, uint32_t(texel), glm::dot(dir, atlas.normal[size_t(texel)]) < 0.0f});
    }
    for (size_t d = 0; d < count; ++d) row[d] = landed[d] / out.raysPerCell;
  });
  if (walksPerArrival <= 0) return out;
  // Per (from, to) with landings, the walks from them.
  std::vector<std::pair<size_t, size_t>> pairs;
  std::vector<std::vector<Landing>> starts;
  for (size_t c = 0; c < count; ++c) {
    std::vector<std::vector<Landing>> byCell(count);
    for (const Landing& l : landings[c]) byCell[l.to].push_back(l);
    for (size_t d = 0; d < count; ++d)
      if (!byCell[d].empty()) pairs.emplace_back(c, d), starts.push_back(std::move(byCell[d]));
  }
  out.arrivals.resize(pairs.size());
  tbb::parallel_for(size_t(0), pairs.size(), [&](size_t i) {
    const auto [from, to] = pairs[i];
    const int walks = int(std::min<size_t>(size_t(walksPerArrival), 16 * starts[i].size()));
    out.arrivals[i] = followArrival(atlas, rays, cellOfTexel, count, from, to, starts[i], walks, offset,
                                    mix64(seed ^ mix64(from * count + to + 0x9e37)));
  });
  return out;
}

std::vector<glm::dvec3> ambientLandedByArrivals(const std::vector<glm::dvec3>& unshot,
                                                const AmbientTransfer& transfer,
                                                std::span<const double> texelUnshot,
                                                std::span<const float> texelArea) {
  const size_t count = transfer.share.size();
  if (unshot.size() != count)
    throw std::invalid_argument("ambientLandedByArrivals: not one unshot power per cell");
  std::vector<int> index(count * count, -1);  // (from, to) -> its arrival
  for (size_t i = 0; i < transfer.arrivals.size(); ++i)
    index[transfer.arrivals[i].from * count + transfer.arrivals[i].to] = int(i);
  std::vector<glm::dvec3> landed(count, glm::dvec3(0.0)), arriving(transfer.arrivals.size(), glm::dvec3(0.0));
  // Light landing on `to` from `from`: that arrival, or (walks met a way the first rays had not) the light
  // of `to`'s own surfaces, or, with neither, it lands and stays there.
  auto arrive = [&](std::vector<glm::dvec3>& into, size_t from, size_t to, const glm::dvec3& power) {
    int i = index[from * count + to];
    if (i < 0) i = index[to * count + to];
    if (i >= 0)
      into[size_t(i)] += power;
    else
      landed[to] += power;
  };
  // The first flight: each ray of a cell weighed by the unshot power per m² where it left, against the
  // cell's mean (the rays were drawn by area). In a room lit through a door that power lies where the
  // light came in, not spread over the room.
  const bool whereItIs = !texelUnshot.empty() && texelArea.size() == texelUnshot.size() &&
                         transfer.rays.size() == count && transfer.sourceArea.size() == count;
  double unshotSum = 0.0;
  for (size_t c = 0; c < count; ++c) {
    unshotSum += unshot[c].r + unshot[c].g + unshot[c].b;
    double held = 0.0;
    if (whereItIs)
      for (const AmbientTransfer::SourceRay& ray : transfer.rays[c])
        if (ray.texel < texelUnshot.size() && texelArea[ray.texel] > 0.0f)
          held += texelUnshot[ray.texel] / texelArea[ray.texel];
    if (held > 0.0) {
      for (const AmbientTransfer::SourceRay& ray : transfer.rays[c])
        if (ray.to >= 0 && texelArea[ray.texel] > 0.0f)
          arrive(arriving, c, size_t(ray.to),
                 unshot[c] * (texelUnshot[ray.texel] / texelArea[ray.texel] / held));
      continue;
    }
    for (size_t d = 0; d < count; ++d)
      if (transfer.share[c][d] > 0.0) arrive(arriving, c, d, unshot[c] * transfer.share[c][d]);
  }
  for (int bounce = 0; bounce < 1000; ++bounce) {
    std::vector<glm::dvec3> next(arriving.size(), glm::dvec3(0.0));
    for (size_t i = 0; i < arriving.size(); ++i) {
      const AmbientTransfer::Arrival& a = transfer.arrivals[i];
      landed[a.to] += arriving[i] * a.landed;
      for (size_t e = 0; e < count; ++e)
        if (a.onward[e] != glm::dvec3(0.0)) arrive(next, a.to, e, arriving[i] * a.onward[e]);
    }
    arriving = std::move(next);
    double left = 0.0;
    for (const glm::dvec3& v : arriving) left += v.r + v.g + v.b;
    if (left <= 1e-9 * (unshotSum + 1e-30)) break;
  }
  return landed;
}

}  // namespace cpgi
