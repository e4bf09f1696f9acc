// The lamps' first shot by rays: the light every emissive patch sends straight to every texel, from the
// exact unoccluded form factor (Lambert's contour over the lamp) and the share of the lamp each receiver
// sees through Embree shadow rays, instead of item buffers drawn from a few eye points on the lamp.
//
// Why: a small lamp is all penumbra. Out of spot-door's housing, 0.1 m of lamp gives a beam whose edge is
// 0.7 m wide on the far wall; 16 eye points cut it into steps, and the texels on the steps were 20 % off
// the reference (issue 11: 6 texels, 77 % of the lit room's error) whatever the item buffer's size. Rays
// per texel see a lamp's every point alike, and cost texels × lamps × rays: a few million rays on the
// seed scenes, under a second on two cores.
//
// Estimate per texel and lamp, over the texel's footprint so that its value is its mean, as the
// reference's (radiosity/reference/reference_tracer.h): 2×2 points at the centres of the texel's quarters
// (8×8 within three texels of the lamp, where F is steep), each with the lamp's contour form factor F there
// and `rays` / 4 points on the lamp (Roberts' R2); the seen share is Σ V k / Σ k with k the point-to-point
// kernel cosθ cosθ' / r², exact wherever the lamp is wholly seen or wholly hidden. A penumbra (the rays
// disagreed, or a neighbour saw the lamp otherwise) is traced again with 16× the rays, each from its own
// point of the texel to its own point of the lamp on a joint 4-D low-discrepancy set (area sampling).
// Measured in bench/RESULTS.md ("The lamps' first shot by rays").
#pragma once

#include <chrono>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

struct LampLight {
  std::vector<glm::vec3> irradiance;  ///< per atlas texel, W/m²; 0 on padding
  std::vector<char> shot;             ///< per patch: 1 for a lamp shot here (its emission is spent)
  double emitted = 0.0;               ///< W (R + G + B) the shot lamps emit
  double landed = 0.0;                ///< W (R + G + B) that reached a texel
  uint64_t rays = 0;                  ///< shadow rays traced
  uint64_t hiddenTexels = 0;          ///< texels × lamps whose rays were not traced, known hidden (LampCull)
  uint64_t tracedHiddenTexels = 0;    ///< texels × lamps traced and found hidden by every ray
};

/// Which texels the lamps' shot leaves untraced. Occluders: a texel that one convex piece of the scene (a
/// triangle, or a rectangle of two: occluder_pieces.h) hides from the whole lamp gets every ray hidden
/// without tracing it, as tracing would give: the result is the same to the bit, for a fraction of the
/// rays in a building whose texels face lamps behind walls. None traces them all (the check of that).
enum class LampCull : uint8_t { None, Occluders };

/// The patches that shoot by rays: those whose material emits and whose texels carry that emission (a
/// cell's first-shot group zeroes the emission of other groups' lamps; they shoot elsewhere).
std::vector<char> lampPatches(const Scene& scene, const LightmapAtlas& atlas);

/// Shoots the lamps flagged in `lamps` (one per patch) to every valid texel of `atlas`, occluded by
/// `occluders` (the whole scene). `rays` per texel and lamp (a multiple of 4, ≥ 4), 16× in penumbrae. A lamp
/// whose texels would gather more than it emits (texels next to it) is scaled back to its power: no light
/// is made up. Deterministic: each texel draws from its own index, whatever the thread count. At `deadline`
/// (checked before each lamp) the lamps not yet shot are left out of `shot`, for the caller to leave unshot
/// (a bake's --time-limit: a partial result). `occluders` must be built from `scene`: the cull takes its
/// pieces from the scene's triangles.
LampLight shootLampsByRays(
    const Scene& scene, const RayScene& occluders, const LightmapAtlas& atlas, const std::vector<char>& lamps,
    int rays, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    LampCull cull = LampCull::Occluders);

}  // namespace cpgi
