// What a caller sets to drive a progressive solve (solve.h), beside the user's settings (solver_params.h).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

/// A first shot made before the solve, elsewhere (radiosity/solve/two_level_solve.h: the lamps shot on the
/// output's atlas, the rest solved on a coarser one): the solve starts after it, as after any shot.
struct PriorShot {
  std::span<const glm::vec3> irradiance;  ///< per atlas texel, W/m², what it delivered
  double emitted = 0.0;                   ///< W (R + G + B) its sources emitted, all counted as shot
};

/// What a caller driving a solve sets, apart from the user's settings: the cell solver (radiosity/cells/)
/// reads what crosses its portals, stops on a per-patch bound and emits with lobes. The stop's fields go to
/// the loop (progressive_loop.h, LoopControls); the emission lobes and bins, the receivers and the lamp
/// flags are the item buffers' alone (ShotEngine::features).

struct SolveControls {
  /// Also read back every texel's received irradiance and unshot residual (SolveResult::incident,
  /// ::residual): what a cell solve hands on through its portals (radiosity/cells/cell_solver.h).
  bool readTransfer = false;
  /// Also stop when the next shooter's unshot power (W, summed over R, G, B) is below this: a bound per
  /// patch rather than a fraction of the input, so a cell solve lit through a door stops where a solve of
  /// the whole scene would leave such small patches unshot (radiosity/cells/cell_solver.h). 0: off.
  double minShotPower = 0.0;
  /// > 0: a shot is strong (SolverParams::strongShotRegions) when it carries at least this power (W, R + G
  /// + B) rather than strongShotFraction of the solve's own emitted power. A cell solve lit through a
  /// door measures its shots against the whole scene's light, as a global solve would: against its own
  /// small input nearly every shot was strong, 16 item buffers each, and spot-door's cells took 3× a
  /// global solve's time per shot (radiosity/cells/cell_round.h, roundBudget).
  double strongShotPower = 0.0;
  /// Whether the emitters' own shots are a lamp's (resampled at beam edges and near the emitter, with
  /// jittered eyes per strong region: receive.comp, uLampShot). A cell solve's emitters are its portals,
  /// re-emitting what its neighbours sent, which a global solve carries by plain reflector shots; shot as
  /// lamps, they cost seed1's cells bake 2.4× the CPU for no gain in any cell (issue 11, session 21).
  bool emittersAreLamps = true;
  /// Directional emission (radiosity/solve/emission_lobes.h): shooters emit with the per-texel lobes of
  /// `emissionLobes` (one per atlas texel; zero or none = Lambertian), and every texel accumulates the
  /// direction moments of what it receives (SolveResult::arrivals). Off: the passes are built without it
  /// and cost and results are those of the plain solver. Lobes without it are an error.
  bool directionalEmission = false;
  std::span<const glm::vec4> emissionLobes = {};
  /// With directional emission, whether the receivers accumulate the direction moments of what they
  /// receive (SolveResult::arrivals; directional portals carry them). Binned portals trace their bins
  /// instead, so without the moments the shooters with no lobe shoot with the plain programs: in
  /// spot-door's cells bake every reflector shot cost 1.6× the plain one for moments nobody read.
  bool arrivalMoments = true;
  /// Binned emission (radiosity/solve/emission_bins.h) for the texels whose lobe is binnedLobe(slot): slot
  /// after slot, kArrivalBins factors f each, normalised to mean 1 (normalisedEmissionBins).
  std::span<const float> emissionBins = {};
  /// Start after this shot: ρ × its irradiance unshot, its power emitted and shot. The atlas's emission is
  /// shot as usual and the scene's punctual lights are not (the prior shot stands for them). Null: none.
  const PriorShot* priorShot = nullptr;
  /// Receive only at the texels flagged here (one per atlas texel, non-zero: receives; empty: every texel):
  /// a lamp's shot evaluated at the output's texels only where a coarser shot found its light varying
  /// (radiosity/solve/refined_lamp_shot.h). Such a shot's sums over part of its receivers cannot check what
  /// it delivered, so it needs `patchShotScale`: per patch, the factor that patch's shots are scaled by
  /// instead of the solver's own check (SolveResult::shotScales of the coarser shot).
  std::span<const uint8_t> receivers = {};
  std::span<const float> patchShotScale = {};
  /// Also read back what the lamps' shots found at each texel (SolveResult::lampFlags).
  bool readLampFlags = false;
  /// Asked each time the unshot share reaches the stop (SolverParams::unshotFraction), with the radiosity
  /// and the unshot residual so far (per atlas texel): true stops; false shoots on and asks again once the
  /// share has fallen to kStopRecheck of what it was (SolveResult::stopChecks counts the asks). The bake's
  /// stop per cell (radiosity/solve/ambient.h, ambientShares). Empty: stop.
  std::function<bool(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      acceptStop = {};
  /// The number the shots count from in the eyes' draw and the item buffer's turn (jitteredEyes): 0 for a
  /// solve; bench/shot_probe.cpp averages one shot over many draws with it.
  uint32_t firstShotNumber = 0;
  /// Shoot no more after this instant (bake --time-limit): the result is what the shots so far gave,
  /// with SolveResult::timedOut set and what is left counted as unshot, so the energy still balances.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

}  // namespace cpgi
