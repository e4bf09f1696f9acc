#include "radiosity/cells/cell_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_first_shot.h"
#include "radiosity/cells/cell_round.h"
#include "radiosity/cells/cell_workers.h"
#include "radiosity/cells/portal_transfer.h"
#include "radiosity/cells/round_stop.h"
#include "radiosity/lightmap/sky_openings.h"

namespace cpgi {
namespace {

glm::dvec3 texelPower(const glm::vec3& v, float area) {
  return glm::dvec3(v) * double(area);
}

}  // namespace

// Step 0: the graph and the parameters, before any work.
void checkCells(const Scene& scene, const CellGraph& graph, const CellSolveParams& params, Context& ctx) {
  if (graph.empty()) throw InputError("cell graph", "the cell graph has no cells");
  const CellValidation validation = validateCells(scene, graph);
  if (!validation.errors.empty()) throw InputError("cell graph", validation.errors.front());
  if (!params.partOfGraph)
    for (const std::string& w : validation.warnings) ctx.warn(w);
  if (params.maxRounds < 1) throw InputError("maximum rounds", "cell rounds must be at least 1");
  if (params.portals == PortalLight::Directional &&
      !(params.lobeMinWidth > 0.0f && params.lobeMinWidth <= 0.45f))
    throw InputError("solver", "the narrowest portal lobe must be in (0, 0.45]");
  if (params.portals == PortalLight::Binned &&
      !(params.portalBinRays >= 64 && params.portalBinRays <= 1 << 20))
    throw InputError("solver", "rays per portal texel for binned portals must be in [64, 1048576]");
  if (!(params.portalDensityScale >= 1.0f && params.portalDensityScale <= 8.0f))
    throw InputError("solver", "the portals' density scale must be in [1, 8]");
}

// The result before the first round: every cell's name, emitted power and texels.
SolveResult startBookkeeping(const CellGraph& graph, const std::vector<CellState>& cells,
                             const LightmapAtlas& global) {
  SolveResult result;
  result.radiosity.assign(global.texelCount(), glm::vec3(0.0f));
  CellSolveData& d = result.perCell.emplace();
  d.cells.resize(cells.size());
  d.portals.resize(graph.portals.size());
  for (size_t c = 0; c < cells.size(); ++c) {
    d.cells[c].name = graph.cells[c].name;
    d.cells[c].emitted = cellPower(cells[c].pending, cells[c].atlas);
    d.cells[c].texels = cells[c].atlas.validTexels();
    d.cells[c].written = !cells[c].boundary;
    result.energy.emitted += d.cells[c].emitted;
    d.maxCellTexels = std::max(d.maxCellTexels, d.cells[c].texels);
  }
  for (size_t p = 0; p < graph.portals.size(); ++p) d.portals[p].name = graph.portals[p].name;
  return result;
}

namespace {

// The cells solved this round, their pending light moved into their atlas's emission; the others wait.
std::vector<size_t> activeCells(std::vector<CellState>& cells, double target) {
  std::vector<size_t> active;
  for (size_t c = 0; c < cells.size(); ++c) {
    CellState& s = cells[c];
    if (!cellSolvesRound(s, target)) continue;
    for (size_t i = 0; i < s.pending.size(); ++i) s.atlas.emission[i] = s.pending[i];
    active.push_back(c);
  }
  return active;
}

// A cell's solve within a round, its progress lines labelled with the cell and round: without it a
// user watched the solve's bar restart once per cell with nothing to say which room it was in.
SolveResult solveLabelled(const std::string& label, const std::function<SolveResult(Context&)>& solve,
                          Context& ctx) {
  Context cellCtx;
  cellCtx.setProgress([&](const Progress& p) {
    Progress labelled = p;
    labelled.status = label + (p.status.empty() ? "" : ": " + p.status);
    ctx.progress(labelled);
  });
  SolveResult solved = solve(cellCtx);
  for (const Context::Timing& t : cellCtx.timings()) ctx.addTiming(t.stage, t.seconds);
  for (const std::string& w : cellCtx.warnings()) ctx.warn(w);
  return solved;
}

// The round's solves are independent (each reads only its own cell): side by side with `jobs`. Every
// cell gets its CellRound (radiosity/cells/cell_round.h), a waiting one too.
std::vector<CellRound> solveRound(const CellGraph& graph, int roundNumber,
                                  const std::vector<CellState>& cells, const std::vector<size_t>& active,
                                  const std::vector<PortalLink>& links, const SolverParams& settings,
                                  const SolveControls& controls, const ShotShape& shape,
                                  const PortalTransfer& transfer, CellWorkers& workers, ArrivalHitCache& hits,
                                  Context& ctx) {
  std::vector<SolveResult> solvedOf(cells.size());
  std::vector<CellRound> round(cells.size());
  {
    auto t = ctx.time("cells: solve");
    workers.run(active.size(), ctx, [&](size_t k, ShotEngine& engine, Context& taskCtx) {
      const size_t c = active[k];
      // Past the deadline a cell's solve would still lay out its engine and shoot nothing: the office's
      // 40 cells after the limit took 20 s so. It waits instead, its light kept as unshot.
      if (std::chrono::steady_clock::now() >= controls.deadline) {
        round[c] = waitingCellRound(c, cells[c]);
        round[c].timedOut = true;
        return;
      }
      const std::string label = "cell " + graph.cells[c].name + " (" + std::to_string(k + 1) + " of " +
                                std::to_string(active.size()) + "), round " + std::to_string(roundNumber);
      solvedOf[c] = solveLabelled(
          label,
          [&](Context& cellCtx) {
            return transfer.solve(c, cells[c], settings, controls, shape, engine, cellCtx);
          },
          taskCtx);
      round[c] = cellRoundOf(c, cells[c], solvedOf[c], links, cells, transfer.binRays(), &hits);
    });
  }
  for (size_t c = 0; c < cells.size(); ++c)
    if (round[c].cell < 0) round[c] = waitingCellRound(c, cells[c]);
  return round;
}

// The round's gathered light becomes every cell's pending; returns the power now unshot everywhere.
double endRound(std::vector<CellState>& cells, const std::vector<CellRound>& round) {
  std::vector<const PortalSend*> sends;
  std::vector<double> kept(cells.size());
  for (size_t c = 0; c < cells.size(); ++c) {
    kept[c] = round[c].keptPower;
    for (const PortalSend& s : round[c].sends) sends.push_back(&s);
  }
  for (size_t c = 0; c < cells.size(); ++c) {
    const std::vector<const PortalSend*> arriving = sendsTo(int(c), sends);
    cells[c].pending = gatherPending(round[c], arriving, cells[c].pending.size());
    cells[c].pendingMoments = gatherPendingMoments(round[c], arriving, cells[c].pending.size());
    cells[c].pendingBins = gatherPendingBins(round[c], arriving);
    cells[c].carried = round[c].carried;
  }
  return roundUnshot(kept, sends);
}

// What is still pending at the stop, per global texel (W/m²), for the ambient term
// (radiosity/solve/ambient.h) to follow: light arrived on a portal and not yet shot is spread over its cell's
// own texels, where it would have landed first. Without it the ambient term spread the whole scene's unshot
// power by area, and a dim room two doors from the lamp came out 19 % bright at the default stop.
std::vector<glm::vec3> pendingPerGlobalTexel(const std::vector<CellState>& cells,
                                             const LightmapAtlas& global) {
  std::vector<glm::vec3> residual(global.texelCount(), glm::vec3(0.0f));
  for (const CellState& s : cells) {
    const std::vector<char> onPortal = portalPatchFlags(s);
    glm::dvec3 portalPower(0.0);
    for (size_t t = 0; t < s.pending.size(); ++t)
      if (s.atlas.patch[t] >= 0 && onPortal[size_t(s.atlas.patch[t])])
        portalPower += texelPower(s.pending[t], s.atlas.area[t]);
    double ownArea = 0.0;
    for (const auto& [g, t] : s.toGlobal) ownArea += global.area[g];
    const glm::vec3 spread = ownArea > 0.0 ? glm::vec3(portalPower / ownArea) : glm::vec3(0.0f);
    for (const auto& [g, t] : s.toGlobal) residual[g] += s.pending[t] + spread;
  }
  return residual;
}

}  // namespace

// The totals once the rounds are over.
void finishBookkeeping(const std::vector<CellState>& cells, const LightmapAtlas& global,
                       SolveResult& result) {
  for (size_t c = 0; c < cells.size(); ++c) {
    CellEnergy& ce = result.perCell->cells[c];
    ce.unshot = cellPower(cells[c].pending, cells[c].atlas);
    result.energy.absorbed += ce.absorbed;
    result.energy.unshot += ce.unshot;
  }
  result.residual = pendingPerGlobalTexel(cells, global);
  result.unshotFraction = result.energy.emitted > 0.0 ? result.energy.unshot / result.energy.emitted : 0.0;
  for (size_t i = 0; i < result.radiosity.size(); ++i)
    if (global.patch[i] < 0) result.radiosity[i] = glm::vec3(0.0f);
}

namespace {

// The cells a round solves, for its progress line: the first six names and how many more.
std::string cellList(const CellGraph& graph, const std::vector<size_t>& active) {
  std::string list = active.size() == 1 ? "cell " : "cells ";
  for (size_t k = 0; k < active.size() && k < 6; ++k) list += (k ? ", " : "") + graph.cells[active[k]].name;
  if (active.size() > 6) list += " and " + std::to_string(active.size() - 6) + " more";
  return list;
}

}  // namespace

const char* portalLightName(PortalLight p) {
  return p == PortalLight::Directional ? "directional" : p == PortalLight::Binned ? "binned" : "diffuse";
}

SolveResult solveCells(const Scene& scene, const CellGraph& graph, const LightmapAtlas& global,
                       const CellSolveParams& params, ShotEngine& engine, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  checkCells(scene, graph, params, ctx);
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<CellState> cells = buildMappedCellAtlases(scene, graph, params, cellOf, global, ctx);
  const size_t unassigned = size_t(std::count_if(cellOf.begin(), cellOf.end(), [](int c) { return c < 0; }));
  if (unassigned > 0 && !params.partOfGraph)
    ctx.warn(std::to_string(unassigned) + " triangles belong to no cell and stay black");
  const std::vector<PortalLink> links = linkPortals(graph, cells);
  const std::unique_ptr<PortalTransfer> transfer = makePortalTransfer(params);
  CellWorkers workers(params.jobs, engine);  // an engine per thread for every cell and round
  // The portals' arrival rays meet the same texels every round: traced once. Sized before the rounds, so
  // that the cells solved side by side each write their own links' entries only.
  ArrivalHitCache arrivalHits(links.size());

  const CellFirstShot first =
      params.firstShot
          ? landFirstShot(
                scene, global,
                FirstShotSum{params.firstShot->emitted,
                             {params.firstShot->irradiance.begin(), params.firstShot->irradiance.end()}},
                cells)
          : shootEmittersIntoCells(scene, global, cellOf, params.solver, cells, workers, ctx);
  SolveResult result = startBookkeeping(graph, cells, global);
  addFirstShotBookkeeping(first, result);
  SolveControls controls;
  controls.readTransfer = true;
  controls.deadline = params.deadline;
  ShotShape shape;
  const double emitted = result.energy.emitted, target = params.solver.unshotFraction * emitted;
  int& rounds = result.perCell->rounds;
  double unshot = emitted;
  double done = 0.0;  // the "cells" progress: unshot power on a log scale from all to the target
  RoundStop stop = roundStop(cells, graph, target, params.maxAmbientShare);
  while (emitted > 0.0 && rounds < params.maxRounds && stop.another(unshot)) {
    if (std::chrono::steady_clock::now() >= params.deadline) {
      result.timedOut = true;
      break;
    }
    ++rounds;
    const SolverParams settings =
        roundBudget(params, stop.target(), unshot, emitted, controls, shape, global.patches.size());
    const std::vector<size_t> active = activeCells(cells, stop.target());
    ctx.progress("cells", done, "round " + std::to_string(rounds) + ": " + cellList(graph, active));
    const std::vector<CellRound> round = solveRound(graph, rounds, cells, active, links, settings, controls,
                                                    shape, *transfer, workers, arrivalHits, ctx);
    for (size_t c : active) {
      addCellRound(round[c], cells[c], graph, result);
      result.timedOut = result.timedOut || round[c].timedOut;
    }
    unshot = endRound(cells, round);
    stop.addRound(inGraphOrder(round));
    done = std::clamp(std::log(std::max(unshot / emitted, 1e-12)) / std::log(params.solver.unshotFraction),
                      0.0, 1.0);
    ctx.progress("cells", done, "round " + std::to_string(rounds));
  }
  result.stopChecks = stop.checks();
  finishBookkeeping(cells, global, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SolveResult solveCellsTwoLevel(const Scene& scene, const CellGraph& graph, const QuadSet& quads,
                               const LightmapAtlas& global, const TwoLevelParams& levels,
                               const CellSolveParams& params, const ShotEngines& engines, Context& ctx,
                               TwoLevelData* data) {
  if (params.firstShot) throw InputError("cells", "a two-level cells solve shoots its lamps itself");
  const CoarseSolve cellByCell = [&](const LightmapAtlas& coarse, const AtlasParams& coarseParams,
                                     const SolveControls& c) {
    CellSolveParams p = params;
    p.atlas = coarseParams;
    p.firstShot = c.priorShot;
    return solveCells(scene, graph, coarse, p, engines.reflections, ctx);
  };
  // Member by member: GCC 12 takes roomStop's std::function for uninitialized under designated initializers.
  SolveControls controls;
  controls.readTransfer = true;
  controls.deadline = params.deadline;
  controls.load = params.load;
  // The sky's gather on the output atlas draws towards the cells' portals onto the outside (the graph's
  // face out of their rooms: resolveCells turns a file's).
  controls.skyOpenings = skyOpeningsOf(graph);
  controls.skyTimeShare = kBakeSkyTimeShare;
  return solveTwoLevel(scene, quads, global, params.atlas, levels, params.solver, engines, ctx, controls,
                       data, cellByCell);
}

AtlasParams coarseAtlasParams(const AtlasParams& atlas) {
  AtlasParams coarse = atlas;
  if (atlas.texelsPerQuad > 0)
    coarse.texelsPerQuad = std::max(2, atlas.texelsPerQuad / 2);
  else
    coarse.density = atlas.density / 2.0f;
  for (float& d : coarse.triangleDensity) d /= 2.0f;
  return coarse;
}

SolveResult solveCellsOnDemand(const Scene& scene, const CellGraph& graph, const CellSelection& selection,
                               BoundaryMode mode, const LightmapAtlas& global, const CellSolveParams& params,
                               ShotEngine& engine, Context& ctx) {
  if (selection.baked.empty()) throw InputError("cells", "an on-demand bake needs at least one cell");
  const CellValidation validation = validateCells(scene, graph);
  if (!validation.errors.empty()) throw InputError("cell graph", validation.errors.front());
  for (const std::string& w : validation.warnings) ctx.warn(w);

  // The solved part of the graph: baked cells, boundary cells in Coarse mode, the portals between them.
  std::vector<int> solved = selection.baked;
  if (mode == BoundaryMode::Coarse)
    solved.insert(solved.end(), selection.boundary.begin(), selection.boundary.end());
  std::sort(solved.begin(), solved.end());
  std::vector<int> subIndex(graph.cells.size(), -1);
  CellGraph sub;
  CellSolveParams subParams = params;
  subParams.partOfGraph = true;
  subParams.boundaryAtlas = coarseAtlasParams(params.atlas);
  subParams.boundaryCells.clear();
  for (int c : solved) {
    subIndex[c] = int(sub.cells.size());
    if (!std::binary_search(selection.baked.begin(), selection.baked.end(), c))
      subParams.boundaryCells.push_back(int(sub.cells.size()));
    sub.cells.push_back(graph.cells[c]);
  }
  for (const PortalQuad& q : graph.portals) {
    if (q.cellA < 0 || q.cellB < 0 || subIndex[q.cellA] < 0 || subIndex[q.cellB] < 0) continue;
    PortalQuad p = q;
    p.cellA = subIndex[q.cellA], p.cellB = subIndex[q.cellB];
    sub.portals.push_back(p);
  }
  return solveCells(scene, sub, global, subParams, engine, ctx);
}

}  // namespace cpgi
