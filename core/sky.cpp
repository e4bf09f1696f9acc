#include "core/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/scene.h"

namespace cpgi {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kDefaultHorizontalIrradiance = 15.0f;  // W/m²: ~10,000 lux at 683 lm/W

// Values a float solve can carry: the scene's own emission is refused past 1e20 W (core/scene_io).
constexpr float kMaxIrradiance = 1.0e12f;

bool inRange(float v, float lo, float hi) {
  return std::isfinite(v) && v >= lo && v <= hi;
}

}  // namespace

float horizontalIrradiance(Sky::Kind kind, float zenith) {
  switch (kind) {
    case Sky::Kind::Uniform:
      return kPi * zenith;  // ∫ L cos θ dω over the upper hemisphere
    case Sky::Kind::CieOvercast:
      return 7.0f * kPi * zenith / 9.0f;  // (Lz/3) 2π ∫₀¹ (1 + 2μ) μ dμ = (Lz/3) 2π (1/2 + 2/3)
    case Sky::Kind::None:
      break;
  }
  return 0.0f;
}

float skyRadiance(const Sky& sky, const glm::vec3& towards) {
  const float cosZenith = towards.y;
  if (!(cosZenith > 0.0f)) return sky.groundRadiance;
  switch (sky.kind) {
    case Sky::Kind::Uniform:
      return sky.zenithRadiance;
    case Sky::Kind::CieOvercast:
      return sky.zenithRadiance * (1.0f + 2.0f * cosZenith) / 3.0f;
    case Sky::Kind::None:
      break;
  }
  return 0.0f;
}

Sky makeSky(const SkyRequest& r) {
  Sky sky;
  sky.kind = r.kind;
  if (r.gatherRays < 1 || r.gatherRays > 65536)
    throw InputError("sky rays", "must be in [1, 65536], got " + std::to_string(r.gatherRays));
  sky.gatherRays = r.gatherRays;
  if (r.kind != Sky::Kind::None) {
    if (r.zenithRadiance && r.horizontalIrradiance)
      throw InputError("sky zenith", "give the sky's zenith radiance or its horizontal irradiance, not both");
    if (r.zenithRadiance) {
      if (!inRange(*r.zenithRadiance, 0.0f, kMaxIrradiance))
        throw InputError("sky zenith",
                         "must be a number in [0, 1e12] W/(m2 sr), got " + std::to_string(*r.zenithRadiance));
      sky.zenithRadiance = *r.zenithRadiance;
    } else {
      const float e = r.horizontalIrradiance.value_or(kDefaultHorizontalIrradiance);
      if (!inRange(e, 0.0f, kMaxIrradiance))
        throw InputError("sky irradiance", "must be a number in [0, 1e12] W/m2, got " + std::to_string(e));
      sky.zenithRadiance = e / horizontalIrradiance(r.kind, 1.0f);
    }
  } else if (r.zenithRadiance || r.horizontalIrradiance) {
    throw InputError("sky", "a sky's radiance or irradiance needs `sky` uniform or cie-overcast");
  }
  float sunOnGround = 0.0f;
  if (r.towardsSun) {
    const glm::vec3 d = *r.towardsSun;
    const float length = glm::length(d);
    if (!(std::isfinite(length) && length > 0.0f))
      throw InputError("sun", "the direction to the sun must be a non-zero vector of finite numbers");
    if (!(d.y / length > 0.0f)) throw InputError("sun", "the sun is below the horizon (Y is up)");
    if (!inRange(r.sunIrradiance, 0.0f, kMaxIrradiance))
      throw InputError("sun", "the irradiance must be a number in [0, 1e12] W/m2");
    sunOnGround = r.sunIrradiance * d.y / length;
  }
  if (r.groundAlbedo) {
    if (!inRange(*r.groundAlbedo, 0.0f, 1.0f))
      throw InputError("ground albedo", "must be in [0, 1] or none, got " + std::to_string(*r.groundAlbedo));
    sky.groundRadiance =
        *r.groundAlbedo * (horizontalIrradiance(sky.kind, sky.zenithRadiance) + sunOnGround) / kPi;
  }
  return sky;
}

void applySky(const SkyRequest& request, Scene& scene) {
  scene.sky = makeSky(request);
  if (!request.towardsSun || !(request.sunIrradiance > 0.0f)) return;
  PunctualLight sun;
  sun.kind = PunctualLight::Kind::Directional;
  sun.name = "sun";
  sun.direction = -glm::normalize(*request.towardsSun);
  sun.intensity = glm::vec3(request.sunIrradiance);
  scene.lights.push_back(sun);
}

const char* skyKindName(Sky::Kind kind) {
  switch (kind) {
    case Sky::Kind::Uniform:
      return "uniform";
    case Sky::Kind::CieOvercast:
      return "cie-overcast";
    case Sky::Kind::None:
      break;
  }
  return "none";
}

std::optional<Sky::Kind> skyKindOf(const std::string& name) {
  for (Sky::Kind k : {Sky::Kind::None, Sky::Kind::Uniform, Sky::Kind::CieOvercast})
    if (name == skyKindName(k)) return k;
  return std::nullopt;
}

}  // namespace cpgi
