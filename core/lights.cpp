#include "core/lights.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cpgi {

float spotFactor(const PunctualLight& light, float cosAngle) {
  if (light.kind != PunctualLight::Kind::Spot) return 1.0f;
  const float cosOuter = std::cos(light.outerCone), cosInner = std::cos(light.innerCone);
  const float ramp = std::clamp((cosAngle - cosOuter) / std::max(cosInner - cosOuter, 1e-4f), 0.0f, 1.0f);
  return ramp * ramp;
}

LightArrival lightArrival(const PunctualLight& light, const glm::vec3& x, const glm::vec3& n) {
  LightArrival a;
  if (light.kind == PunctualLight::Kind::Directional) {
    a.toLight = -light.direction;
    a.distance = std::numeric_limits<float>::infinity();
    a.irradiance = light.intensity * std::max(glm::dot(n, a.toLight), 0.0f);
    return a;
  }
  const glm::vec3 d = light.position - x;
  const float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return a;
  a.distance = std::sqrt(d2);
  a.toLight = d / a.distance;
  const float cosReceiver = glm::dot(n, a.toLight);
  if (cosReceiver <= 0.0f) return a;
  float window = 1.0f;
  if (light.range > 0.0f) {
    const float r = a.distance / light.range, r4 = r * r * r * r;
    window = std::clamp(1.0f - r4, 0.0f, 1.0f);
    window *= window;
  }
  a.irradiance = light.intensity *
                 (spotFactor(light, glm::dot(light.direction, -a.toLight)) * window * cosReceiver / d2);
  return a;
}

glm::dvec3 punctualPower(const PunctualLight& light) {
  constexpr double pi = std::numbers::pi;
  const glm::dvec3 intensity(light.intensity);
  switch (light.kind) {
    case PunctualLight::Kind::Point:
      return 4.0 * pi * intensity;
    case PunctualLight::Kind::Spot: {
      const double cosInner = std::cos(double(light.innerCone)), cosOuter = std::cos(double(light.outerCone));
      return 2.0 * pi * intensity * ((1.0 - cosInner) + (cosInner - cosOuter) / 3.0);
    }
    case PunctualLight::Kind::Directional:
      break;
  }
  return glm::dvec3(0.0);
}

}  // namespace cpgi
