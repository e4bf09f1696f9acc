// What a caller sets to drive a progressive solve (solve.h), beside the user's settings (solver_params.h).
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/lightmap/sky_openings.h"
#include "radiosity/solve/ambient.h"

namespace cpgi {

/// A refused stop (SolveControls::acceptStop) is asked again once the unshot share has fallen to this
/// fraction of the share it was refused at.
inline constexpr double kStopRecheck = 0.7;

/// After the first refused stop (SolveControls::acceptStop), the loop shoots at most this many times as
/// many shots again as it took to reach it, or kStopRefusedTexelShots' worth if that is more, then stops
/// whatever acceptStop says (SolveResult::stopBounded). Without a bound the stop per room kept a daylit
/// house shooting for a room's last fraction of a per cent: unshot under 1 % by shot 200, still shooting
/// at shot 2 900 (0.02 % unshot) after 25 minutes (issue 46). What is left unshot is the ambient term's
/// (radiosity/solve/ambient.h).
inline constexpr double kStopRefusedShots = 1.0;

/// The least the stop per room may shoot on past its first refusal, in shots × receiver texels (a shot
/// costs about its receivers): some CPU seconds. Where shots are cheap, as many shots again is too few
/// for a room three openings from the lamp, whose light arrives after the rest of the scene's is shot:
/// random plans stopped at the bound with such rooms 60–70 % ambient term and their means 6–10 % off,
/// within 2 % after a few hundred shots more (bench/RESULTS.md, "The stop per room's bound").
inline constexpr double kStopRefusedTexelShots = 2.0e7;

/// A first shot made before the solve, elsewhere (radiosity/solve/two_level_solve.h: the lamps shot on the
/// output's atlas, the rest solved on a coarser one): the solve starts after it, as after any shot.
struct PriorShot {
  std::span<const glm::vec3> irradiance;  ///< per atlas texel, W/m², what it delivered
  double emitted = 0.0;                   ///< W (R + G + B) its sources emitted, all counted as shot
};

/// The stop per room (SolveControls::acceptStop) cell by cell, so that the time estimate foresees its
/// refusals (radiosity/solve/solve_estimate.h): the same rule (RoomStop) asked of the cells' light.
struct RoomStopView {
  /// Per texel of the solve's atlas, its cell: an entry of CellLight.
  std::vector<int> texelCell;
  /// The cells' light from the solve's radiosity and unshot residual (per texel of its atlas).
  std::function<CellLight(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      cellLight;
  /// Whether acceptStop accepts the cells' light so.
  std::function<bool(const CellLight&)> accepts;
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
  /// acceptStop cell by cell, for the time estimate (empty: it foresees the unshot stop alone).
  RoomStopView roomStop = {};
  /// Also stop when the next shooter's unshot power (W, summed over R, G, B) is below this: a bound per
  /// patch rather than a fraction of the input, so a solve lit from outside its atlas (a cell through its
  /// door) stops where a solve of the whole scene would leave such small patches unshot
  /// (radiosity/cells/cell_round.h). 0: off.
  double minShotPower = 0.0;
  /// Shoot no more after this instant (bake --time-limit): the result is what the shots so far gave,
  /// with SolveResult::timedOut set and what is left counted as unshot, so the energy still balances.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// The wall seconds a CPU second of this process takes as the machine runs now (its load: the bake's
  /// CpuShare, radiosity/bake/bake_limits.h; at least 1): a two-level solve's set-up is estimated with it
  /// and not started when it would end past the deadline (two_level_solve.h). Empty: 1.
  std::function<double()> load = {};
  /// The least work, in shots × receiver texels, the stop per room may add past its first refusal
  /// (kStopRefusedTexelShots; tests set 0 to see the bound in shots alone).
  double refusedStopTexelShots = kStopRefusedTexelShots;
  /// The openings onto the outside the sky gather draws part of its directions towards (sky_openings.h:
  /// the outside cell's portals of the bake's rooms). Empty: cosine directions alone.
  std::vector<SkyOpening> skyOpenings = {};
  /// The share of the time from the sky gather's start to `deadline` the gather may take (skyDeadline):
  /// its passes stop there with the rays they have, and the interreflection gets the rest. 1: all of it,
  /// which on a map of a million texels left the solve no shot (bench/RESULTS.md, "The daylit maps").
  double skyTimeShare = 1.0;
};

/// A bake's SolveControls::skyTimeShare, global or cells: the sky gather and the interreflection halve the
/// time to the solve's deadline. A gather cut at 64 rays a texel is noisier; a solve cut before its first
/// shot leaves all the reflected light to the flat ambient term.
inline constexpr double kBakeSkyTimeShare = 0.5;

/// The sky gather's own deadline under `controls`: skyTimeShare of the time from now to its deadline (none
/// stays none, a deadline passed stays passed).
inline std::chrono::steady_clock::time_point skyDeadline(const SolveControls& controls) {
  const auto now = std::chrono::steady_clock::now();
  if (controls.deadline == std::chrono::steady_clock::time_point::max() || controls.deadline <= now)
    return controls.deadline;
  const double share = std::clamp(controls.skyTimeShare, 0.0, 1.0);
  return now +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>((controls.deadline - now) * share);
}

}  // namespace cpgi
