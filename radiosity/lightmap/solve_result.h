// What a radiosity solve hands back: one type for a solve of a whole atlas (radiosity/gpu/gl_shot_engine.h)
// and for a solve cell by cell through portals (radiosity/cells/cell_solver.h), so that a caller (bake,
// compare-cells, the benchmarks) reads the radiosity and the energy the same way whichever ran; each
// solver adds its own details beside them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

/// Energy bookkeeping, W summed over R, G, B. At every step emitted = absorbed + unshot + escaped,
/// where escaped is the part of the shot power no receiver caught (open scenes, form-factor error).
/// A cell-by-cell solve sums shot and received over its cell solves.
struct EnergyTotals {
  double emitted = 0.0;
  double shot = 0.0;      ///< power that left shooters so far
  double received = 0.0;  ///< Σ irradiance × area over all texels
  double absorbed = 0.0;  ///< Σ (1 − ρ) irradiance × area
  double unshot = 0.0;    ///< Σ residual × area
  /// Σ over shots of max(0, received − shot) beyond a float tolerance: light the solve made up, which a
  /// correct solve never does (a shooter's form factors sum to at most 1). Non-zero is a defect.
  double created = 0.0;
  /// The largest received / shot of any one shot (≤ 1 when no energy is created).
  double worstShotGain = 0.0;
  double escaped() const { return shot - received; }
};

/// Watts summed over R, G, B. For every cell: emitted + received = absorbed + sent + unshot + escaped.
struct CellEnergy {
  std::string name;
  double emitted = 0.0;        ///< by its own emitters
  double received = 0.0;       ///< injected by neighbours through its portals
  double absorbed = 0.0;       ///< by its surfaces (portals excluded)
  double sent = 0.0;           ///< collected on its portals and handed to the neighbours
  double unshot = 0.0;         ///< left at the end: residual plus received light not yet solved
  double escaped = 0.0;        ///< shot but caught by no receiver (form-factor error)
  double created = 0.0;        ///< Σ EnergyTotals::created of its solves (non-zero is a defect)
  double worstShotGain = 0.0;  ///< the largest EnergyTotals::worstShotGain of its solves
  int solves = 0, shots = 0;
  size_t texels = 0;     ///< valid texels of its atlas, portals included
  double seconds = 0.0;  ///< its solves
  bool written = true;   ///< false for an on-demand bake's boundary cell (solved, texels left black)
};

struct PortalEnergy {
  std::string name;
  double aToB = 0.0, bToA = 0.0;  ///< W through the opening each way
};

/// A cell-by-cell solve's details.
struct CellSolveData {
  int rounds = 0;  ///< solve rounds (1 = the direct step only)
  std::vector<CellEnergy> cells;
  std::vector<PortalEnergy> portals;
  size_t maxCellTexels = 0;
};

/// What a lamp's shot found at a receiver texel (receive.comp's LAMP_* bits): its value there is not one
/// that a coarser texel's neighbours would interpolate.
enum LampFlag : uint8_t {
  kLampEdge = 1,        ///< a shadow or beam edge crosses the texel
  kLampNear = 2,        ///< within two of its texels of the lamp
  kLampPartlySeen = 4,  ///< some of the lamp's eyes see its centre and some do not (a penumbra)
};

struct SolveResult {
  std::vector<glm::vec3> radiosity;  ///< per atlas texel (W/m²), padding 0, not dilated
  int shots = 0;
  double unshotFraction = 0.0;  ///< unshot / emitted at the end (0 when nothing emits)
  EnergyTotals energy;
  double seconds = 0.0;  ///< solve time (a cell solve: all solves, atlases and syncs)
  /// Stopped at SolveControls::deadline (a cell solve: CellSolveParams::deadline) before its target: a
  /// valid but partial result.
  bool timedOut = false;
  /// How often SolveControls::acceptStop was asked (0 without it); it refused all but the last of them
  /// unless another bound stopped the solve first.
  int stopChecks = 0;
  /// The shot at which acceptStop first refused (0: never), and whether the loop then stopped at its bound
  /// of kStopRefusedShots × as many shots again (radiosity/solve/progressive_loop.h) with acceptStop still
  /// refusing: the stop per room not met, its rest left to the ambient term.
  int stopRefusedAt = 0;
  bool stopBounded = false;

  // A solve of one atlas (gl_shot_engine.h):
  /// With SolveControls::readTransfer, per atlas texel: irradiance received over the whole solve (W/m²;
  /// a texel of albedo 0 keeps all of it, e.g. a portal) and the residual still unshot at the end.
  std::vector<glm::vec3> incident, residual;
  /// With ShotShape::directionalEmission, per atlas texel: the arrival moments of everything it received
  /// (emission_lobes.h, arrivalMoment), to be fitted into a lobe on the far side of a portal.
  std::vector<glm::vec4> arrivals;
  std::vector<EnergyTotals> history;  ///< after the initial state and after every shot
  std::vector<int> shooters;          ///< the patch of every shot, in order
  /// Per shot, the factor what it gathered was scaled by to what its eyes saw (1: none; gl_shot_backend.cpp).
  std::vector<float> shotScales;
  /// With ShotShape::readLampFlags, per atlas texel, LampFlag bits of what the lamps' shots found there.
  std::vector<uint8_t> lampFlags;
  double setupSeconds = 0.0;  ///< programs and textures

  /// A cell-by-cell solve (cell_solver.h): rounds, per-cell and per-portal energy.
  std::optional<CellSolveData> perCell;
};

}  // namespace cpgi
