// The lights' first shot for a cell-by-cell solve: where the light of every lamp lands first, over the
// whole scene at once, before the cells take over.
//
// Light from a lamp crosses a door as a beam: it lands on the far room's floor in the lamp's shape. A
// portal that re-emits it diffusely (the thesis's model) spreads that beam over the whole room, and the
// room past the next door got 20 % too much of it (issue 11: openings C 1.206 converged, seed3 B 1.109).
// Shot over the whole scene, where portals are no geometry, the direct light lands where it does in a
// global solve, and the portals carry only what the surfaces reflect, which is far closer to diffuse.
// The cost is the global solve's own first shots: one per emitter region, into the global atlas. They shoot
// in groups, the emitters of one cell each (first_shot_groups.h), side by side on the bake's workers or as
// cell jobs on many machines, and the groups' irradiance is added in one fixed order.
#pragma once

#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_workers.h"
#include "radiosity/cells/first_shot_groups.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

/// The first shot's energy, for the cells' bookkeeping.
struct CellFirstShot {
  std::vector<double> absorbed;  ///< per cell, W (R + G + B): (1 − ρ) E × area
  double landed = 0.0;           ///< W landed on the cells' texels (R + G + B)
  double emitted = 0.0;          ///< W the lamps and punctual lights emitted (R + G + B)
  /// Per global texel, the emitters' own exitance (W/m²): it is in the radiosity but shot already.
  std::vector<glm::vec3> emission;
};

/// Shoots the emitters of the solved cells and the scene's punctual lights once over the whole scene on
/// the GPU (into `global` with black receivers, `settings`' visibility), group by group on `workers`,
/// then lands the sum in the cells (landFirstShot). `cellOfTriangle`: per scene triangle its cell in the
/// solved graph, or -1 (emitters there are dark).
CellFirstShot shootEmittersIntoCells(const Scene& scene, const LightmapAtlas& global,
                                     const std::vector<int>& cellOfTriangle, const SolverParams& settings,
                                     std::vector<CellState>& cells, CellWorkers& workers, Context& ctx);

/// Hands each cell ρ E of the groups' summed irradiance as pending light in place of its own emitters'
/// exitance (they have shot): a written cell by its texels' map (mapCellTexels), a boundary cell
/// (CellState::boundary, a coarser atlas) by the point under each texel. Portal patches get none; light
/// landing in no solved cell escapes. CPU only (the cell jobs' first-shot sum runs it).
CellFirstShot landFirstShot(const Scene& scene, const LightmapAtlas& global, const FirstShotSum& sum,
                            std::vector<CellState>& cells);

/// The first shot's share of the bookkeeping: each cell emitted what landed in it (the reflected part is in
/// its pending light already, the rest absorbed at once); what landed nowhere escaped from the cell that
/// got the most, so that every cell balances. The emitters' exitance joins the radiosity.
void addFirstShotBookkeeping(const CellFirstShot& shot, SolveResult& result);

}  // namespace cpgi
