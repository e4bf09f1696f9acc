// One cell's share of one round of Algorithm 3 (thesis ch. 8) as a plain value: what a solve of the cell
// leaves behind in it and hands on through its portals. Both ways of running the rounds go through these
// functions, so that they give the same numbers bit for bit:
//  - in one process (solveCells, cell_solver.cpp): every cell of a round solved, then the round applied;
//  - as cell jobs (cell_jobs.h): each job solves one round of some cells from files and writes its
//    CellRound to files (cell_job_files.h); the next round's jobs gather from them, the last gather
//    applies every round in order.
// A round: the cells holding enough pending light solve it (cellSolvesRound, roundBudget), each gives a
// CellRound (cellRoundOf, or waitingCellRound for a cell that waits); then each cell's next pending light
// is its own kept share plus what arrives through its portals (gatherPending), and the round's unshot power
// decides whether another round runs (roundUnshot).
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/emission_bins.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

/// Light one cell hands to a neighbour through one portal in one round.
struct PortalSend {
  int portal = -1;         ///< graph portal
  int from = -1, to = -1;  ///< graph cells
  /// (texel of the receiving cell's atlas, exitance W/m²) to add to its pending light, in link order.
  std::vector<std::pair<int32_t, glm::vec3>> exitance;
  /// Directional portals: the arrival moments that go with each `exitance` entry (same order, world
  /// coordinates, weighted like the exitance); empty with diffuse portals.
  std::vector<glm::vec4> moments;
  /// Binned portals: the arrival bins that go with each `exitance` entry (same order), found by rays in
  /// the sending cell and summing to the entry's R + G + B; empty otherwise.
  std::vector<ArrivalBins> bins;
  glm::vec3 scale{0.0f};  ///< exitance = sending side's irradiance × scale (power through the opening kept)
  double watts = 0.0;     ///< power collected on the sending side (W, R + G + B)
  double arriving = 0.0;  ///< power of `exitance` over the receiving texels (W, R + G + B)
  glm::dvec3 arrivingRgb{0.0};  ///< the same per channel (W), for the receiving cell's stop (round_stop.h)
};

/// Per link, per sending texel, the texels its arrival bins' rays meet (traceArrivalHits), kept from one
/// round to the next (cellRoundOf).
using ArrivalHitCache = std::vector<std::vector<std::vector<int32_t>>>;

/// What one cell's round leaves: its own share of the next round's pending light and what it sends.
struct CellRound {
  int cell = -1;                   ///< graph cell
  bool solved = false;             ///< false: it waited (too little pending light), its pending light kept
  bool timedOut = false;           ///< its solve stopped at the bake's --time-limit (not in job files)
  std::vector<glm::vec3> kept;     ///< per cell texel: its own share of the next pending light (W/m²)
  std::vector<glm::vec3> carried;  ///< per cell texel: the part of `kept` already in the radiosity
  std::vector<glm::vec4> keptMoments;       ///< directional portals: per cell texel, the moments of `kept`
  std::map<int32_t, ArrivalBins> keptBins;  ///< binned portals: per texel with bins, those of `kept`
  std::vector<glm::vec3> radiosity;  ///< per cell texel: radiosity gained this round (solved cells only)
  std::vector<PortalSend> sends;     ///< solved cells only, in link order (portal, then A→B before B→A)
  double keptPower = 0.0;            ///< power of `kept` (W, R + G + B)
  glm::dvec3 keptRgb{0.0};           ///< the same per channel (W), for the stop (round_stop.h)
  /// Σ area × (R + G + B) of `radiosity` over the cell's own texels that do not emit (W): its reflectors'
  /// light gained this round, for the stop.
  double reflectorGain = 0.0;
  // The solve's figures (SolveResult), for the bookkeeping.
  int shots = 0;
  double seconds = 0.0, shot = 0.0, received = 0.0, escaped = 0.0, created = 0.0, worstShotGain = 0.0;
  double absorbed = 0.0;  ///< by the cell's surfaces: the solve's absorbed less what its portals collected
};

/// Σ (R + G + B) × area over the valid texels of `atlas` (W).
double cellPower(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas);
/// Σ exitance × area over the valid texels of `atlas` per channel (W).
glm::dvec3 cellPowerRgb(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas);
/// Per texel of `s.atlas`, 1 where it is the cell's own (not a portal's) and its material does not emit.
std::vector<char> reflectorTexels(const CellState& s);

/// Whether a cell holding `s.pending` solves in a round of the scene's target unshot power `target` (W):
/// a cell holding a negligible share waits (its light stays pending, counted as unshot).
bool cellSolvesRound(const CellState& s, double target);

/// The rays a cell's shot measures its regions' coverage with (SolverParams::coverageRays, 1 024 for the
/// whole scene). A shot's coverage rays do not grow with its receivers: over a room's two thousand texels
/// they were a tenth of the gather's CPU, against nothing over a whole building's atlas. A quarter of them
/// scale each shot within 1 % (the spread of 256 draws of a room's ~0.97 covered), which the room's many
/// shots average out: random plan 22's rooms' means moved by 0.01 % at most, the office's by 0.11 %.
inline constexpr int kCellCoverageRays = 256;

/// The settings of a round's solves. Half the scene's budget is for what the solves leave unshot (the
/// other half for what the portals collect): a solve stops at that fraction of the round's input
/// (`unshot`: the power unshot everywhere before the round, the emitted power before the first), or as
/// soon as no patch holds more than its share of it (half the budget over the scene's `globalPatches`).
/// A cell lit only through a door must not be solved to the scene's fraction of its own small input: a
/// room of many small patches would then take more shots than the whole scene. For the same reason a
/// shot is strong (more eyes) by the scene's `emitted` power (W), not by the cell's input.
/// A portal's receiver texels are seen through points as far apart at any portalDensityScale.
SolverParams roundBudget(const CellSolveParams& params, double target, double unshot, double emitted,
                         SolveControls& controls, ShotShape& shape, size_t globalPatches);

/// Cell `c`'s round after its solve `solved` (of `s`, its pending light as the atlas's emission): its
/// residual kept, its radiosity gained, and through each of `links` leaving it, the irradiance collected
/// on the sending side as exitance on the far side, rescaled so that the power through the opening is
/// exactly what arrived (the charts of the two sides may differ). Indices are those of `cells`.
/// `binRays` > 0 (binned portals): each send's entries get their arrival bins by that many rays per
/// sending texel into the cell (portalArrivalBins).
/// `hits` (may be null): per link of `links`, per texel, the texels its arrival rays meet
/// (traceArrivalHits), traced on the first round that needs them and read again on every later one: a
/// portal texel's rays depend on where it is only, and the cell's geometry and atlas do not change between
/// rounds. The same floats as without.
CellRound cellRoundOf(size_t c, const CellState& s, const SolveResult& solved,
                      const std::vector<PortalLink>& links, const std::vector<CellState>& cells,
                      int binRays = 0, ArrivalHitCache* hits = nullptr);

/// Per entry of `link.texels`, the arrival bins at its sending texel by `rays` rays into cell `s`, each
/// taking the exitance the texel it meets shot in `solved` (what it held pending, plus what it gained,
/// less what it left unshot), shaped by that texel's own bins where it has any; each channel scaled to
/// sum to that channel of `weights[k]`. Deterministic: the rays of a texel depend on where it is only.
/// `hits` (may be null): per entry of `link.texels`, the texels its rays meet; an entry without
/// `rayCount` of them is traced and kept there.
std::vector<ArrivalBins> portalArrivalBins(const CellState& s, const SolveResult& solved,
                                           const RayScene& rays, const PortalLink& link,
                                           const std::vector<glm::vec3>& weights, int rayCount,
                                           std::vector<std::vector<int32_t>>* hits = nullptr);

/// Cell `c`'s round when it waits: its pending light kept, nothing sent.
CellRound waitingCellRound(size_t c, const CellState& s);

/// Cell `own.cell`'s pending light for the next round (`texels` entries): its own kept share and the
/// exitance `arriving` through its portals, added in the solver's order (a waiting cell's own share first;
/// otherwise by sending cell, its own share at its own index). `arriving`: sends to it, sorted by
/// (from, portal).
std::vector<glm::vec3> gatherPending(const CellRound& own, const std::vector<const PortalSend*>& arriving,
                                     size_t texels);
/// The same for the arrival bins (binned portals), per texel that has any.
std::map<int32_t, ArrivalBins> gatherPendingBins(const CellRound& own,
                                                 const std::vector<const PortalSend*>& arriving);

/// The same for the arrival moments (directional portals): empty when neither `own` nor any send has
/// moments.
std::vector<glm::vec4> gatherPendingMoments(const CellRound& own,
                                            const std::vector<const PortalSend*>& arriving, size_t texels);

/// The power unshot after a round: per cell in order, its kept power then the power arriving at it (sorted by
/// sender and portal). `keptPower` per graph cell; `sends` every send of the round (any order).
double roundUnshot(const std::vector<double>& keptPower, std::vector<const PortalSend*> sends);

/// `sends` to cell `to`, sorted by (from, portal), as gatherPending takes them.
std::vector<const PortalSend*> sendsTo(int to, const std::vector<const PortalSend*>& sends);

/// A solved round's share of the bookkeeping of `result` (a cells SolveResult, perCell set): the solve's
/// figures, its radiosity into `result.radiosity` through `s.toGlobal`, the power through each portal.
void addCellRound(const CellRound& r, const CellState& s, const CellGraph& graph, SolveResult& result);

// The whole solve's steps that the cell jobs share with solveCells (cell_solver.cpp).

/// Step 0: the graph and the parameters, before any work; throws InputError when unusable.
void checkCells(const Scene& scene, const CellGraph& graph, const CellSolveParams& params, Context& ctx);
/// The result before the first round (after the first shot): every cell's name, emitted power and texels.
SolveResult startBookkeeping(const CellGraph& graph, const std::vector<CellState>& cells,
                             const LightmapAtlas& global);
/// The totals once the rounds are over, `cells` holding their final pending light.
void finishBookkeeping(const std::vector<CellState>& cells, const LightmapAtlas& global, SolveResult& result);

}  // namespace cpgi
