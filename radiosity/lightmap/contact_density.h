// How fine the light must be solved on each surface (issue 13). Light that has bounced is smooth on a
// scale of the distances to what the surface sees, so a coarse atlas carries it, except where something
// stands close in front of a surface: a lamp hung 1 cm under a ceiling shades the ceiling above it from
// every bounce with an edge as sharp as its own, which a coarse texel smears half a texel into the light
// (openings' lamp room: 4 % RMSE at 5 texels/m against 0.5 % at 10). Such surfaces get texels of about half
// the gap, up to the output's resolution.
#pragma once

#include <chrono>
#include <span>
#include <vector>

#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

/// Per scene triangle, the output atlas's texel density there (texels per metre along its chart's
/// coarser texel edge; 0 for a triangle it does not hold).
std::vector<float> outputDensity(const LightmapAtlas& atlas, size_t triangleCount);

/// Per scene triangle, `coarse`, or where something lies within 2 / coarse metres in front of it (rays
/// along its normal from points about half a coarse texel apart, at least 4 of them hitting: about a
/// coarse texel's area), 2 / that gap (the 4th nearest hit), at most `fine` of the triangle (and never
/// below `coarse`, unless `fine` is: never finer than the output). A triangle whose every point finds
/// something within 2 / coarse metres is covered all over and keeps `coarse`: its shade has no edge inside.
/// Past `deadline` it stops between batches of triangles: those not reached keep `coarse` (or `fine`).
std::vector<float> contactDensity(
    const Scene& scene, const RayScene& rays, float coarse, std::span<const float> fine,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

}  // namespace cpgi
