#include "radiosity/lightmap/direct_light.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/lights.h"

namespace cpgi {

namespace {

// Per light, Σ irradiance × area (W, R + G + B) over the texels.
using LandedPerLight = std::vector<double>;

// One pass over the texels: every light's irradiance at every valid texel, times `scale` per light, into
// `irradiance`; returns what each light delivered.
LandedPerLight gather(const std::vector<PunctualLight>& lights, const RayScene& occluders,
                      const LightmapAtlas& atlas, const std::vector<char>& skipPatch,
                      const std::vector<float>& scale, std::vector<glm::vec3>& irradiance) {
  // Ray origins leave the surface by the reference's offset (radiosity/reference), so both see the same
  // thin occluders.
  const float offset = std::max(1e-5f * occluders.diagonal(), 1e-6f);
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, atlas.texelCount(), 256), LandedPerLight(lights.size(), 0.0),
      [&](const tbb::blocked_range<size_t>& range, LandedPerLight sum) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
          const int32_t patch = atlas.patch[i];
          if (patch < 0 || (!skipPatch.empty() && skipPatch[size_t(patch)])) continue;
          const glm::vec3 x = atlas.position[i], n = atlas.normal[i], origin = x + offset * n;
          glm::vec3 e(0.0f);
          for (size_t k = 0; k < lights.size(); ++k) {
            const LightArrival a = lightArrival(lights[k], x, n);
            if (!(a.irradiance.r + a.irradiance.g + a.irradiance.b > 0.0f)) continue;
            const float far = std::isinf(a.distance) ? 3.0e38f : a.distance - offset;
            if (far > 0.0f && occluders.occluded(origin, a.toLight, 0.0f, far)) continue;
            const glm::vec3 got = a.irradiance * scale[k];
            e += got;
            sum[k] += (double(got.r) + got.g + got.b) * atlas.area[i];
          }
          irradiance[i] = e;
        }
        return sum;
      },
      [](LandedPerLight a, const LandedPerLight& b) {
        for (size_t k = 0; k < a.size(); ++k) a[k] += b[k];
        return a;
      });
}

}  // namespace

DirectLight shootPunctualLights(const std::vector<PunctualLight>& lights, const RayScene& occluders,
                                const LightmapAtlas& atlas, Context& ctx,
                                const std::vector<char>& skipPatch) {
  auto timer = ctx.time("direct light");
  DirectLight out;
  out.irradiance.assign(atlas.texelCount(), glm::vec3(0.0f));
  if (lights.empty()) return out;
  std::vector<float> scale(lights.size(), 1.0f);
  LandedPerLight landed = gather(lights, occluders, atlas, skipPatch, scale, out.irradiance);
  // Texel centres sample I cosθ/d², which is steep next to a lamp: a closed room on coarse texels can sum
  // to more than the lamp emits (+0.4 % for a lamp 1 m from 25 cm texels). Such a light is scaled back to
  // its power, as the solver scales back a shot that delivered more than it carried, so that no light is
  // made up (escaped ≥ 0).
  bool rescaled = false;
  for (size_t k = 0; k < lights.size(); ++k) {
    if (lights[k].kind == PunctualLight::Kind::Directional) continue;
    const glm::dvec3 p = punctualPower(lights[k]);
    const double power = p.r + p.g + p.b;
    if (landed[k] > power) scale[k] = float(power / landed[k]), rescaled = true;
  }
  if (rescaled) landed = gather(lights, occluders, atlas, skipPatch, scale, out.irradiance);
  for (size_t k = 0; k < lights.size(); ++k) {
    out.landed += landed[k];
    if (lights[k].kind == PunctualLight::Kind::Directional) out.directionalLanded += landed[k];
  }
  return out;
}

double punctualEmitted(const std::vector<PunctualLight>& lights, double directionalLanded) {
  double power = directionalLanded;
  for (const PunctualLight& l : lights)
    if (l.kind != PunctualLight::Kind::Directional) {
      const glm::dvec3 p = punctualPower(l);
      power += p.r + p.g + p.b;
    }
  return power;
}

}  // namespace cpgi
