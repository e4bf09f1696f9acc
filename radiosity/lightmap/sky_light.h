// The sky's share of the first shot (core/sky.h): the irradiance the sky dome and the ground at infinity
// give every texel, gathered with Embree rays in the texel's cosine-weighted hemisphere, added to the
// punctual lights' DirectLight. The solver then starts from ρE as unshot radiosity like any first shot
// (radiosity/gpu/gl_shot_engine.h); cell by cell, the first shot over the whole scene puts into each room
// the sky it sees through its openings (radiosity/cells/cell_first_shot.h).
//
// Why a gather and not emitter geometry: a dome of patches far outside the scene would shoot through
// item buffers in which the building is a few pixels across, and the light through a window would hinge
// on those pixels; a texel's hemisphere, by contrast, sees a window at its true solid angle. The sky is an
// infinite source, so its power is what the scene intercepts (as a directional light's): every W landed
// counts as emitted, and what the surfaces reflect back out of the scene is escaped.
#pragma once

#include <chrono>

#include "core/context.h"
#include "core/sky.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/direct_light.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/sky_openings.h"

namespace cpgi {

/// What a sky gather did: the directions per texel asked (Sky::gatherRays) and gathered.
struct SkyGatherData {
  int requestedRays = 0;
  int rays = 0;           ///< directions every texel's estimate has (fewer than asked after a deadline)
  bool timedOut = false;  ///< the deadline stopped it after a pass: a valid estimate with fewer rays
};

/// Adds the sky's irradiance at every valid texel of `atlas` to `direct` (irradiance, landed and
/// directionalLanded, since an infinite source emits what lands), occluded by `occluders` (the whole
/// scene). `sky.gatherRays` directions per texel, a randomly shifted low-discrepancy set (Roberts' R2) per
/// texel seeded by its index, so the result is the same for every run and thread count. A texel whose
/// hemisphere is closed (inside a closed building) gets exactly 0. Does nothing when !sky.lights().
/// The directions are gathered in passes over all texels (8, 16, 32, ... up to gatherRays), reported as
/// progress ("sky light") every few seconds; past `deadline` no pass starts or goes on, and every texel
/// keeps the estimate of the last whole pass, with a warning. The first pass goes first over every chart
/// row's first texel and every 16th after it, then over the others by a halving stride: cut short past
/// those, every texel it did not reach takes the estimate of the one before it in its row (within 15
/// texels). Without a deadline the result is that of one pass of gatherRays.
/// With `openings` (sky_openings.h: the outside's portals), a texel inside one of them draws half its
/// directions towards those before it, combined with the cosine half by the balance heuristic: the same
/// mean, without the noise of a sky seen through a small far door in a few of its cosine directions.
SkyGatherData addSkyLight(
    const Sky& sky, const RayScene& occluders, const LightmapAtlas& atlas, DirectLight& direct, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    const std::vector<SkyOpening>& openings = {});

/// The whole first shot made on the CPU: the scene's punctual lights (direct_light.h) and its sky, over
/// a ray scene of all its triangles; the sky gather stops at `deadline` and draws towards `openings` as
/// addSkyLight says.
DirectLight shootPunctualAndSky(
    const Scene& scene, const LightmapAtlas& atlas, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max(),
    const std::vector<SkyOpening>& openings = {});

}  // namespace cpgi
