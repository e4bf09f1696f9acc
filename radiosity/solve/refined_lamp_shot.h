// The lamps' shot at the output's texels only where its light varies (issue 13). Direct light from an
// area lamp is smooth except at shadow and beam edges, in penumbrae and near the lamp, yet each output
// texel costs the shot a visibility test and a form factor per eye (seed3 at 64² texels per quad: 16 eyes
// on 4.9 M texels, 41 s of an 83 s bake). So the lamps shoot first onto a coarser atlas of the same scene;
// where its texels say the light is smooth (their values close, no edge, penumbra or lamp among them,
// LampFlag) the output texels take it interpolated, and the lamps shoot again onto the output atlas for the
// other texels alone, with each shot scaled as the coarse one was (what the eyes saw covered is the same
// shot's, whatever the receivers' texels).
#pragma once

#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

struct RefinedLampParams {
  /// The coarse shot's texels per metre: the output's divided by `coarsening`, not below `minDensity`
  /// (or the output's where that is coarser). Where the coarse atlas would hold more than a quarter of the
  /// output's texels, the lamps shoot on the output atlas alone.
  float coarsening = 4.0f;
  float minDensity = 10.0f;
  /// Output texels next to coarse texels where interpolation would miss by more than `tolerance` × (their
  /// value + `floorShare` × the mean over the scene's lit texels) are shot at their own resolution.
  float tolerance = 0.01f;
  float floorShare = 0.01f;
};

struct RefinedLampData {
  size_t coarseTexels = 0;  ///< valid texels of the coarse shot's atlas (0: the output's shot alone)
  size_t refinedTexels =
      0;  ///< output texels shot at their own resolution (all of them when coarseTexels is 0)
  double coarseSeconds = 0.0, fineSeconds = 0.0;
};

/// Shadow rays per texel and lamp of the lamps' shot on an engine without lamp shots of its own, when
/// SolverParams::lampRays gives none (the command line's default).
inline constexpr int kLampRaysOnCpu = 64;

/// The first shot of every emitter patch (and the scene's punctual lights and sky, as solveProgressive
/// shoots them) over `atlas`, the output's atlas built from `quads` with `atlasParams`: radiosity, incident
/// (the direct irradiance) and residual per texel, energy as one solve's after those shots (received never
/// above what was shot), shots, shooters and their scales. With SolverParams::lampRays, or on an engine
/// without lamp shots (EngineFeatures::lampShots: the rays), the lamps are shot by shadow rays at every
/// output texel instead (shootFirstOnCpu, SolverParams::lampRays or kLampRaysOnCpu); the coarse and
/// refined item-buffer shots are for `lampRays` 0 on the GL engine.
SolveResult shootLampsRefined(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                              const AtlasParams& atlasParams, const RefinedLampParams& params,
                              const SolverParams& settings, ShotEngine& engine, Context& ctx,
                              const SolveControls& controls, RefinedLampData* data = nullptr);

}  // namespace cpgi
