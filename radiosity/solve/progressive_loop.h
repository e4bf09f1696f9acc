// Progressive radiosity's shooting loop (thesis ch. 6; Cohen et al. 1988), once for every way of seeing
// (shot_backend.h): take the patch with the most unshot power, shoot it, scale what its receivers gathered
// to what its eyes saw, keep the energy books, and stop at the unshot share, at the caller's stop per room,
// at a bound per patch or at the deadline. The time left is estimated from the shots so far
// (solve_estimate.h) and reported as progress.
#pragma once

#include <chrono>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "radiosity/lightmap/shot_settings.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/shot_backend.h"
#include "radiosity/solve/solve_controls.h"

namespace cpgi {

/// The shot the loop stops at, past a stop first refused after `shots` shots over `receivers` texels,
/// with at least `texelShots` (kStopRefusedTexelShots) of work allowed.
int refusedStopBound(int shots, size_t receivers, double texelShots);

/// What a caller driving the loop sets besides the user's ShotSettings.
struct LoopControls {
  /// Asked each time the unshot share reaches the stop (ShotSettings::unshotFraction), with the radiosity
  /// and the unshot residual so far (per atlas texel): true stops; false shoots on and asks again at
  /// kStopRecheck of the share (SolveResult::stopChecks counts the asks). The bake's stop per room
  /// (radiosity/solve/ambient.h, ambientShares). Empty: stop.
  std::function<bool(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      acceptStop = {};
  /// acceptStop cell by cell (its cellLight and accepts; its texelCell is the caller's), and per patch its
  /// cell: the time estimate foresees the stop per room's refusals with them. Empty: only the unshot stop.
  RoomStopView roomStop = {};
  std::vector<int> patchCell = {};
  /// Also stop when the next shooter's unshot power (W, R + G + B) is below this: a bound per patch, so a
  /// cell solve lit through a door stops where a solve of the whole scene would (radiosity/cells/). 0: off.
  double minShotPower = 0.0;
  /// > 0: a shot is strong when it carries at least this power (W) rather than
  /// ShotSettings::strongShotFraction of the solve's own emitted power (a cell solve measures its shots
  /// against the whole scene's light).
  double strongShotPower = 0.0;
  /// Whether an emitter's own shots are a lamp's (ShotBackend::shoot's `lamp`).
  bool emittersAreLamps = true;
  /// Per patch, the factor its shots are scaled by instead of the loop's own check (a shot at some
  /// receivers only, whose sums cannot check what it delivered: radiosity/solve/refined_lamp_shot.h). Empty:
  /// the loop's check.
  std::span<const float> patchShotScale = {};
  /// Shooters emit with lobes (radiosity/solve/emission_lobes.h): a shot may land up to the lobes'
  /// normalisation tolerance over its power before it is scaled back.
  bool lobedEmission = false;
  /// Shoot no more after this instant: the result is the shots so far, SolveResult::timedOut set and
  /// what is left counted as unshot, so the energy still balances.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// The least work the stop per room may add past its first refusal (refusedStopBound).
  double refusedStopTexelShots = kStopRefusedTexelShots;
};

/// Runs the loop on `backend` (after construction, before start()) until a stop. Fills SolveResult's
/// books (shots, energy, history, shooters, shotScales, unshotFraction, stopChecks, stopRefusedAt,
/// stopBounded, timedOut), not its
/// per-texel results: the caller reads those back (ShotBackend::readBack). Records "solve: shots".
SolveResult runProgressiveLoop(ShotBackend& backend, const ShotSettings& settings,
                               const LoopControls& controls, Context& ctx);

}  // namespace cpgi
