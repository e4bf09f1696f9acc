#include "radiosity/cells/cell_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "radiosity/cells/cell_workers.h"
#include "radiosity/gpu/emission_lobes.h"

namespace cpgi {
namespace {

double power(const std::vector<glm::vec3>& exitance, const LightmapAtlas& atlas) {
  double sum = 0.0;
  for (size_t i = 0; i < exitance.size(); ++i)
    if (atlas.patch[i] >= 0) sum += (double(exitance[i].r) + exitance[i].g + exitance[i].b) * atlas.area[i];
  return sum;
}

glm::dvec3 texelPower(const glm::vec3& v, float area) { return glm::dvec3(v) * double(area); }

// One cell, ready to solve again and again: its atlas, where its texels go in the global atlas, and its
// portal patches.
struct CellState {
  CellScene cs;
  LightmapAtlas atlas;
  std::vector<std::pair<int32_t, int32_t>> toGlobal;  ///< (global texel, cell texel)
  std::vector<int> portalPatch;                       ///< per CellScene::portals entry
  std::vector<glm::vec3> pending;  ///< exitance to shoot at the next solve (W/m²)
  std::vector<glm::vec3> carried;  ///< the part of `pending` already counted in the radiosity
  /// Directional portals: arrival moments of `pending` per texel (emission_lobes.h); empty otherwise.
  std::vector<glm::vec4> pendingArrivals;
};

// Per portal and direction: (texel in the receiving cell, texel in the sending cell).
struct PortalLink {
  int portal = -1;
  int from = -1, to = -1;  ///< cells
  int fromPatch = -1, toPatch = -1;
  std::vector<std::pair<int32_t, int32_t>> texels;
};

std::vector<int> patchOfTriangle(const LightmapAtlas& atlas, size_t triangles) {
  std::vector<int> of(triangles, -1);
  for (size_t p = 0; p < atlas.patches.size(); ++p)
    for (int32_t t : atlas.patches[p].triangles)
      if (t >= 0) of[t] = int(p);
  return of;
}

// Directional portals. One cell solve, emitting `pending` with the lobes fitted to its arrival moments.
SolveResult solveDirectional(const CellState& s, const SolverParams& solverParams, float lobeMinWidth,
                             const EglContext& gl, Context& ctx, SolverPrograms& programs) {
  SolverParams p = solverParams;
  p.directionalEmission = true;
  return solveProgressive(s.cs.scene, s.atlas, p, fitEmissionLobes(s.pendingArrivals, s.atlas, lobeMinWidth), gl,
                          ctx, programs);
}

// Directional portals: the moments of what a solve left unshot. A texel's residual is the part of its
// pending exitance it did not shoot (portal texels have albedo 0 and gain none), so its moments are the
// pending ones scaled by the same share.
void carryArrivals(const CellState& s, const std::vector<glm::vec3>& residual, std::vector<glm::vec4>& next) {
  for (size_t i = 0; i < s.pendingArrivals.size(); ++i) {
    const float pending = s.pending[i].r + s.pending[i].g + s.pending[i].b;
    const float left = residual[i].r + residual[i].g + residual[i].b;
    if (s.pendingArrivals[i].w > 0.0f && pending > 0.0f && left > 0.0f)
      next[i] += s.pendingArrivals[i] * std::min(left / pending, 1.0f);
  }
}

}  // namespace

const char* portalLightName(PortalLight p) { return p == PortalLight::Directional ? "directional" : "diffuse"; }

PortalLight parsePortalLight(const std::string& name) {
  if (name == "diffuse") return PortalLight::Diffuse;
  if (name == "directional") return PortalLight::Directional;
  throw InputError("--portals", "must be diffuse or directional, not '" + name + "'");
}

CellScene makeCellScene(const Scene& scene, const CellGraph& graph, int cell) {
  CellScene out;
  out.scene.materials = scene.materials;
  out.scene.nodePaths = scene.nodePaths;
  const uint32_t portalMaterial = uint32_t(out.scene.materials.size());
  out.scene.materials.push_back(Material{"portal", glm::vec3(0.0f), glm::vec3(0.0f)});
  for (uint32_t t : graph.cells[cell].triangles) {
    out.scene.triangles.push_back(scene.triangles[t]);
    out.globalTriangle.push_back(t);
  }
  out.ownTriangles = out.scene.triangles.size();
  for (int p : graph.portalsOf(cell)) {
    const PortalQuad& q = graph.portals[p];
    const glm::vec3 into = q.cellA == cell ? -q.normal : q.normal;
    const auto& c = q.corners;
    Triangle a, b;
    a.p = {c[0], c[1], c[2]}, b.p = {c[0], c[2], c[3]};
    if (glm::dot(a.geometricNormal(), into) < 0.0f) a.p = {c[0], c[2], c[1]}, b.p = {c[0], c[3], c[2]};
    a.n = b.n = {into, into, into};
    a.material = b.material = portalMaterial;
    a.node = b.node = uint32_t(out.scene.nodePaths.size());
    out.scene.nodePaths.push_back(q.name);
    out.scene.triangles.push_back(a), out.scene.triangles.push_back(b);
    out.globalTriangle.push_back(uint32_t(-1)), out.globalTriangle.push_back(uint32_t(-1));
    out.portals.push_back(p);
  }
  return out;
}

void mapPatchTexels(const LightmapAtlas& from, int fromPatch, const LightmapAtlas& to, int toPatch,
                    std::vector<int32_t>& sourceOfTexel) {
  const Patch& q = from.patches[fromPatch];
  const Patch& p = to.patches[toPatch];
  if (sourceOfTexel.size() != to.texelCount())
    sourceOfTexel.assign(to.texelCount(), -1);
  else
    for (int j = 0; j < p.h; ++j) std::fill_n(sourceOfTexel.begin() + (p.y + j) * to.width + p.x, p.w, -1);
  std::vector<int32_t> valid;
  for (int j = 0; j < q.h; ++j)
    for (int i = 0; i < q.w; ++i) {
      const int32_t s = (q.y + j) * from.width + q.x + i;
      if (from.patch[s] == fromPatch) valid.push_back(s);
    }
  if (valid.empty()) return;
  const glm::vec3 u = q.texelU, v = q.texelV;
  const double uu = glm::dot(u, u), uv = glm::dot(u, v), vv = glm::dot(v, v), det = uu * vv - uv * uv;
  for (int j = 0; j < p.h; ++j)
    for (int i = 0; i < p.w; ++i) {
      const int32_t t = (p.y + j) * to.width + p.x + i;
      if (to.patch[t] != toPatch) continue;
      const glm::vec3 d = to.position[t] - q.origin;
      const double du = glm::dot(d, u), dv = glm::dot(d, v);
      const double a = (vv * du - uv * dv) / det, b = (uu * dv - uv * du) / det;
      const int ii = std::clamp(int(std::floor(a)), 0, q.w - 1), jj = std::clamp(int(std::floor(b)), 0, q.h - 1);
      const int32_t s = (q.y + jj) * from.width + q.x + ii;
      if (from.patch[s] == fromPatch) {
        sourceOfTexel[t] = s;
        continue;
      }
      // Outside the valid part (a loose triangle's edge): the nearest valid texel.
      float best = std::numeric_limits<float>::max();
      for (int32_t c : valid) {
        const glm::vec3 e = from.position[c] - to.position[t];
        if (glm::dot(e, e) < best) best = glm::dot(e, e), sourceOfTexel[t] = c;
      }
    }
}

CellSolveResult solveCells(const Scene& scene, const CellGraph& graph, const LightmapAtlas& global,
                           const CellSolveParams& params, const EglContext& gl, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  if (graph.empty()) throw InputError("--cells", "the cell graph has no cells");
  const CellValidation validation = validateCells(scene, graph);
  if (!validation.errors.empty()) throw InputError("--cells", validation.errors.front());
  if (!params.partOfGraph)
    for (const std::string& w : validation.warnings) ctx.warn(w);
  if (params.maxRounds < 1) throw InputError("solver", "cell rounds must be at least 1");
  const bool directional = params.portals == PortalLight::Directional;
  if (directional && !(params.lobeMinWidth > 0.0f && params.lobeMinWidth <= 0.45f))
    throw InputError("solver", "the narrowest portal lobe must be in (0, 0.45]");

  const size_t nc = graph.cells.size();
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::vector<int32_t> localIndex(scene.triangles.size(), -1);
  std::vector<CellState> cells(nc);
  std::vector<std::vector<int>> cellPatchOf(nc);  // per cell, per cell-scene triangle: its patch
  std::vector<char> boundary(nc, 0);                // on-demand boundary cells: coarse atlas, not written
  for (int c : params.boundaryCells) boundary.at(size_t(c)) = 1;
  std::vector<int32_t> source;
  {
    auto t = ctx.time("cells: atlases");
    // Cells side by side (TBB): a cell's triangles are its own, so the localIndex writes never meet;
    // each cell's warnings and timings go to ctx in cell order afterwards.
    std::vector<Context> cellCtx(nc);
    tbb::parallel_for(size_t(0), nc, [&](size_t c) {
      CellState& s = cells[c];
      s.cs = makeCellScene(scene, graph, int(c));
      for (size_t i = 0; i < s.cs.ownTriangles; ++i) localIndex[s.cs.globalTriangle[i]] = int32_t(i);
      s.atlas = buildAtlas(s.cs.scene, findQuads(s.cs.scene), boundary[c] ? params.boundaryAtlas : params.atlas,
                           cellCtx[c]);
      const std::vector<int> patchOf = patchOfTriangle(s.atlas, s.cs.scene.triangles.size());
      for (size_t k = 0; k < s.cs.portals.size(); ++k) s.portalPatch.push_back(patchOf[s.cs.ownTriangles + 2 * k]);
      cellPatchOf[c] = patchOf;
      s.pending.assign(s.atlas.texelCount(), glm::vec3(0.0f));
      for (size_t i = 0; i < s.atlas.texelCount(); ++i)
        if (s.atlas.patch[i] >= 0) s.pending[i] = s.atlas.emission[i];
      s.carried.assign(s.atlas.texelCount(), glm::vec3(0.0f));
      if (directional) s.pendingArrivals.assign(s.atlas.texelCount(), glm::vec4(0.0f));
    });
    for (const Context& c : cellCtx) {
      for (const Context::Timing& timing : c.timings()) ctx.addTiming(timing.stage, timing.seconds);
      for (const std::string& w : c.warnings()) ctx.warn(w);
    }
    // Global charts → cell charts. A global chart may be a grid of quads (radiosity/lightmap/quad_grids.h) that
    // the cells cut apart, so each texel goes by the triangle under it to that triangle's cell patch.
    size_t differing = 0;
    for (size_t gp = 0; gp < global.patches.size(); ++gp) {
      const Patch& P = global.patches[gp];
      std::vector<std::pair<int, int>> target(P.quads.empty() ? 1 : P.quads.size(), {-1, -1});  // (cell, patch)
      for (size_t m = 0; m < target.size(); ++m) {
        const int32_t tri = P.triangles[P.quads.empty() ? 0 : 2 * m];
        const int c = cellOf[tri];
        if (c < 0 || boundary[c]) continue;
        target[m] = {c, cellPatchOf[c][localIndex[tri]]};
      }
      std::vector<std::pair<int, int>> distinct = target;
      std::sort(distinct.begin(), distinct.end());
      distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
      for (const auto& [c, q] : distinct) {
        if (c < 0 || q < 0) continue;
        CellState& s = cells[c];
        const Patch& Q = s.atlas.patches[q];
        if (distinct.size() == 1 && (Q.w != P.w || Q.h != P.h || (P.quad >= 0) != (Q.quad >= 0))) ++differing;
        mapPatchTexels(s.atlas, q, global, int(gp), source);
        const int tw = P.w / P.grid.x, th = P.h / P.grid.y;
        for (int j = 0; j < P.h; ++j)
          for (int i = 0; i < P.w; ++i) {
            const int32_t g = (P.y + j) * global.width + P.x + i;
            const size_t m = P.quads.empty() ? 0 : size_t(j / th) * P.grid.x + size_t(i / tw);
            if (source[g] >= 0 && target[m] == std::pair{c, q}) s.toGlobal.push_back({g, source[g]});
          }
      }
    }
    if (differing > 0)
      ctx.warn(std::to_string(differing) + " patches are charted differently in their cell than in the whole scene");
  }
  size_t unassigned = 0;
  for (int c : cellOf) unassigned += c < 0;
  if (unassigned > 0 && !params.partOfGraph)
    ctx.warn(std::to_string(unassigned) + " triangles belong to no cell and stay black");

  // Portal links both ways.
  std::vector<PortalLink> links;
  for (size_t p = 0; p < graph.portals.size(); ++p) {
    const PortalQuad& q = graph.portals[p];
    auto patchIn = [&](int c) {
      const CellState& s = cells[c];
      for (size_t k = 0; k < s.cs.portals.size(); ++k)
        if (s.cs.portals[k] == int(p)) return s.portalPatch[k];
      return -1;
    };
    for (auto [from, to] : {std::pair{q.cellA, q.cellB}, std::pair{q.cellB, q.cellA}}) {
      PortalLink link{int(p), from, to, patchIn(from), patchIn(to), {}};
      if (link.fromPatch < 0 || link.toPatch < 0) throw InputError(q.name, "portal has no patch (degenerate quad?)");
      mapPatchTexels(cells[from].atlas, link.fromPatch, cells[to].atlas, link.toPatch, source);
      const Patch& P = cells[to].atlas.patches[link.toPatch];
      for (int j = 0; j < P.h; ++j)
        for (int i = 0; i < P.w; ++i) {
          const int32_t t = (P.y + j) * cells[to].atlas.width + P.x + i;
          if (source[t] >= 0) link.texels.push_back({t, source[t]});
        }
      links.push_back(std::move(link));
    }
  }

  CellSolveResult result;
  result.radiosity.assign(global.texelCount(), glm::vec3(0.0f));
  result.cells.resize(nc);
  result.portals.resize(graph.portals.size());
  for (size_t c = 0; c < nc; ++c) {
    result.cells[c].name = graph.cells[c].name;
    result.cells[c].emitted = power(cells[c].pending, cells[c].atlas);
    result.cells[c].texels = cells[c].atlas.validTexels();
    result.cells[c].written = !boundary[c];
    result.emitted += result.cells[c].emitted;
    result.maxCellTexels = std::max(result.maxCellTexels, result.cells[c].texels);
  }
  for (size_t p = 0; p < graph.portals.size(); ++p) result.portals[p].name = graph.portals[p].name;

  SolverParams solverParams = params.solver;
  solverParams.readTransfer = true;
  CellWorkers workers(params.jobs, gl);  // programs compiled once per context for every cell and round
  const double target = params.solver.unshotFraction * result.emitted;
  double unshot = result.emitted;
  while (result.emitted > 0.0 && unshot > target && result.rounds < params.maxRounds) {
    ++result.rounds;
    // Half the scene's budget is for what the solves leave unshot (the other half for what the portals
    // collect): a solve stops at that fraction of the round's input, or as soon as no patch holds more
    // than its share of it (half the budget over the scene's patches). A cell lit only through a door
    // must not be solved to the scene's fraction of its own small input: a room of many small patches
    // would then take more shots than the whole scene.
    solverParams.unshotFraction = std::clamp(0.5 * target / unshot, 1e-9, 0.999999);
    solverParams.minShotPower = 0.5 * target / double(std::max<size_t>(global.patches.size(), 1));
    std::vector<std::vector<glm::vec3>> nextPending(nc), nextCarried(nc);
    std::vector<std::vector<glm::vec4>> nextArrivals(nc);  // directional portals only
    for (size_t c = 0; c < nc; ++c) nextPending[c].assign(cells[c].pending.size(), glm::vec3(0.0f));
    if (directional)
      for (size_t c = 0; c < nc; ++c) nextArrivals[c].assign(cells[c].pending.size(), glm::vec4(0.0f));
    std::vector<size_t> active;  // the cells solved this round
    for (size_t c = 0; c < nc; ++c) {
      CellState& s = cells[c];
      const double injected = power(s.pending, s.atlas);
      // A cell holding a negligible share waits (its light stays pending, counted as unshot).
      if (!(injected > 1e-6 * target)) {
        for (size_t i = 0; i < s.pending.size(); ++i) nextPending[c][i] += s.pending[i];
        for (size_t i = 0; i < s.pendingArrivals.size(); ++i) nextArrivals[c][i] += s.pendingArrivals[i];
        nextCarried[c] = s.carried;
        continue;
      }
      for (size_t i = 0; i < s.pending.size(); ++i) s.atlas.emission[i] = s.pending[i];
      active.push_back(c);
    }
    // The round's solves are independent (each reads only its own cell): side by side with --jobs.
    std::vector<SolveResult> solvedOf(nc);
    {
      auto t = ctx.time("cells: solve");
      auto solve = [&](size_t k, const EglContext& context, SolverPrograms& programs, Context& taskCtx) {
        const CellState& s = cells[active[k]];
        solvedOf[active[k]] =
            directional ? solveDirectional(s, solverParams, params.lobeMinWidth, context, taskCtx, programs)
                        : solveProgressive(s.cs.scene, s.atlas, solverParams, context, taskCtx, programs);
      };
      workers.run(active.size(), ctx, solve);
    }
    // Syncs in cell order, so the numbers do not depend on which solve finished first.
    for (size_t c : active) {
      CellState& s = cells[c];
      CellEnergy& ce = result.cells[c];
      const SolveResult solved = std::move(solvedOf[c]);
      ++ce.solves;
      ce.shots += solved.shots;
      result.shots += solved.shots;
      ce.seconds += solved.seconds;
      ce.escaped += solved.energy.escaped();
      for (const auto& [g, t] : s.toGlobal) result.radiosity[g] += solved.radiosity[t] - s.carried[t];
      // What the solve left unshot is shot at the next one; it is in the radiosity already.
      nextCarried[c] = solved.residual;
      for (size_t i = 0; i < s.pending.size(); ++i) nextPending[c][i] += solved.residual[i];
      if (directional) carryArrivals(s, solved.residual, nextArrivals[c]);
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
        // Diffuse re-emission: exitance on the far side = irradiance on this side, rescaled so that
        // the power through the opening is exactly what arrived (charts of the two sides may differ).
        glm::vec3 scale(0.0f);
        for (int k = 0; k < 3; ++k) scale[k] = arrived[k] > 0.0 ? float(sent[k] / arrived[k]) : 0.0f;
        for (const auto& [tt, ft] : link.texels) nextPending[link.to][tt] += solved.incident[ft] * scale;
        // Directional: the moments go along, in world coordinates (the far side's normal is this side's
        // negated, as the moments assume), weighted like the exitance they describe.
        if (directional)
          for (const auto& [tt, ft] : link.texels)
            nextArrivals[link.to][tt] += solved.arrivals[ft] * ((scale.r + scale.g + scale.b) / 3.0f);
        const double w = sent.r + sent.g + sent.b;
        collected += w;
        ce.sent += w;
        result.cells[link.to].received += w;
        (link.from == graph.portals[link.portal].cellA ? result.portals[link.portal].aToB
                                                       : result.portals[link.portal].bToA) += w;
      }
      // Portal texels have albedo 0: all they received counts as absorbed by the solver.
      ce.absorbed += solved.energy.absorbed - collected;
    }
    unshot = 0.0;
    for (size_t c = 0; c < nc; ++c) {
      cells[c].pending = std::move(nextPending[c]);
      if (directional) cells[c].pendingArrivals = std::move(nextArrivals[c]);
      cells[c].carried = nextCarried[c].empty() ? std::vector<glm::vec3>(cells[c].pending.size(), glm::vec3(0.0f))
                                                : std::move(nextCarried[c]);
      unshot += power(cells[c].pending, cells[c].atlas);
    }
    ctx.progress("cells", std::clamp(std::log(std::max(unshot / result.emitted, 1e-12)) /
                                         std::log(params.solver.unshotFraction), 0.0, 1.0),
                 "round " + std::to_string(result.rounds));
  }
  for (size_t c = 0; c < nc; ++c) {
    CellEnergy& ce = result.cells[c];
    ce.unshot = power(cells[c].pending, cells[c].atlas);
    result.absorbed += ce.absorbed;
    result.escaped += ce.escaped;
    result.unshot += ce.unshot;
  }
  result.unshotFraction = result.emitted > 0.0 ? result.unshot / result.emitted : 0.0;
  for (size_t i = 0; i < result.radiosity.size(); ++i)
    if (global.patch[i] < 0) result.radiosity[i] = glm::vec3(0.0f);
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

CellSolveResult solveCellsOnDemand(const Scene& scene, const CellGraph& graph, const CellSelection& selection,
                                   BoundaryMode mode, const LightmapAtlas& global, const CellSolveParams& params,
                                   const EglContext& gl, Context& ctx) {
  if (selection.baked.empty()) throw InputError("cells", "an on-demand bake needs at least one cell");
  const CellValidation validation = validateCells(scene, graph);
  if (!validation.errors.empty()) throw InputError("--cells", validation.errors.front());
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
