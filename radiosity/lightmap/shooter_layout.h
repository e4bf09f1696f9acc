// How the progressive solvers cut a shooter patch up (radiosity/gpu/gl_shot_engine.cpp,
// radiosity/cpu/ray_shot.cpp): visibility regions, each seen from an eye point on the region (an item buffer
// on the GPU, rays on the CPU) and with its own residual pyramid (sub-shooters for the form factor,
// shaders/shooter_pyramid.comp). The eye is placed where the region is open: a lamp hanging 1 cm under a
// ceiling's centre or a cube standing on a floor must not hide the whole region's light (design.md §6, "a
// large shooter treated as a point").
#pragma once

#include <chrono>
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
  float regionSize = 1.0f;  ///< metres per region along a chart edge (see SolverParams)
  int maxRegions = 2;       ///< per chart edge
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
