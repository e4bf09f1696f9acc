// How a KHR_lights_punctual light (core/scene.h, PunctualLight) lights a point: the one definition of a
// light's falloff that every back end evaluates (the bake's exact first shot, the path-traced reference's
// next-event estimation), each with its own visibility. Formulas of the glTF extension's specification:
// inverse square with the optional smooth range window, the spot's cone falloff, cosine at the receiver.
#pragma once

#include <glm/glm.hpp>

#include "core/scene.h"

namespace cpgi {

/// Lumens per watt: glTF's photometric units (candela, lux) → cpgi's radiometric ones (W/sr, W/m²).
/// Blender's glTF exporter converts with the same constant, so a P-watt Blender lamp reads back as P W.
constexpr double kLumensPerWatt = 683.0;

/// A spot's intensity relative to its axis for a direction at `cosAngle` from it: 1 within the inner cone,
/// 0 beyond the outer one, and in between the square of the linear ramp in cos (the glTF extension's
/// recommended falloff). 1 for point and directional lights.
float spotFactor(const PunctualLight& light, float cosAngle);

/// What one light gives a surface point, before any occlusion test.
struct LightArrival {
  glm::vec3 toLight{0.0f};     ///< unit direction from the point towards the light
  float distance = 0.0f;       ///< metres to the light; +inf for a directional light
  glm::vec3 irradiance{0.0f};  ///< W/m² per channel on a surface of normal n there; 0 behind it
};
/// The light at `x` on a surface of unit normal `n`: I(ω)·cosθ/d² (point, spot, with the range window) or
/// E·cosθ (directional).
LightArrival lightArrival(const PunctualLight& light, const glm::vec3& x, const glm::vec3& n);

/// The power a point or spot light emits, W per channel: ∫ I(ω) dΩ = 4π I for a point,
/// 2π I ((1 − cos inner) + (cos inner − cos outer)/3) for a spot (the range window is ignored: light it cuts
/// counts as escaped). Zero for a directional light, whose power is what the scene intercepts.
glm::dvec3 punctualPower(const PunctualLight& light);

}  // namespace cpgi
