// What a caller sets to drive a progressive solve (solve.h), beside the user's settings (solver_params.h).
#pragma once

#include <chrono>
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

/// When a solve stops and what it reads back, set by its caller apart from the user's settings
/// (solver_params.h); how its shots are made is apart (shot_shape.h). The stop's fields go to the loop
/// (progressive_loop.h, LoopControls).
struct SolveControls {
  /// Also read back every texel's received irradiance and unshot residual (SolveResult::incident,
  /// ::residual): what a cell solve hands on through its portals (radiosity/cells/cell_solver.h), the
  /// ambient term's input (radiosity/solve/ambient.h) and a two-level solve's light on the output.
  bool readTransfer = false;
  /// Start after this shot: ρ × its irradiance unshot, its power emitted and shot. The atlas's emission is
  /// shot as usual and the scene's punctual lights are not (the prior shot stands for them). Null: none.
  const PriorShot* priorShot = nullptr;
  /// Asked each time the unshot share reaches the stop (SolverParams::unshotFraction), with the radiosity
  /// and the unshot residual so far (per atlas texel): true stops; false shoots on and asks again once the
  /// share has fallen to kStopRecheck of what it was (SolveResult::stopChecks counts the asks). The bake's
  /// stop per room (radiosity/solve/ambient.h, ambientShares). Empty: stop.
  std::function<bool(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      acceptStop = {};
  /// Also stop when the next shooter's unshot power (W, summed over R, G, B) is below this: a bound per
  /// patch rather than a fraction of the input, so a solve lit from outside its atlas (a cell through its
  /// door) stops where a solve of the whole scene would leave such small patches unshot
  /// (radiosity/cells/cell_round.h). 0: off.
  double minShotPower = 0.0;
  /// Shoot no more after this instant (bake --time-limit): the result is what the shots so far gave,
  /// with SolveResult::timedOut set and what is left counted as unshot, so the energy still balances.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

}  // namespace cpgi
