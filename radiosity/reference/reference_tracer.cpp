#include "radiosity/reference/reference_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/lights.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
/// Independent batches per point: enough degrees of freedom for a usable per-texel error (t-tails of
/// 15 dof), few enough that each batch's low-discrepancy set still has many points.
constexpr int kBatches = 16;

/// PCG32 (O'Neill 2014): small, fast, and seedable per sample point, which is what makes the
/// result independent of how TBB splits the work.
class Pcg32 {
 public:
  explicit Pcg32(uint64_t seed) {
    state_ = 0;
    next();
    state_ += seed;
    next();
  }
  uint32_t next() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + 1442695040888963407ull;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1).
  float uniform() { return float(next() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_;
};

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

float maxComponent(const glm::vec3& v) {
  return std::max(v.x, std::max(v.y, v.z));
}

/// A direction about `n` with density cosθ/π (Malley's method on Duff et al.'s branchless frame).
glm::vec3 sampleCosine(const glm::vec3& n, float r1, float r2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  const glm::vec3 t1(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::vec3 t2(b, sign + n.y * n.y * a, -n.y);
  const float phi = 2.0f * kPi * r1;
  const float radius = std::sqrt(r2);
  const float z = std::sqrt(std::max(0.0f, 1.0f - r2));
  return glm::normalize(radius * std::cos(phi) * t1 + radius * std::sin(phi) * t2 + z * n);
}

/// The uniforms one vertex consumes: emitter choice and point on it, then the bounce direction.
struct FirstVertexSamples {
  float light[3];
  float direction[2];
};

/// Roberts' R_d low-discrepancy sequences ("The unreasonable effectiveness of quasirandom sequences",
/// 2018): frac(i·α) with α from the generalised golden ratio. Any count of points is well spread, so spp
/// need not be a square. Shifted by a random vector per batch (Cranley–Patterson), each point is still
/// uniform, the estimate unbiased, and the spread of batch means an honest error.
double fraction(double x) {
  return x - std::floor(x);
}
void r2Point(uint64_t i, const float shift[2], float out[2]) {
  constexpr double g = 1.32471795724474602596;  // plastic number, x³ = x + 1
  out[0] = float(fraction(shift[0] + double(i) / g));
  out[1] = float(fraction(shift[1] + double(i) / (g * g)));
}
void r3Point(uint64_t i, const float shift[3], float out[3]) {
  constexpr double g = 1.22074408460575947536;  // x⁴ = x + 1
  out[0] = float(fraction(shift[0] + double(i) / g));
  out[1] = float(fraction(shift[1] + double(i) / (g * g)));
  out[2] = float(fraction(shift[2] + double(i) / (g * g * g)));
}

float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/// What the tracer needs per scene triangle, flattened once.
struct SurfaceTable {
  std::vector<glm::vec3> normal;  ///< geometric, by winding; zero for degenerate triangles
  std::vector<glm::vec3> albedo;
  std::vector<glm::vec3> emission;
  std::vector<int32_t> emitterIndex;  ///< position in `emitters`, -1 for a triangle that does not emit
  std::vector<uint32_t> emitters;     ///< emissive triangles
  // The fallback selection for scenes with many emitters: proportional to power (area × Σ emission).
  std::vector<float> emitterCdf;
  std::vector<float> emitterProbability;

  explicit SurfaceTable(const Scene& scene) {
    const size_t count = scene.triangles.size();
    normal.resize(count);
    albedo.resize(count, glm::vec3(0.0f));
    emission.resize(count, glm::vec3(0.0f));
    emitterIndex.resize(count, -1);
    std::vector<double> weights;
    for (size_t t = 0; t < count; ++t) {
      const Triangle& tri = scene.triangles[t];
      normal[t] = tri.geometricNormal();
      if (tri.material < scene.materials.size()) {
        albedo[t] = glm::clamp(scene.materials[tri.material].albedo, 0.0f, 1.0f);
        emission[t] = glm::max(scene.materials[tri.material].emission, 0.0f);
      }
      const double weight = double(tri.area()) * (emission[t].x + emission[t].y + emission[t].z);
      if (weight > 0.0 && normal[t] != glm::vec3(0.0f)) {
        emitterIndex[t] = static_cast<int32_t>(emitters.size());
        emitters.push_back(static_cast<uint32_t>(t));
        weights.push_back(weight);
      }
    }
    double total = 0.0;
    for (double w : weights) total += w;
    double running = 0.0;
    for (size_t k = 0; k < emitters.size(); ++k) {
      running += weights[k];
      emitterCdf.push_back(float(running / total));
      emitterProbability.push_back(float(weights[k] / total));
    }
    if (!emitterCdf.empty()) emitterCdf.back() = 1.0f;
  }
};

/// F(dA → triangle), unoccluded, by Lambert's contour formula after clipping to the front half-space
/// (the float, allocation-free twin of form_factors.h's oracle, for choosing lights per vertex).
float triangleFormFactor(const glm::vec3& x, const glm::vec3& n, const Triangle& tri) {
  glm::vec3 poly[4];
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    const glm::vec3 a = tri.p[i] - x, b = tri.p[(i + 1) % 3] - x;
    const float da = glm::dot(n, a), db = glm::dot(n, b);
    if (da >= 0.0f) poly[m++] = a;
    if ((da >= 0.0f) != (db >= 0.0f)) poly[m++] = a + (da / (da - db)) * (b - a);
  }
  float sum = 0.0f;
  for (int i = 0; i < m && m >= 3; ++i) {
    const glm::vec3 c = glm::cross(poly[i], poly[(i + 1) % m]);
    const float cl = glm::length(c);
    if (cl > 0.0f) sum += std::atan2(cl, glm::dot(poly[i], poly[(i + 1) % m])) * glm::dot(n, c) / cl;
  }
  return std::abs(sum) / (2.0f * kPi);
}

/// How next-event estimation picks an emitter at one vertex. With few emitters, in proportion to an
/// estimate of each one's unoccluded irradiance there (so a lamp in another room is rarely tried): exact
/// (Lambert) at the sample point, where it is computed once for all its paths, and a point-source estimate
/// at deeper vertices, where it must be cheap. With many emitters, by power. An emitter that could light
/// the vertex keeps a non-zero chance, or else is left wholly to the BSDF strategy by MIS (its light pdf
/// is 0), so the choice never biases the estimate, only its variance.
struct LightSelection {
  static constexpr size_t kMaxAdaptive = 64;
  bool adaptive = false;
  float cdf[kMaxAdaptive];
  float total = 0.0f;

  LightSelection(const SurfaceTable& s, const Scene& scene, const glm::vec3& x, const glm::vec3& n,
                 bool exact) {
    if (s.emitters.size() > kMaxAdaptive) return;
    adaptive = true;
    for (size_t k = 0; k < s.emitters.size(); ++k) {
      const uint32_t t = s.emitters[k];
      const Triangle& tri = scene.triangles[t];
      const glm::vec3& e = s.emission[t];
      float w = 0.0f;
      if (glm::dot(s.normal[t], x - tri.p[0]) > 0.0f) {  // only the emitting side lights anything
        if (exact) {
          w = (e.x + e.y + e.z) * triangleFormFactor(x, n, tri);
        } else if (glm::dot(n, tri.p[0] - x) > 0.0f || glm::dot(n, tri.p[1] - x) > 0.0f ||
                   glm::dot(n, tri.p[2] - x) > 0.0f) {
          const glm::vec3 d = tri.centroid() - x;
          const float r2 = glm::dot(d, d), r = std::sqrt(r2), area = tri.area();
          const float cosX = std::max(glm::dot(n, d) / r, 0.05f),
                      cosY = std::max(-glm::dot(s.normal[t], d) / r, 0.05f);
          w = (e.x + e.y + e.z) * area * cosX * cosY / (r2 + area);
        }
      }
      total += w;
      cdf[k] = total;
    }
  }
  /// The emitter (index into SurfaceTable::emitters) for a uniform u, or −1 when none can be chosen.
  int pick(const SurfaceTable& s, float u) const {
    if (!adaptive) {
      const auto it = std::upper_bound(s.emitterCdf.begin(), s.emitterCdf.end(), u);
      return int(std::min<size_t>(it - s.emitterCdf.begin(), s.emitters.size() - 1));
    }
    if (!(total > 0.0f)) return -1;
    const float target = u * total;
    for (size_t k = 0; k < s.emitters.size(); ++k)
      if (target < cdf[k]) return int(k);
    for (size_t k = s.emitters.size(); k-- > 0;)  // u·total rounded up to total: the last with weight
      if (k == 0 || cdf[k] > cdf[k - 1]) return int(k);
    return -1;
  }
  float probability(const SurfaceTable& s, int k) const {
    if (!adaptive) return s.emitterProbability[k];
    if (!(total > 0.0f)) return 0.0f;
    return (cdf[k] - (k > 0 ? cdf[k - 1] : 0.0f)) / total;
  }
};

class PathTracer {
 public:
  PathTracer(const Scene& scene, const ReferenceParams& params)
      : scene_(scene), rays_(scene), surfaces_(scene), params_(params) {
    offset_ = params.rayOffset > 0.0f ? params.rayOffset : std::max(1e-5f * rays_.diagonal(), 1e-6f);
  }

  /// One path's estimate of ρ·H at the point (B minus the point's own emission). `first` holds the
  /// uniforms for the first vertex (stratified by the caller); deeper vertices draw from `rng`.
  glm::vec3 reflected(const SamplePoint& point, const LightSelection& firstLights,
                      const FirstVertexSamples& first, Pcg32& rng, uint64_t& rayCount) const {
    glm::vec3 throughput = glm::clamp(point.albedo, 0.0f, 1.0f);
    if (maxComponent(throughput) <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 sum(0.0f);
    glm::vec3 x = point.position;
    glm::vec3 n = point.normal;
    const bool sky = scene_.sky.lights();
    for (int bounce = 0; bounce < params_.maxBounces; ++bounce) {
      const glm::vec3 origin = x + offset_ * n;
      FirstVertexSamples u = first;
      if (bounce > 0) u = {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
      std::optional<LightSelection> deeperLights;
      if (bounce > 0) deeperLights.emplace(surfaces_, scene_, x, n, false);
      const LightSelection& lights = bounce > 0 ? *deeperLights : firstLights;
      sum += throughput * directLight(x, origin, n, lights, u, rayCount);
      if (!scene_.lights.empty()) sum += throughput * punctualLight(x, origin, n, rng, rayCount);

      const glm::vec3 dir = sampleCosine(n, u.direction[0], u.direction[1]);
      ++rayCount;
      const RayScene::Hit hit = rays_.intersect(origin, dir);
      if (!hit) {
        // The path leaves the scene: the sky or the ground at infinity (core/sky.h) lights it. No other
        // strategy samples the sky, so the cosine-sampled direction's estimate of H is π·L, unweighted.
        if (sky) sum += throughput * (kPi * skyRadiance(scene_.sky, dir));
        break;
      }
      const auto t = static_cast<size_t>(hit.triangle);
      const glm::vec3& ny = surfaces_.normal[t];
      const float cosY = -glm::dot(ny, dir);
      if (cosY <= 0.0f) break;  // a back face: one-sided surfaces show black from behind
      if (const int k = surfaces_.emitterIndex[t]; k >= 0) {
        const float pdfArea = lights.probability(surfaces_, k) / scene_.triangles[t].area();
        const float pdfLight = pdfArea * hit.t * hit.t / cosY;
        const float pdfBsdf = std::max(glm::dot(n, dir), 0.0f) / kPi;
        // π·L with L = E/π: the BSDF strategy's estimate of H is w·E.
        sum += throughput * powerHeuristic(pdfBsdf, pdfLight) * surfaces_.emission[t];
      }
      throughput *= surfaces_.albedo[t];
      if (bounce + 1 >= params_.rouletteAfter) {
        // Survival by the albedo just met, weight 1/albedo: the throughput stays at the point's own
        // albedo instead of growing on the few long paths that cumulative-throughput roulette lets live,
        // which in rooms of albedo 0.5–0.8 was most of the noise.
        const float survive = std::min(0.95f, maxComponent(surfaces_.albedo[t]));
        if (survive <= 0.0f || rng.uniform() >= survive) break;
        throughput /= survive;
      } else if (maxComponent(throughput) <= 0.0f) {
        break;
      }
      const Triangle& tri = scene_.triangles[t];
      x = (1.0f - hit.u - hit.v) * tri.p[0] + hit.u * tri.p[1] + hit.v * tri.p[2];
      n = ny;
    }
    return sum;
  }

  LightSelection lightsAt(const glm::vec3& x, const glm::vec3& n) const {
    return LightSelection(surfaces_, scene_, x, n, true);
  }

 private:
  /// Next-event estimate of the irradiance at x from one point on one emitter, MIS-weighted.
  glm::vec3 directLight(const glm::vec3& x, const glm::vec3& origin, const glm::vec3& n,
                        const LightSelection& lights, const FirstVertexSamples& u, uint64_t& rayCount) const {
    if (surfaces_.emitters.empty()) return glm::vec3(0.0f);
    const int k = lights.pick(surfaces_, u.light[0]);
    if (k < 0) return glm::vec3(0.0f);
    const uint32_t e = surfaces_.emitters[k];
    const Triangle& tri = scene_.triangles[e];
    const float su = std::sqrt(u.light[1]);
    const float b1 = 1.0f - su, b2 = u.light[2] * su;
    const glm::vec3 y = b1 * tri.p[0] + b2 * tri.p[1] + (1.0f - b1 - b2) * tri.p[2];
    const glm::vec3& ny = surfaces_.normal[e];
    const glm::vec3 d = y - x;
    const float r2 = glm::dot(d, d);
    if (r2 <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 w = d / std::sqrt(r2);
    const float cosX = glm::dot(n, w);
    const float cosY = -glm::dot(ny, w);
    if (cosX <= 0.0f || cosY <= 0.0f) return glm::vec3(0.0f);
    // Visible when the first thing the ray meets is the emitter there. A shadow ray stopped short of the
    // light (the old test: occluded up to the light point moved off its surface, less an offset) passed
    // through a wall that meets the lamp's edge within that offset of the light point: light from a lamp
    // against a zero-thickness partition leaked into the room behind.
    const glm::vec3 toY = y - origin;
    const float distance = glm::length(toY);
    ++rayCount;
    if (distance <= offset_) return glm::vec3(0.0f);
    const float slack = 1e-4f * distance + offset_;
    const RayScene::Hit seen = rays_.intersect(origin, toY / distance, 0.0f, distance + slack);
    if (!seen) return glm::vec3(0.0f);
    const auto s = static_cast<size_t>(seen.triangle);
    const bool light = s == e || (surfaces_.emitterIndex[s] >= 0 && std::abs(seen.t - distance) <= slack &&
                                  glm::dot(surfaces_.normal[s], ny) > 0.999f);
    if (!light) return glm::vec3(0.0f);
    const float pdfLight = lights.probability(surfaces_, k) / tri.area() * r2 / cosY;  // per steradian
    const float pdfBsdf = cosX / kPi;
    return powerHeuristic(pdfLight, pdfBsdf) * (surfaces_.emission[e] / kPi) * cosX / pdfLight;
  }

  /// Next-event estimate of the irradiance at x from the punctual lights (core/lights.h), which no
  /// bounce can hit: every light with its own shadow ray when there are few, else one light drawn in
  /// proportion to its unoccluded irradiance there and weighted by the inverse of that chance.
  glm::vec3 punctualLight(const glm::vec3& x, const glm::vec3& origin, const glm::vec3& n, Pcg32& rng,
                          uint64_t& rayCount) const {
    auto visible = [&](const LightArrival& a) {
      ++rayCount;
      const float far = std::isinf(a.distance) ? 3.0e38f : a.distance - offset_;
      return !(far > 0.0f && rays_.occluded(origin, a.toLight, 0.0f, far));
    };
    constexpr size_t kAllUpTo = 8;
    const std::vector<PunctualLight>& lights = scene_.lights;
    glm::vec3 sum(0.0f);
    if (lights.size() <= kAllUpTo) {
      for (const PunctualLight& light : lights) {
        const LightArrival a = lightArrival(light, x, n);
        if (maxComponent(a.irradiance) > 0.0f && visible(a)) sum += a.irradiance;
      }
      return sum;
    }
    std::vector<float> weight(lights.size());
    float total = 0.0f;
    for (size_t k = 0; k < lights.size(); ++k) {
      const glm::vec3 e = lightArrival(lights[k], x, n).irradiance;
      total += weight[k] = e.r + e.g + e.b;
    }
    if (!(total > 0.0f)) return sum;
    float target = rng.uniform() * total;
    size_t k = 0;
    while (k + 1 < lights.size() && (target >= weight[k] || weight[k] <= 0.0f)) target -= weight[k++];
    if (weight[k] <= 0.0f) return sum;
    const LightArrival a = lightArrival(lights[k], x, n);
    return visible(a) ? a.irradiance * (total / weight[k]) : sum;
  }

  const Scene& scene_;
  RayScene rays_;
  SurfaceTable surfaces_;
  ReferenceParams params_;
  float offset_ = 0.0f;
};

}  // namespace

ReferenceResult traceReference(const Scene& scene, std::span<const SamplePoint> points,
                               const ReferenceParams& params, Context& ctx,
                               std::span<const uint64_t> streams) {
  if (!streams.empty() && streams.size() != points.size())
    throw std::invalid_argument("traceReference: one stream per point, or none");
  if (params.spp < 2)
    throw InputError("samples per texel",
                     "needs at least 2 samples per texel, got " + std::to_string(params.spp));
  auto timer = ctx.time("reference");
  const PathTracer tracer(scene, params);

  // Independent randomly shifted batches of a low-discrepancy set; spp rounds up to a whole number of them.
  const int batches = std::min(params.spp, kBatches);
  const int perBatch = (params.spp + batches - 1) / batches;
  ReferenceResult result;
  result.spp = batches * perBatch;
  result.radiosity.assign(points.size(), glm::vec3(0.0f));
  result.standardError.assign(points.size(), glm::vec3(0.0f));
  std::atomic<uint64_t> rays{0};

  // Chunks run one after another so that progress is reported from this thread only.
  const size_t chunks = std::clamp<size_t>(points.size() / 256, 1, 100);
  for (size_t c = 0; c < chunks; ++c) {
    const size_t begin = points.size() * c / chunks, end = points.size() * (c + 1) / chunks;
    tbb::parallel_for(
        tbb::blocked_range<size_t>(begin, end, 4), [&](const tbb::blocked_range<size_t>& range) {
          uint64_t localRays = 0;
          for (size_t i = range.begin(); i < range.end(); ++i) {
            const SamplePoint& point = points[i];
            const uint64_t stream = streams.empty() ? uint64_t(i) : streams[i];
            Pcg32 rng(splitmix64(params.seed ^ splitmix64(stream)));
            // The light choice is made once at the centre; a start elsewhere in the footprint keeps it
            // unbiased, since MIS weighs each path by the same choice's probabilities.
            const LightSelection firstLights = tracer.lightsAt(point.position, point.normal);
            const bool spread = point.footprintU != glm::vec3(0.0f) || point.footprintV != glm::vec3(0.0f);
            glm::dvec3 sum(0.0), sumSquares(0.0);
            for (int b = 0; b < batches; ++b) {
              const float lightShift[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
              const float directionShift[2] = {rng.uniform(), rng.uniform()};
              glm::dvec3 batchSum(0.0);
              for (int s = 0; s < perBatch; ++s) {
                FirstVertexSamples first;
                r3Point(uint64_t(s), lightShift, first.light);
                r2Point(uint64_t(s), directionShift, first.direction);
                SamplePoint start = point;
                if (spread) {
                  const float du = rng.uniform() - 0.5f, dv = rng.uniform() - 0.5f;
                  start.position += du * point.footprintU + dv * point.footprintV;
                }
                batchSum += glm::dvec3(tracer.reflected(start, firstLights, first, rng, localRays));
              }
              const glm::dvec3 batchMean = batchSum / double(perBatch);
              sum += batchMean;
              sumSquares += batchMean * batchMean;
            }
            const double k = batches;
            const glm::dvec3 mean = sum / k;
            // The batch means are independent and identically distributed: their spread is the error.
            const glm::dvec3 variance = glm::max((sumSquares - k * mean * mean) / (k - 1.0), 0.0);
            result.radiosity[i] = glm::vec3(glm::dvec3(point.emission) + mean);
            result.standardError[i] = glm::vec3(glm::sqrt(variance / k));
          }
          rays += localRays;
        });
    ctx.progress("reference", double(c + 1) / double(chunks),
                 std::to_string(end) + " of " + std::to_string(points.size()) + " texels");
  }
  result.rays = rays.load();
  return result;
}

ReferenceResult traceReference(const Scene& scene, const LightmapAtlas& atlas, const ReferenceParams& params,
                               Context& ctx, std::span<const size_t> ranks) {
  std::vector<SamplePoint> points;
  std::vector<size_t> texels;
  std::vector<uint64_t> streams;
  size_t rank = 0, next = 0;  // next: the first of `ranks` not yet reached
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    const bool chosen = ranks.empty() || (next < ranks.size() && ranks[next] == rank);
    if (chosen) {
      SamplePoint point{atlas.position[i], atlas.normal[i], atlas.albedo[i], atlas.emission[i]};
      const Patch& patch = atlas.patches[size_t(atlas.patch[i])];
      if (params.texelMean) {  // a loose triangle's valid squares lie inside it too
        point.footprintU = patch.texelU;
        point.footprintV = patch.texelV;
      }
      points.push_back(point);
      texels.push_back(i);
      streams.push_back(rank);
      if (!ranks.empty()) ++next;
    }
    ++rank;
  }
  if (next < ranks.size())
    throw std::invalid_argument("traceReference: texel ranks not increasing or beyond the valid texels");
  ReferenceResult compact = traceReference(scene, points, params, ctx, streams);
  ReferenceResult result;
  result.spp = compact.spp;
  result.rays = compact.rays;
  result.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  result.standardError.assign(atlas.texelCount(), glm::vec3(0.0f));
  for (size_t k = 0; k < texels.size(); ++k) {
    result.radiosity[texels[k]] = compact.radiosity[k];
    result.standardError[texels[k]] = compact.standardError[k];
  }
  return result;
}

double relativeStandardError(const ReferenceResult& result, std::span<const float> area) {
  double noise = 0.0, signal = 0.0;
  const size_t count = std::min({area.size(), result.radiosity.size(), result.standardError.size()});
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3 s(result.standardError[i]), b(result.radiosity[i]);
    noise += area[i] * glm::dot(s, s);
    signal += area[i] * glm::dot(b, b);
  }
  return signal > 0.0 ? std::sqrt(noise / signal) : 0.0;
}

}  // namespace cpgi
