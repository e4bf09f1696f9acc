#include "radiosity/reference_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "radiosity/ray_scene.h"

namespace cpgi {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

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

float maxComponent(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

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

float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/// What the tracer needs per scene triangle, flattened once.
struct SurfaceTable {
  std::vector<glm::vec3> normal;     ///< geometric, by winding; zero for degenerate triangles
  std::vector<glm::vec3> albedo;
  std::vector<glm::vec3> emission;
  std::vector<float> emitterPdfArea;  ///< density of NEE picking a point here, per m² (0: not an emitter)
  // Emitter selection, proportional to emitted power (area × Σ emission).
  std::vector<uint32_t> emitters;
  std::vector<float> emitterCdf;

  explicit SurfaceTable(const Scene& scene) {
    const size_t count = scene.triangles.size();
    normal.resize(count);
    albedo.resize(count, glm::vec3(0.0f));
    emission.resize(count, glm::vec3(0.0f));
    emitterPdfArea.resize(count, 0.0f);
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
      emitterPdfArea[emitters[k]] = float(weights[k] / total / scene.triangles[emitters[k]].area());
    }
    if (!emitterCdf.empty()) emitterCdf.back() = 1.0f;
  }

  uint32_t pickEmitter(float u) const {
    const auto it = std::upper_bound(emitterCdf.begin(), emitterCdf.end(), u);
    return emitters[std::min<size_t>(it - emitterCdf.begin(), emitters.size() - 1)];
  }
};

class PathTracer {
 public:
  PathTracer(const Scene& scene, const ReferenceParams& params)
      : scene_(scene), rays_(scene), surfaces_(scene), params_(params) {
    offset_ = params.rayOffset > 0.0f ? params.rayOffset : std::max(1e-5f * rays_.diagonal(), 1e-6f);
  }

  /// One path's estimate of ρ·H at the point (B minus the point's own emission).
  glm::vec3 reflected(const SamplePoint& point, Pcg32& rng, uint64_t& rayCount) const {
    glm::vec3 throughput = glm::clamp(point.albedo, 0.0f, 1.0f);
    if (maxComponent(throughput) <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 sum(0.0f);
    glm::vec3 x = point.position;
    glm::vec3 n = point.normal;
    for (int bounce = 0; bounce < params_.maxBounces; ++bounce) {
      const glm::vec3 origin = x + offset_ * n;
      sum += throughput * directLight(x, origin, n, rng, rayCount);

      const glm::vec3 dir = sampleCosine(n, rng.uniform(), rng.uniform());
      ++rayCount;
      const RayScene::Hit hit = rays_.intersect(origin, dir);
      if (!hit) break;
      const auto t = static_cast<size_t>(hit.triangle);
      const glm::vec3& ny = surfaces_.normal[t];
      const float cosY = -glm::dot(ny, dir);
      if (cosY <= 0.0f) break;  // a back face: one-sided surfaces show black from behind
      if (surfaces_.emitterPdfArea[t] > 0.0f) {
        const float pdfLight = surfaces_.emitterPdfArea[t] * hit.t * hit.t / cosY;
        const float pdfBsdf = std::max(glm::dot(n, dir), 0.0f) / kPi;
        // π·L with L = E/π: the BSDF strategy's estimate of H is w·E.
        sum += throughput * powerHeuristic(pdfBsdf, pdfLight) * surfaces_.emission[t];
      }
      throughput *= surfaces_.albedo[t];
      if (bounce + 1 >= params_.rouletteAfter) {
        const float survive = std::min(0.95f, maxComponent(throughput));
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

 private:
  /// Next-event estimate of the irradiance at x from one point on one emitter, MIS-weighted.
  glm::vec3 directLight(const glm::vec3& x, const glm::vec3& origin, const glm::vec3& n, Pcg32& rng,
                        uint64_t& rayCount) const {
    if (surfaces_.emitters.empty()) return glm::vec3(0.0f);
    const uint32_t e = surfaces_.pickEmitter(rng.uniform());
    const Triangle& tri = scene_.triangles[e];
    const float su = std::sqrt(rng.uniform());
    const float b1 = 1.0f - su, b2 = rng.uniform() * su;
    const glm::vec3 y = b1 * tri.p[0] + b2 * tri.p[1] + (1.0f - b1 - b2) * tri.p[2];
    const glm::vec3& ny = surfaces_.normal[e];
    const glm::vec3 d = y - x;
    const float r2 = glm::dot(d, d);
    if (r2 <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 w = d / std::sqrt(r2);
    const float cosX = glm::dot(n, w);
    const float cosY = -glm::dot(ny, w);
    if (cosX <= 0.0f || cosY <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 target = y + offset_ * ny;
    const glm::vec3 toTarget = target - origin;
    const float distance = glm::length(toTarget);
    ++rayCount;
    if (distance <= offset_ || rays_.occluded(origin, toTarget / distance, 0.0f, distance - offset_))
      return glm::vec3(0.0f);
    const float pdfLight = surfaces_.emitterPdfArea[e] * r2 / cosY;  // per steradian
    const float pdfBsdf = cosX / kPi;
    return powerHeuristic(pdfLight, pdfBsdf) * (surfaces_.emission[e] / kPi) * cosX / pdfLight;
  }

  const Scene& scene_;
  RayScene rays_;
  SurfaceTable surfaces_;
  ReferenceParams params_;
  float offset_ = 0.0f;
};

}  // namespace

ReferenceResult traceReference(const Scene& scene, std::span<const SamplePoint> points,
                               const ReferenceParams& params, Context& ctx) {
  if (params.spp < 2) throw InputError("--spp", "needs at least 2 samples per texel, got " + std::to_string(params.spp));
  auto timer = ctx.time("reference");
  const PathTracer tracer(scene, params);

  ReferenceResult result;
  result.spp = params.spp;
  result.radiosity.assign(points.size(), glm::vec3(0.0f));
  result.standardError.assign(points.size(), glm::vec3(0.0f));
  std::atomic<uint64_t> rays{0};

  // Chunks run one after another so that progress is reported from this thread only.
  const size_t chunks = std::clamp<size_t>(points.size() / 256, 1, 100);
  for (size_t c = 0; c < chunks; ++c) {
    const size_t begin = points.size() * c / chunks, end = points.size() * (c + 1) / chunks;
    tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 4), [&](const tbb::blocked_range<size_t>& range) {
      uint64_t localRays = 0;
      for (size_t i = range.begin(); i < range.end(); ++i) {
        const SamplePoint& point = points[i];
        Pcg32 rng(splitmix64(params.seed ^ splitmix64(i)));
        glm::dvec3 sum(0.0), sumSquares(0.0);
        for (int s = 0; s < params.spp; ++s) {
          const glm::dvec3 value(tracer.reflected(point, rng, localRays));
          sum += value;
          sumSquares += value * value;
        }
        const double n = params.spp;
        const glm::dvec3 mean = sum / n;
        const glm::dvec3 variance = glm::max((sumSquares - n * mean * mean) / (n - 1.0), 0.0);
        result.radiosity[i] = glm::vec3(glm::dvec3(point.emission) + mean);
        result.standardError[i] = glm::vec3(glm::sqrt(variance / n));
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
                               Context& ctx) {
  std::vector<SamplePoint> points;
  std::vector<size_t> texels;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    points.push_back({atlas.position[i], atlas.normal[i], atlas.albedo[i], atlas.emission[i]});
    texels.push_back(i);
  }
  ReferenceResult compact = traceReference(scene, points, params, ctx);
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
