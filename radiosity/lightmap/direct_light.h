// The exact first shot of the scene's punctual lights (KHR_lights_punctual, core/lights.h) onto an atlas:
// a progressive solver cannot shoot a point source (it has no area to put in an item buffer), and needs
// not, since the light it sends to each texel is known in closed form. Each valid texel gets the
// irradiance every light gives its sample point, with one Embree shadow ray per light and texel (TBB
// parallel); a solver then starts from it as light already shot (radiosity/gpu/gl_shot_engine.h,
// SolveResult's energy: the lights' power counts as emitted and shot, what lands as received).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

struct DirectLight {
  std::vector<glm::vec3> irradiance;  ///< per atlas texel, W/m²; 0 on padding and skipped patches
  double landed = 0.0;                ///< Σ irradiance × area, W summed over R, G, B
  /// The part of `landed` from sources at infinity, directional lights and the sky (sky_light.h), whose
  /// power is what the scene intercepts.
  double directionalLanded = 0.0;
};

/// The lights' direct irradiance at every valid texel of `atlas`, occluded by `occluders` (build it from
/// the whole scene: light from a lamp in one room lands through a door in the next). Texels of patches
/// marked in `skipPatch` (one flag per patch, or empty) get none: a cell's portal patches, whose light
/// already lands beyond them. Surfaces are one-sided: a texel facing away from a light gets nothing from it.
/// A point or spot light whose texel-centre sum would exceed its power (coarse texels next to it in a
/// closed room) is scaled back to its power: no light is made up.
DirectLight shootPunctualLights(const std::vector<PunctualLight>& lights, const RayScene& occluders,
                                const LightmapAtlas& atlas, Context& ctx,
                                const std::vector<char>& skipPatch = {});

/// What the lights emit, W summed over R, G, B: point and spot lights by core/lights.h's punctualPower;
/// directional lights by what `landed` says they delivered (an infinite source's power is what the scene
/// intercepts), so that none of their light counts as escaped.
double punctualEmitted(const std::vector<PunctualLight>& lights, double directionalLanded);

}  // namespace cpgi
