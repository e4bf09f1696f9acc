// Directional lightmaps (issue 48 item 4): per texel, the L1 spherical harmonics of the light arriving
// there, four coefficients per colour channel in Godot's and Unity's basis and order
// (radiosity/lightmap/spherical_harmonics.h): L00, L1−1 (y), L10 (z), L11 (x), world axes of the scene
// file. A normal-mapped surface then shades with its bumped normal n: the vector irradiance V = (L11,
// L1−1, L10) / Y1 gives E(n) ≈ max(0, V · n), exact at the texel's own normal; Ramamoorthi & Hanrahan's
// evaluation (an engine's SH lightmap shader) gives E(n) = L00 π Y00 + 2π/3 Y1 (L1 · n).
//
// L1 SH rather than a dominant direction and an ambient colour: it is linear in the light, so it filters
// bilinearly and sums over sources (a room lit by two lamps and a window keeps each's share), and the
// irradiance vector inside it is exact for light from one side of a surface.
//
// Gathered after the solve, not in its shots: a ray gather over the baked radiosity (baked_radiance.h),
// the same on either engine, and through every path by which light reaches an output texel (the lamps'
// shot by rays or item buffers, the punctual lights and the sky's first shot, the coarse level's
// interreflection interpolated, a cell solve's portals), none of which would each have to carry 12 more
// floats a texel. The gather's directions are then scaled per channel so that V · n_s is the texel's
// irradiance (lightmap_irradiance.exr) exactly: its noise moves the direction, never the light's level.
#pragma once

#include <array>
#include <chrono>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/baked_radiance.h"

namespace cpgi {

struct DirectionalLightmap {
  /// Per coefficient (L00, L1−1, L10, L11), per atlas texel, RGB; 0 on padding (undilated).
  std::array<std::vector<glm::vec3>, 4> sh;
  /// Per atlas texel, the irradiance the gather found at the texel's normal before it was scaled to the
  /// solve's (V · n_s), for the checks; 0 on padding.
  std::vector<glm::vec3> gathered;
  size_t texels = 0;      ///< valid texels gathered
  bool complete = true;   ///< false: the deadline stopped the gather, and texels not gathered hold 0
  size_t undirected = 0;  ///< channels of valid texels with light the gather did not find (V = E n_s)
  uint64_t rays = 0;
  double seconds = 0.0;
};

/// Gathers the L1 SH of every valid texel of `atlas` from the bake's `radiosity` (per texel, W/m²,
/// undilated), scaled to `irradiance` (E per texel, engine_lightmap.h). Deterministic. Past `deadline`
/// (looked at every 64 texels) it stops with `complete` false.
DirectionalLightmap gatherDirectionalLightmap(
    const Scene& scene, const LightmapAtlas& atlas, const std::vector<glm::vec3>& radiosity,
    const std::vector<glm::vec3>& irradiance, const GatherParams& params, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

/// Texel `i`'s four coefficients, in order.
std::array<glm::vec3, 4> texelSh(const DirectionalLightmap& map, size_t i);

}  // namespace cpgi
