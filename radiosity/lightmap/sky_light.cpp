#include "radiosity/lightmap/sky_light.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

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

// The irradiance at one texel: (π/N) Σ L(ω_k) over the N cosine-distributed directions that leave the
// scene (pdf cos θ/π, so each sample's estimate of ∫ L cos θ dω is π L).
float gatherAt(const Sky& sky, const RayScene& occluders, const glm::vec3& origin, const glm::vec3& n,
               uint64_t texel) {
  // An orthonormal frame about n (Duff et al. 2017).
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  const glm::vec3 t1(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), t2(b, sign + n.y * n.y * a, -n.y);
  const uint64_t h = mix64(texel);
  const double shift1 = double(h >> 40) * 0x1p-24, shift2 = double((h >> 16) & 0xffffff) * 0x1p-24;
  constexpr double g = 1.32471795724474602596;  // plastic number: Roberts' R2 sequence
  double sum = 0.0;
  for (int k = 0; k < sky.gatherRays; ++k) {
    const float u1 = fraction(shift1 + double(k) / g), u2 = fraction(shift2 + double(k) / (g * g));
    const float phi = 2.0f * kPi * u1, r = std::sqrt(u2);
    const glm::vec3 dir =
        glm::normalize(r * std::cos(phi) * t1 + r * std::sin(phi) * t2 + std::sqrt(1.0f - u2) * n);
    const float radiance = skyRadiance(sky, dir);
    if (radiance > 0.0f && !occluders.occluded(origin, dir, 0.0f, 3.0e38f)) sum += radiance;
  }
  return float(double(kPi) * sum / sky.gatherRays);
}

}  // namespace

void addSkyLight(const Sky& sky, const RayScene& occluders, const LightmapAtlas& atlas, DirectLight& direct,
                 Context& ctx) {
  if (!sky.lights()) return;
  auto timer = ctx.time("sky light");
  direct.irradiance.resize(atlas.texelCount(), glm::vec3(0.0f));
  // The same offset off the surface as the punctual lights' shadow rays and the reference's paths.
  const float offset = std::max(1e-5f * occluders.diagonal(), 1e-6f);
  std::vector<float> irradiance(atlas.texelCount(), 0.0f);
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, atlas.texelCount(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
          if (atlas.patch[i] >= 0)
            irradiance[i] =
                gatherAt(sky, occluders, atlas.position[i] + offset * atlas.normal[i], atlas.normal[i], i);
      });
  // Summed in texel order: the same total whatever the thread count.
  double landed = 0.0;
  for (size_t i = 0; i < irradiance.size(); ++i) {
    if (!(irradiance[i] > 0.0f)) continue;
    direct.irradiance[i] += glm::vec3(irradiance[i]);
    landed += 3.0 * double(irradiance[i]) * atlas.area[i];
  }
  direct.landed += landed;
  direct.directionalLanded += landed;
}

DirectLight shootPunctualAndSky(const Scene& scene, const LightmapAtlas& atlas, Context& ctx) {
  const RayScene rays(scene);
  DirectLight direct = shootPunctualLights(scene.lights, rays, atlas, ctx);
  addSkyLight(scene.sky, rays, atlas, direct, ctx);
  return direct;
}

}  // namespace cpgi
