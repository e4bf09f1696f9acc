#include "radiosity/cells/cell_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "radiosity/cells/cell_atlases.h"
#include "radiosity/cells/cell_first_shot.h"
#include "radiosity/cells/cell_workers.h"
#include "radiosity/cells/portal_transfer.h"

namespace cpgi {
namespace {

double power(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas) {
  double sum = 0.0;
  for (size_t i = 0; i < exitance.size(); ++i)
    if (atlas.patch[i] >= 0) sum += (double(exitance[i].r) + exitance[i].g + exitance[i].b) * atlas.area[i];
  return sum;
}

glm::dvec3 texelPower(const glm::vec3& v, float area) {
  return glm::dvec3(v) * double(area);
}

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
    d.cells[c].emitted = power(cells[c].pending, cells[c].atlas);
    d.cells[c].texels = cells[c].atlas.validTexels();
    d.cells[c].written = !cells[c].boundary;
    result.energy.emitted += d.cells[c].emitted;
    d.maxCellTexels = std::max(d.maxCellTexels, d.cells[c].texels);
  }
  for (size_t p = 0; p < graph.portals.size(); ++p) d.portals[p].name = graph.portals[p].name;
  return result;
}

// The round's stopping rule. Half the scene's budget is for what the solves leave unshot (the other half for
// what the portals collect): a solve stops at that fraction of the round's input, or as soon as no patch
// holds more than its share of it (half the budget over the scene's patches). A cell lit only through a
// door must not be solved to the scene's fraction of its own small input: a room of many small patches
// would then take more shots than the whole scene.
SolverParams roundBudget(const SolverParams& settings, double target, double unshot, SolveControls& controls,
                         size_t globalPatches) {
  SolverParams round = settings;
  round.unshotFraction = std::clamp(0.5 * target / unshot, 1e-9, 0.999999);
  controls.minShotPower = 0.5 * target / double(std::max<size_t>(globalPatches, 1));
  return round;
}

// What the next round starts from, per cell, gathered during this one.
struct NextRound {
  std::vector<std::vector<glm::vec3>> pending, carried;
};

// The cells solved this round, their pending light moved into their atlas's emission. A cell holding a
// negligible share waits (its light stays pending, counted as unshot).
std::vector<size_t> activeCells(std::vector<CellState>& cells, double target, NextRound& next,
                                PortalTransfer& transfer) {
  std::vector<size_t> active;
  for (size_t c = 0; c < cells.size(); ++c) {
    CellState& s = cells[c];
    if (!(power(s.pending, s.atlas) > 1e-6 * target)) {
      for (size_t i = 0; i < s.pending.size(); ++i) next.pending[c][i] += s.pending[i];
      transfer.keepPending(c);
      next.carried[c] = s.carried;
      continue;
    }
    for (size_t i = 0; i < s.pending.size(); ++i) s.atlas.emission[i] = s.pending[i];
    active.push_back(c);
  }
  return active;
}

// The round's solves are independent (each reads only its own cell): side by side with `jobs`.
std::vector<SolveResult> solveRound(const std::vector<CellState>& cells, const std::vector<size_t>& active,
                                    const SolverParams& settings, const SolveControls& controls,
                                    const PortalTransfer& transfer, CellWorkers& workers, Context& ctx) {
  std::vector<SolveResult> solvedOf(cells.size());
  auto t = ctx.time("cells: solve");
  workers.run(active.size(), ctx,
              [&](size_t k, const EglContext& context, SolverPrograms& programs, Context& taskCtx) {
                SolveControls own = controls;
                own.programs = &programs;
                solvedOf[active[k]] =
                    transfer.solve(active[k], cells[active[k]], settings, own, context, taskCtx);
              });
  return solvedOf;
}

// Re-emission through the portals leaving cell `c` after its solve: the irradiance collected on the
// sending side becomes exitance on the far side. Returns the power collected (W, R + G + B).
double sendThroughPortals(size_t c, const CellState& s, const SolveResult& solved,
                          const std::vector<PortalLink>& links, const std::vector<CellState>& cells,
                          const CellGraph& graph, NextRound& next, PortalTransfer& transfer,
                          CellSolveData& result) {
  double collected = 0.0;
  for (const PortalLink& link : links) {
    if (link.from != int(c)) continue;
    const LightmapAtlas& to = cells[link.to].atlas;
    glm::dvec3 sent(0.0), arrived(0.0);
    for (const auto& [tt, ft] : link.texels) arrived += texelPower(solved.incident[ft], to.area[tt]);
    const Patch& F = s.atlas.patches[link.fromPatch];
    for (int j = 0; j < F.h; ++j)
      for (int i = 0; i < F.w; ++i) {
        const size_t t = size_t(F.y + j) * s.atlas.width + F.x + i;
        if (s.atlas.patch[t] == link.fromPatch) sent += texelPower(solved.incident[t], s.atlas.area[t]);
      }
    // Exitance on the far side = irradiance on this side, rescaled so that the power through the opening
    // is exactly what arrived (charts of the two sides may differ).
    glm::vec3 scale(0.0f);
    for (int k = 0; k < 3; ++k) scale[k] = arrived[k] > 0.0 ? float(sent[k] / arrived[k]) : 0.0f;
    for (const auto& [tt, ft] : link.texels) next.pending[link.to][tt] += solved.incident[ft] * scale;
    transfer.send(link, solved, scale);
    const double w = sent.r + sent.g + sent.b;
    collected += w;
    result.cells[c].sent += w;
    result.cells[link.to].received += w;
    (link.from == graph.portals[link.portal].cellA ? result.portals[link.portal].aToB
                                                   : result.portals[link.portal].bToA) += w;
  }
  return collected;
}

// One cell's solve into the result, in cell order so the numbers do not depend on which solve finished
// first: its radiosity into the global atlas, what it left unshot kept pending, its portals' light sent on.
void syncCell(size_t c, const CellState& s, const SolveResult& solved, const std::vector<PortalLink>& links,
              const std::vector<CellState>& cells, const CellGraph& graph, NextRound& next,
              PortalTransfer& transfer, SolveResult& result) {
  CellEnergy& ce = result.perCell->cells[c];
  ++ce.solves;
  ce.shots += solved.shots;
  result.shots += solved.shots;
  ce.seconds += solved.seconds;
  ce.escaped += solved.energy.escaped();
  ce.created += solved.energy.created;
  ce.worstShotGain = std::max(ce.worstShotGain, solved.energy.worstShotGain);
  result.energy.created += solved.energy.created;
  result.energy.worstShotGain = std::max(result.energy.worstShotGain, solved.energy.worstShotGain);
  result.energy.shot += solved.energy.shot;
  result.energy.received += solved.energy.received;
  for (const auto& [g, t] : s.toGlobal) result.radiosity[g] += solved.radiosity[t] - s.carried[t];
  // What the solve left unshot is shot at the next one; it is in the radiosity already.
  next.carried[c] = solved.residual;
  for (size_t i = 0; i < s.pending.size(); ++i) next.pending[c][i] += solved.residual[i];
  transfer.keepUnshot(c, s, solved.residual);
  const double collected =
      sendThroughPortals(c, s, solved, links, cells, graph, next, transfer, *result.perCell);
  // Portal texels have albedo 0: all they received counts as absorbed by the solver.
  ce.absorbed += solved.energy.absorbed - collected;
}

// The round's gathered light becomes pending; returns the power now unshot everywhere.
double endRound(std::vector<CellState>& cells, NextRound& next, PortalTransfer& transfer) {
  double unshot = 0.0;
  for (size_t c = 0; c < cells.size(); ++c) {
    cells[c].pending = std::move(next.pending[c]);
    cells[c].carried = next.carried[c].empty()
                           ? std::vector<glm::vec3>(cells[c].pending.size(), glm::vec3(0.0f))
                           : std::move(next.carried[c]);
    unshot += power(cells[c].pending, cells[c].atlas);
  }
  transfer.endRound();
  return unshot;
}

// What is still pending at the stop, per global texel (W/m²), for the ambient term (radiosity/gpu/ambient.h)
// to follow: light arrived on a portal and not yet shot is spread over its cell's own texels, where it
// would have landed first. Without it the ambient term spread the whole scene's unshot power by area, and
// a dim room two doors from the lamp came out 19 % bright at the default stop.
std::vector<glm::vec3> pendingPerGlobalTexel(const std::vector<CellState>& cells, const LightmapAtlas& global) {
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

// The totals once the rounds are over.
void finishBookkeeping(const std::vector<CellState>& cells, const LightmapAtlas& global,
                       SolveResult& result) {
  for (size_t c = 0; c < cells.size(); ++c) {
    CellEnergy& ce = result.perCell->cells[c];
    ce.unshot = power(cells[c].pending, cells[c].atlas);
    result.energy.absorbed += ce.absorbed;
    result.energy.unshot += ce.unshot;
  }
  result.residual = pendingPerGlobalTexel(cells, global);
  result.unshotFraction = result.energy.emitted > 0.0 ? result.energy.unshot / result.energy.emitted : 0.0;
  for (size_t i = 0; i < result.radiosity.size(); ++i)
    if (global.patch[i] < 0) result.radiosity[i] = glm::vec3(0.0f);
}

// The cells a round solves, for its progress line: the first six names and how many more.
std::string cellList(const CellGraph& graph, const std::vector<size_t>& active) {
  std::string list = active.size() == 1 ? "cell " : "cells ";
  for (size_t k = 0; k < active.size() && k < 6; ++k) list += (k ? ", " : "") + graph.cells[active[k]].name;
  if (active.size() > 6) list += " and " + std::to_string(active.size() - 6) + " more";
  return list;
}

}  // namespace

const char* portalLightName(PortalLight p) {
  return p == PortalLight::Directional ? "directional" : "diffuse";
}

SolveResult solveCells(const Scene& scene, const CellGraph& graph, const LightmapAtlas& global,
                       const CellSolveParams& params, const EglContext& gl, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  checkCells(scene, graph, params, ctx);
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<CellState> cells;
  {
    auto t = ctx.time("cells: atlases");
    std::vector<int32_t> localIndex;
    cells = buildCellAtlases(scene, graph, params, localIndex, ctx);
    mapCellTexels(cells, cellOf, localIndex, global, ctx);
  }
  const size_t unassigned = size_t(std::count_if(cellOf.begin(), cellOf.end(), [](int c) { return c < 0; }));
  if (unassigned > 0 && !params.partOfGraph)
    ctx.warn(std::to_string(unassigned) + " triangles belong to no cell and stay black");
  const std::vector<PortalLink> links = linkPortals(graph, cells);
  const std::unique_ptr<PortalTransfer> transfer = makePortalTransfer(params, cells);
  CellWorkers workers(params.jobs, gl);  // programs compiled once per context for every cell and round

  const CellFirstShot first = shootEmittersIntoCells(scene, global, cellOf, params.solver, cells, workers, ctx);
  SolveResult result = startBookkeeping(graph, cells, global);
  addFirstShotBookkeeping(first, result);
  SolveControls controls;
  controls.readTransfer = true;
  controls.deadline = params.deadline;
  const double emitted = result.energy.emitted, target = params.solver.unshotFraction * emitted;
  int& rounds = result.perCell->rounds;
  double unshot = emitted;
  double done = 0.0;  // the "cells" progress: unshot power on a log scale from all to the target
  while (emitted > 0.0 && unshot > target && rounds < params.maxRounds) {
    if (std::chrono::steady_clock::now() >= params.deadline) {
      result.timedOut = true;
      break;
    }
    ++rounds;
    const SolverParams settings = roundBudget(params.solver, target, unshot, controls, global.patches.size());
    NextRound next{std::vector<std::vector<glm::vec3>>(cells.size()),
                   std::vector<std::vector<glm::vec3>>(cells.size())};
    for (size_t c = 0; c < cells.size(); ++c)
      next.pending[c].assign(cells[c].pending.size(), glm::vec3(0.0f));
    transfer->beginRound();
    const std::vector<size_t> active = activeCells(cells, target, next, *transfer);
    ctx.progress("cells", done, "round " + std::to_string(rounds) + ": " + cellList(graph, active));
    std::vector<SolveResult> solved = solveRound(cells, active, settings, controls, *transfer, workers, ctx);
    for (size_t c : active) {
      syncCell(c, cells[c], solved[c], links, cells, graph, next, *transfer, result);
      result.timedOut = result.timedOut || solved[c].timedOut;
    }
    unshot = endRound(cells, next, *transfer);
    done = std::clamp(std::log(std::max(unshot / emitted, 1e-12)) / std::log(params.solver.unshotFraction), 0.0,
                      1.0);
    ctx.progress("cells", done, "round " + std::to_string(rounds));
  }
  finishBookkeeping(cells, global, result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

AtlasParams coarseAtlasParams(const AtlasParams& atlas) {
  AtlasParams coarse = atlas;
  if (atlas.texelsPerQuad > 0)
    coarse.texelsPerQuad = std::max(2, atlas.texelsPerQuad / 2);
  else
    coarse.density = atlas.density / 2.0f;
  return coarse;
}

SolveResult solveCellsOnDemand(const Scene& scene, const CellGraph& graph, const CellSelection& selection,
                               BoundaryMode mode, const LightmapAtlas& global, const CellSolveParams& params,
                               const EglContext& gl, Context& ctx) {
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
  return solveCells(scene, sub, global, subParams, gl, ctx);
}

}  // namespace cpgi
