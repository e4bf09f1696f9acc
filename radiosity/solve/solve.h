// A progressive radiosity solve of one atlas (thesis ch. 6) on any shot engine: the exact first shot of
// the scene's punctual lights, sky and (SolverParams::lampRays) lamps on the CPU, then the shooting loop
// (progressive_loop.h) on the engine's backend, then the per-texel results read back.
#pragma once

#include <chrono>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/shot_engine.h"
#include "radiosity/solve/shot_shape.h"
#include "radiosity/solve/solve_controls.h"
#include "radiosity/solve/solver_params.h"

namespace cpgi {

/// Solves `atlas` with the user's `settings` on `engine`, stopping and reading back as `controls` say and
/// shooting as `shape` asks. `scene` supplies
/// occluders: every scene triangle blocks light, those outside the atlas receive none. Its punctual lights
/// (Scene::lights) and sky are shot first, exactly (radiosity/lightmap/direct_light.h): the solve starts
/// from their reflected light as unshot radiosity and counts their power as emitted and shot; a caller's
/// prior shot (SolveControls::priorShot) stands for them. Throws InputError for bad settings or a control
/// the engine cannot honour (EngineFeatures), SystemError for device failures.
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                             ShotEngine& engine, Context& ctx, const SolveControls& controls = {},
                             const ShotShape& shape = {});

/// The first shot alone, all of it on the CPU: the punctual lights and sky, and the lamps by `lampRays`
/// shadow rays per texel and lamp (> 0; 16× in penumbrae, radiosity/lightmap/lamp_light.h), up to
/// `controls.deadline`, the sky drawn partly towards `controls.skyOpenings` and stopped at skyDeadline (the
/// rest of `controls` is not read). As a solve after it: per texel the radiosity (emission + ρE), the
/// irradiance E and the residual ρE (the lamps' own light spent); energy with the lights' power emitted and
/// shot. What an engine without lamp shots of its own (EngineFeatures::lampShots) starts a two-level solve
/// from.
SolveResult shootFirstOnCpu(const Scene& scene, const LightmapAtlas& atlas, int lampRays, Context& ctx,
                            const SolveControls& controls = {});

}  // namespace cpgi
