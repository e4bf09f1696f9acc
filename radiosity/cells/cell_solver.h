// Radiosity with cells and portals (thesis ch. 8, Algorithm 3). Every cell is solved alone, with only its
// own triangles and one patch per portal (the portal quad facing into the cell) in its own atlas, so a
// solve's memory follows the cell. A portal patch has albedo 0: it never reflects nor re-shoots inside its
// cell, it only keeps, per texel, the irradiance that reaches the opening. At each sync that irradiance
// becomes the exitance of the same quad on the other side (a diffuse area emitter: the power through the
// opening is conserved), and the cells that received light are solved again. Radiosity is linear, so each
// round is a fresh solve of the newly injected light (plus what the previous solve left unshot) and the
// rounds add up. Results land in one global atlas (the same layout as a global bake), patch by patch.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/solve.h"
#include "radiosity/solve/two_level_solve.h"

namespace cpgi {

/// How a portal re-emits on the far side what reached it: diffuse (the thesis: a Lambertian area light) or
/// directional (the light keeps the directions it arrived with; radiosity/solve/emission_lobes.h). One
/// PortalTransfer class per model (radiosity/cells/portal_transfer.h).
/// Binned: the directions kept per channel in kBinGrid² bins found by rays in the sending cell
/// (radiosity/solve/emission_bins.h), for light more concentrated than one lobe can say.
enum class PortalLight { Diffuse, Directional, Binned };
const char* portalLightName(PortalLight p);

struct CellSolveParams {
  /// Per-cell solver settings. Its unshotFraction is the whole scene's target: rounds go on until the
  /// unshot power everywhere, plus the power held on portals and not yet re-emitted, is at most this
  /// fraction of the emitted power. Each round's solves stop at half that budget (of the scene's
  /// emitted power, not of their own input).
  SolverParams solver;
  /// The per-cell atlases use these too (the same charts as the global atlas built with them).
  AtlasParams atlas;
  int maxRounds = 64;  ///< syncs at most (>= 1)
  PortalLight portals = PortalLight::Diffuse;
  /// Directional portals: the narrowest lobe, as the standard deviation per axis of sin θ (≈ radians when
  /// narrow), in (0, 0.45]. A collimated beam gets this width, so that receivers, sampled at texel
  /// centres, do not alias it; a wider arrival keeps its own width. What crosses a portal is reflected
  /// light (the lamps' direct light is shot over the whole scene first), never a thin beam, and the fit
  /// puts the arrivals' spread into a Lambertian share beside the narrowest lobe: at 0.05 openings' room C
  /// read 0.960 (11.8 % per texel) at the default stop and 0.956 converged, at 0.1 / 0.15 / 0.2 / 0.3
  /// 0.969 / 0.977 / 0.987 / 1.016 (9.3 / 8.3 / 8.5 / 12.4 %), 0.985 (6.7 %) converged at 0.2, room B
  /// 4.9 % → 3.7 % (bench/RESULTS.md, `bake --lobe-width`).
  float lobeMinWidth = 0.2f;
  /// Binned portals: rays per sending portal texel that find its arrival bins (>= 64).
  int portalBinRays = 2048;
  /// The portals' texels per metre as a multiple of the atlas's density (>= 1). A portal texel re-emits
  /// one distribution of directions from its whole area; what comes through a door varies across it
  /// (one jamb sees the lit room's wall, the other its floor), and a wall at right angles to the door
  /// sees each texel from 45–90°. At the solve's 0.2 m a room lit through one door read a strip +30 %
  /// beside one −30 % on that wall; at 0.1 m it is the global bake's within its noise (bench/RESULTS.md,
  /// "The portals' texels"). The light read between texels, or its eyes spread over them, did not do it.
  /// It is 1 by default. At 2 a portal's receiving texels are seen through 2 × 2 points (roundBudget:
  /// ShotShape::openingPoints), the same points a square metre; with portalBinRays 1024 the random plans'
  /// cells bakes cost 1.3× main's and their rooms over the global bake's RMSE + 2 points went 7 → 3 of
  /// 37, where 2048 rays and 4 × 4 points cost 2.4× (bench/RESULTS.md, "The portals' texels at half the
  /// cost"); the bake's tests at those settings were not run.
  float portalDensityScale = 1.0f;
  /// Cells solved at once within a round (>= 1), each extra one on its own thread and GL context
  /// (radiosity/cells/cell_workers.h). Any value gives the same result as 1.
  int jobs = 1;
  /// On-demand bakes (solveCellsOnDemand): cells of the graph solved on `boundaryAtlas` only to light
  /// their neighbours through the portals; their texels are not written.
  std::vector<int> boundaryCells;
  AtlasParams boundaryAtlas;
  /// Set by solveCellsOnDemand: the graph is part of the scene's, so triangles in no cell and a
  /// disconnected graph are expected (the whole graph was validated and warned about).
  bool partOfGraph = false;
  /// Start no round, and stop every cell solve, after this instant (bake --time-limit): light still in
  /// flight stays pending, counted as unshot, and the result has SolveResult::timedOut. The direct step
  /// (the emitters' first shot) always runs.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// The wall seconds a CPU second takes as the machine runs now (SolveControls::load): a two-level cells
  /// solve's set-up is estimated with it. Empty: 1.
  std::function<double()> load = {};
  /// The stop per cell (radiosity/cells/round_stop.h): at the unshot target, rounds go on while in some
  /// cell the ambient term would be more than this share of its light (bake --ambient-share); 0: the
  /// target alone.
  double maxAmbientShare = 0.0;
  /// The emitters' first shot made elsewhere, over `global` (a two-level bake, solveCellsTwoLevel: the
  /// lamps and punctual lights shot onto the output's atlas, their irradiance averaged onto the coarse
  /// one): landed in the cells in place of shooting them. Null: the cells shoot them (cell_first_shot.h).
  const PriorShot* firstShot = nullptr;
};

/// Solves the scene cell by cell into `global` (an atlas of the whole scene); the result's perCell holds
/// the rounds and the energy per cell and portal. Throws InputError when the graph is unusable
/// (validateCells errors); triangles in no cell stay black (a warning in ctx).
SolveResult solveCells(const Scene& scene, const CellGraph& graph, const LightmapAtlas& global,
                       const CellSolveParams& params, ShotEngine& engine, Context& ctx);

/// An on-demand bake (radiosity/cells/cell_selection.h): solveCells over the selection's baked cells and, in
/// Coarse mode, its boundary cells on a coarse atlas (coarseAtlasParams);
/// only the baked cells' texels are written. Portals to cells left out are open (light leaving through
/// them counts as escaped). `result.perCell->cells` lists the solved cells in graph order (boundary ones with
/// written = false); `result.perCell->portals` the portals between them.
SolveResult solveCellsOnDemand(const Scene& scene, const CellGraph& graph, const CellSelection& selection,
                               BoundaryMode mode, const LightmapAtlas& global, const CellSolveParams& params,
                               ShotEngine& engine, Context& ctx);

/// A cells bake in two levels (radiosity/solve/two_level_solve.h): the lamps and punctual lights shoot onto
/// `global` (the output's atlas, built with `params.atlas` from `quads`) at its own texels where their light
/// varies, and the cells solve the light they leave on an atlas of `levels.solveDensity` texels per metre
/// (finer at contacts), which comes back to `global` interpolated: the lamps on `engines.lamps`, the cells'
/// solves on `engines.reflections`, as a global two-level solve. Not for cell jobs (their plan is one
/// level). `data` receives the levels' figures when not null.
SolveResult solveCellsTwoLevel(const Scene& scene, const CellGraph& graph, const QuadSet& quads,
                               const LightmapAtlas& global, const TwoLevelParams& levels,
                               const CellSolveParams& params, const ShotEngines& engines, Context& ctx,
                               TwoLevelData* data = nullptr);

/// The boundary cells' atlas: half the texels per edge of `atlas` (at least 2 per quad edge). Most of a
/// shot's time is the item buffer, which the atlas does not change; the receive pass and memory scale
/// with the texels. A quarter per edge put room B of seed1 (8²/quad) 8.6 % off the whole bake, half
/// 3.6 % (3.9 % with merged charts).
AtlasParams coarseAtlasParams(const AtlasParams& atlas);

}  // namespace cpgi
