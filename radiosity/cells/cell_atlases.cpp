#include "radiosity/cells/cell_atlases.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/quads.h"

namespace cpgi {
namespace {

std::vector<int> patchOfTriangle(const LightmapAtlas& atlas, size_t triangles) {
  std::vector<int> of(triangles, -1);
  for (size_t p = 0; p < atlas.patches.size(); ++p)
    for (int32_t t : atlas.patches[p].triangles)
      if (t >= 0) of[t] = int(p);
  return of;
}

// Where the texels of global patch `gp` go: per quad of its chart (one for a single quad or a loose
// triangle), the (cell, cell patch) under it; (-1, -1) for a triangle in no written cell.
std::vector<std::pair<int, int>> cellPatchesUnder(const Patch& P, const std::vector<CellState>& cells,
                                                  const std::vector<int>& cellOfTriangle,
                                                  const std::vector<int32_t>& localIndex) {
  std::vector<std::pair<int, int>> target(P.quads.empty() ? 1 : P.quads.size(), {-1, -1});
  for (size_t m = 0; m < target.size(); ++m) {
    const int32_t tri = P.triangles[P.quads.empty() ? 0 : 2 * m];
    const int c = cellOfTriangle[tri];
    if (c < 0 || cells[c].boundary) continue;
    target[m] = {c, cells[c].patchOfTriangle[localIndex[tri]]};
  }
  return target;
}

}  // namespace

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
      const int ii = std::clamp(int(std::floor(a)), 0, q.w - 1),
                jj = std::clamp(int(std::floor(b)), 0, q.h - 1);
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

// A cell's atlas settings: the scene's per-triangle densities (bake --density auto) carried over to the
// cell scene's triangles, so that its charts are the whole scene's; its portals take the plain density.
AtlasParams cellAtlasParams(const AtlasParams& params, const CellScene& cs, float portalDensityScale) {
  AtlasParams p = params;
  if (params.texelsPerQuad > 0 || (params.triangleDensity.empty() && portalDensityScale == 1.0f)) return p;
  p.triangleDensity.assign(cs.scene.triangles.size(), params.density * portalDensityScale);
  for (size_t i = 0; i < cs.ownTriangles; ++i)
    p.triangleDensity[i] =
        params.triangleDensity.empty() ? params.density : params.triangleDensity.at(cs.globalTriangle[i]);
  return p;
}

std::vector<CellState> buildCellAtlases(const Scene& scene, const CellGraph& graph,
                                        const CellSolveParams& params, std::vector<int32_t>& localIndex,
                                        Context& ctx) {
  const size_t nc = graph.cells.size();
  std::vector<CellState> cells(nc);
  for (int c : params.boundaryCells) cells.at(size_t(c)).boundary = true;
  localIndex.assign(scene.triangles.size(), -1);
  // Cells side by side (TBB): a cell's triangles are its own, so the localIndex writes never meet;
  // each cell's warnings and timings go to ctx in cell order afterwards.
  std::vector<Context> cellCtx(nc);
  tbb::parallel_for(size_t(0), nc, [&](size_t c) {
    CellState& s = cells[c];
    s.cs = makeCellScene(scene, graph, int(c));
    for (size_t i = 0; i < s.cs.ownTriangles; ++i) localIndex[s.cs.globalTriangle[i]] = int32_t(i);
    s.atlas = buildAtlas(
        s.cs.scene, findQuads(s.cs.scene),
        cellAtlasParams(s.boundary ? params.boundaryAtlas : params.atlas, s.cs, params.portalDensityScale),
        cellCtx[c]);
    s.patchOfTriangle = patchOfTriangle(s.atlas, s.cs.scene.triangles.size());
    for (size_t k = 0; k < s.cs.portals.size(); ++k) {
      std::array<int, 2> patches{s.patchOfTriangle[s.cs.ownTriangles + 2 * k],
                                 s.patchOfTriangle[s.cs.ownTriangles + 2 * k + 1]};
      // A degenerate triangle (three corners in a row) has no patch: the other is the whole portal.
      if (patches[0] < 0) patches[0] = patches[1];
      if (patches[1] < 0) patches[1] = patches[0];
      s.portalPatches.push_back(patches);
    }
    s.pending.assign(s.atlas.texelCount(), glm::vec3(0.0f));
    for (size_t i = 0; i < s.atlas.texelCount(); ++i)
      if (s.atlas.patch[i] >= 0) s.pending[i] = s.atlas.emission[i];
    s.carried.assign(s.atlas.texelCount(), glm::vec3(0.0f));
  });
  for (const Context& c : cellCtx) {
    for (const Context::Timing& timing : c.timings()) ctx.addTiming(timing.stage, timing.seconds);
    for (const std::string& w : c.warnings()) ctx.warn(w);
  }
  return cells;
}

void mapCellTexels(std::vector<CellState>& cells, const std::vector<int>& cellOfTriangle,
                   const std::vector<int32_t>& localIndex, const LightmapAtlas& global, Context& ctx) {
  std::vector<int32_t> source;
  size_t differing = 0;
  for (size_t gp = 0; gp < global.patches.size(); ++gp) {
    const Patch& P = global.patches[gp];
    const std::vector<std::pair<int, int>> target = cellPatchesUnder(P, cells, cellOfTriangle, localIndex);
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
    ctx.warn(std::to_string(differing) +
             " patches are charted differently in their cell than in the whole scene");
}

std::vector<char> portalPatchFlags(const CellState& s) {
  std::vector<char> portal(s.atlas.patches.size(), 0);
  for (const std::array<int, 2>& patches : s.portalPatches)
    for (int p : patches)
      if (p >= 0) portal[size_t(p)] = 1;
  return portal;
}

std::vector<CellState> buildMappedCellAtlases(const Scene& scene, const CellGraph& graph,
                                              const CellSolveParams& params,
                                              const std::vector<int>& cellOfTriangle,
                                              const LightmapAtlas& global, Context& ctx) {
  auto t = ctx.time("cells: atlases");
  std::vector<int32_t> localIndex;
  std::vector<CellState> cells = buildCellAtlases(scene, graph, params, localIndex, ctx);
  mapCellTexels(cells, cellOfTriangle, localIndex, global, ctx);
  return cells;
}

std::vector<PortalLink> linkPortals(const CellGraph& graph, const std::vector<CellState>& cells) {
  std::vector<PortalLink> links;
  std::vector<int32_t> source;
  for (size_t p = 0; p < graph.portals.size(); ++p) {
    const PortalQuad& q = graph.portals[p];
    auto patchesIn = [&](int c) {
      const CellState& s = cells[c];
      for (size_t k = 0; k < s.cs.portals.size(); ++k)
        if (s.cs.portals[k] == int(p)) return s.portalPatches[k];
      return std::array<int, 2>{-1, -1};
    };
    for (auto [from, to] : {std::pair{q.cellA, q.cellB}, std::pair{q.cellB, q.cellA}}) {
      PortalLink link{int(p), from, to, patchesIn(from), patchesIn(to), {}};
      if (link.fromPatches[0] < 0 || link.toPatches[0] < 0)
        throw InputError(q.name, "portal has no patch (degenerate quad?)");
      // Each receiving patch from the sending cell's patch of the same triangle (both cells build the
      // portal's two triangles from the same corners, in the same order).
      for (int m = 0; m < 2; ++m) {
        if (m == 1 && link.toPatches[1] == link.toPatches[0]) break;
        mapPatchTexels(cells[from].atlas, link.fromPatches[m], cells[to].atlas, link.toPatches[m], source);
        const Patch& P = cells[to].atlas.patches[link.toPatches[m]];
        for (int j = 0; j < P.h; ++j)
          for (int i = 0; i < P.w; ++i) {
            const int32_t t = (P.y + j) * cells[to].atlas.width + P.x + i;
            if (cells[to].atlas.patch[t] == link.toPatches[m] && source[t] >= 0)
              link.texels.push_back({t, source[t]});
          }
      }
      links.push_back(std::move(link));
    }
  }
  return links;
}

}  // namespace cpgi
