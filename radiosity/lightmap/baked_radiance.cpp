#include "radiosity/lightmap/baked_radiance.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/lights.h"
#include "core/sky.h"
#include "radiosity/lightmap/lightmap_sampling.h"

namespace cpgi {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// A counter-based generator: the jitter of sample k at a point depends on (seed, k) alone, whatever the
// thread that draws it.
float uniform01(uint64_t seed, uint64_t k) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + k * 0xD1B54A32D192ED03ull + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return float(z >> 40) * (1.0f / 16777216.0f);
}

// An orthonormal frame around unit n (Duff et al., "Building an orthonormal basis, revisited", 2017).
void frameOf(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

}  // namespace

BakedRadiance::BakedRadiance(const Scene& scene, const RayScene& rays, const LightmapAtlas& atlas,
                             const std::vector<glm::vec3>& radiosity)
    : scene_(scene), rays_(rays), atlas_(atlas), reflected_(atlas.texelCount(), glm::vec3(0.0f)) {
  double total = 0.0;
  for (size_t i = 0; i < atlas.texelCount(); ++i) {
    if (atlas.patch[i] < 0) continue;
    reflected_[i] = glm::max(radiosity[i] - atlas.emission[i], glm::vec3(0.0f));
    const glm::vec3 le = atlas.emission[i];
    const double power = (double(le.r) + le.g + le.b) * atlas.area[i];
    if (!(power > 0.0)) continue;
    emitters_.push_back(uint32_t(i));
    total += power;
    emitterCdf_.push_back(total);
  }
  for (double& c : emitterCdf_) c /= total;
  emitterChance_.assign(atlas.texelCount(), 0.0f);
  for (size_t k = 0; k < emitters_.size(); ++k)
    emitterChance_[emitters_[k]] = float(emitterCdf_[k] - (k > 0 ? emitterCdf_[k - 1] : 0.0));
  dilate(atlas, reflected_);
  // The offset of the bake's own rays (radiosity/lightmap/direct_light.cpp), so both see the same thin
  // occluders.
  offset_ = std::max(1e-5f * rays.diagonal(), 1e-6f);
}

uint64_t BakedRadiance::raysTraced() const {
  return traced_.load();
}

void BakedRadiance::gather(const glm::vec3& x, const glm::vec3& normal, uint64_t seed,
                           const GatherParams& params, std::vector<ArrivalSample>& out) const {
  out.clear();
  const glm::vec3 origin = x + offset_ * normal;
  const int side = std::max(1, int(std::lround(std::sqrt(double(std::max(params.rays, 1))))));
  const int emitterSamples = emitters_.empty() ? 0 : std::max(params.emitterSamples, 0);
  gatherDirections(origin, normal, seed, side, emitterSamples, out);
  gatherEmitters(origin, normal, seed, side * side, emitterSamples, out);
  gatherLights(origin, normal, out);
}

float BakedRadiance::emitterDensity(uint32_t texel, float r2, float cosEmitter) const {
  return emitterChance_[texel] * r2 / (atlas_.area[texel] * cosEmitter);
}

// Stratified directions, uniform by solid angle over the hemisphere of `normal` (the sphere when it is
// zero): what each ray finds stands for 2π/N (4π/N) of solid angle. An emissive surface's Le is weighted
// against the emitter draws' density there (power heuristic).
void BakedRadiance::gatherDirections(const glm::vec3& origin, const glm::vec3& normal, uint64_t seed,
                                     int side, int emitterSamples, std::vector<ArrivalSample>& out) const {
  const bool sphere = normal == glm::vec3(0.0f);
  glm::vec3 t(1, 0, 0), b(0, 1, 0), n(0, 0, 1);
  if (!sphere) n = normal, frameOf(n, t, b);
  const float directionDensity = float(side * side) / ((sphere ? 4.0f : 2.0f) * kPi);  // N p_d
  const bool sky = scene_.sky.lights();
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const uint64_t k = uint64_t(j * side + i);
      const float u1 = (float(i) + uniform01(seed, 2 * k)) / float(side);
      const float u2 = (float(j) + uniform01(seed, 2 * k + 1)) / float(side);
      const float z = sphere ? 1.0f - 2.0f * u1 : u1, r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const float phi = 2.0f * kPi * u2;
      const glm::vec3 w = r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
      const RayScene::Hit hit = rays_.intersect(origin, w, sphere ? 0.0f : offset_);
      glm::vec3 radiance(0.0f);
      if (!hit) {
        if (sky) radiance = glm::vec3(skyRadiance(scene_.sky, w));
      } else if (glm::dot(scene_.triangles[size_t(hit.triangle)].geometricNormal(), w) < 0.0f) {
        const std::array<glm::vec2, 3>& uv = atlas_.triangleUV[size_t(hit.triangle)];
        const glm::vec2 at = (1.0f - hit.u - hit.v) * uv[0] + hit.u * uv[1] + hit.v * uv[2];
        radiance = sampleBilinear(atlas_.width, atlas_.height, reflected_, at) / kPi;
        const int tx = std::clamp(int(at.x * float(atlas_.width)), 0, atlas_.width - 1);
        const int ty = std::clamp(int(at.y * float(atlas_.height)), 0, atlas_.height - 1);
        const uint32_t texel = uint32_t(ty) * uint32_t(atlas_.width) + uint32_t(tx);
        if (atlas_.patch[texel] >= 0 && atlas_.emission[texel] != glm::vec3(0.0f)) {
          const float cosEmitter = -glm::dot(atlas_.normal[texel], w);
          float weight = 1.0f;
          if (emitterSamples > 0 && emitterChance_[texel] > 0.0f && cosEmitter > 0.0f) {
            const float drawn = float(emitterSamples) * emitterDensity(texel, hit.t * hit.t, cosEmitter);
            weight =
                directionDensity * directionDensity / (directionDensity * directionDensity + drawn * drawn);
          }
          radiance += weight * atlas_.emission[texel] / kPi;
        }
      }
      if (radiance != glm::vec3(0.0f)) out.push_back({w, radiance / directionDensity});
    }
  traced_ += uint64_t(side) * uint64_t(side);
}

// Points on the emissive texels, texel drawn by its power and the point uniform over its parallelogram.
void BakedRadiance::gatherEmitters(const glm::vec3& origin, const glm::vec3& normal, uint64_t seed,
                                   int directions, int samples, std::vector<ArrivalSample>& out) const {
  if (emitters_.empty() || samples <= 0) return;
  const float directionDensity = float(directions) / ((normal == glm::vec3(0.0f) ? 4.0f : 2.0f) * kPi);
  const uint64_t base = 1ull << 40;  // apart from gatherDirections' draws
  for (int s = 0; s < samples; ++s) {
    const float pick = (float(s) + uniform01(seed, base + 3 * uint64_t(s))) / float(samples);
    const size_t k = std::min(
        size_t(std::lower_bound(emitterCdf_.begin(), emitterCdf_.end(), double(pick)) - emitterCdf_.begin()),
        emitters_.size() - 1);
    const uint32_t texel = emitters_[k];
    const Patch& p = atlas_.patches[size_t(atlas_.patch[texel])];
    const int i = int(texel % uint32_t(atlas_.width)) - p.x, j = int(texel / uint32_t(atlas_.width)) - p.y;
    const glm::vec3 y = p.origin + (float(i) + uniform01(seed, base + 3 * uint64_t(s) + 1)) * p.texelU +
                        (float(j) + uniform01(seed, base + 3 * uint64_t(s) + 2)) * p.texelV;
    const glm::vec3 d = y - origin;
    const float r2 = glm::dot(d, d);
    if (!(r2 > 0.0f)) continue;
    const float r = std::sqrt(r2);
    const glm::vec3 w = d / r;
    const float cosEmitter = -glm::dot(atlas_.normal[texel], w);
    if (cosEmitter <= 0.0f || (normal != glm::vec3(0.0f) && glm::dot(normal, w) <= 0.0f)) continue;
    ++traced_;
    if (rays_.occluded(origin, w, 0.0f, r * (1.0f - 1e-4f) - offset_)) continue;
    // Le/π / (M p_e) times the power heuristic's weight (M p_e)² / ((N p_d)² + (M p_e)²).
    const float drawn = float(samples) * emitterDensity(texel, r2, cosEmitter);
    out.push_back(
        {w, atlas_.emission[texel] / kPi * drawn / (directionDensity * directionDensity + drawn * drawn)});
  }
}

// The punctual lights, each one direction: its irradiance on a surface facing it.
void BakedRadiance::gatherLights(const glm::vec3& origin, const glm::vec3& normal,
                                 std::vector<ArrivalSample>& out) const {
  for (const PunctualLight& light : scene_.lights) {
    const glm::vec3 towards = lightArrival(light, origin, glm::vec3(0, 1, 0)).toLight;
    if (normal != glm::vec3(0.0f) && glm::dot(normal, towards) <= 0.0f) continue;
    const LightArrival a = lightArrival(light, origin, towards);
    if (!(a.irradiance.r + a.irradiance.g + a.irradiance.b > 0.0f)) continue;
    ++traced_;
    const float far = std::isinf(a.distance) ? 3.0e38f : a.distance - offset_;
    if (far > 0.0f && rays_.occluded(origin, a.toLight, 0.0f, far)) continue;
    out.push_back({a.toLight, a.irradiance});
  }
}

}  // namespace cpgi
