// How the progressive solvers cut a shooter patch up (radiosity/gpu/gl_shot_regions.cpp,
// radiosity/cpu/ray_shot.cpp): visibility regions, each seen from an eye point on the region (an item buffer
// on the GPU, rays on the CPU) and with its own residual pyramid (sub-shooters for the form factor,
// shaders/shooter_pyramid.comp). The eye is placed where the region is open: a lamp hanging 1 cm under a
// ceiling's centre or a cube standing on a floor must not hide the whole region's light (design.md §6, "a
// large shooter treated as a point").
#pragma once

#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct ShooterLayout {
  glm::vec3 tangent{0.0f}, bitangent{0.0f}, normal{0.0f};  ///< the item buffers' frame
  glm::ivec2 regions{1};                                   ///< along the chart's x and y
  std::vector<glm::ivec4> rects;  ///< per region (row-major): chart texels x0, y0, x1, y1 (exclusive)
  std::vector<glm::vec3> eyes;    ///< per region: a texel sample point of the region
  float texelRadius = 0.0f;       ///< half a texel's longer diagonal, m
};

struct LayoutParams {
  LayoutParams() = default;
  LayoutParams(float size, int regions, std::vector<uint8_t> openingPatches = {})
      : regionSize(size), maxRegions(regions), openings(std::move(openingPatches)) {}

  float regionSize = 1.0f;  ///< metres per region along a chart edge (see SolverParams)
  int maxRegions = 2;       ///< per chart edge
  /// Per patch (empty: none), non-zero for an opening: a cell's portal, cut into `openingRegions` per
  /// chart edge whatever its size (up to its texels). A portal sits in its wall's thickness, between
  /// the reveals, so a receiver off its axis sees a strip of it hidden by a jamb; one eye for a 1 m region
  /// gave the region's whole light past that jamb (a door 5 m away got 9 % more than exact from plan 8's
  /// R1:R3 portal, bench/RESULTS.md "The portals' error").
  std::vector<uint8_t> openings;
  int openingRegions = 4;
};

/// Lays out every patch of the atlas. For each region the eye is the candidate texel (the centre and a
/// 3×3 grid over the region) whose surroundings are most open: the largest distance to the nearest
/// triangle along five rays (the normal and four 60° tilts), capped at the region's size; ties go to
/// the candidate nearest the centre. Deterministic. Past `deadline` it stops between batches of patches and
/// returns the layouts of the first patches only (fewer than atlas.patches): an engine's set-up then stops.
std::vector<ShooterLayout> layoutShooters(
    const Scene& scene, const LightmapAtlas& atlas, const LayoutParams& params,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

}  // namespace cpgi
