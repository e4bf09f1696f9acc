// Algorithm 3's set-up (thesis ch. 8): every cell as a scene of its own with its own atlas, where each of
// its texels lands in the global atlas, and the portal links that carry light from one cell to the next.
// Stages of solveCells (cell_solver.cpp), in this order.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/emission_bins.h"

namespace cpgi {

/// The scene one cell is solved in: its triangles (in graph order) then two triangles per portal, facing
/// into the cell, with a material of albedo 0 and no emission appended.
struct CellScene {
  Scene scene;
  std::vector<uint32_t> globalTriangle;  ///< per cell-scene triangle: the scene triangle, or -1 for a portal
  std::vector<int> portals;              ///< graph portal per portal pair, in triangle order
  size_t ownTriangles = 0;               ///< the first ownTriangles triangles are the cell's
};
CellScene makeCellScene(const Scene& scene, const CellGraph& graph, int cell);

/// For every valid texel of `to`'s patch `toPatch`, the texel of `from`'s patch `fromPatch` covering the same
/// point (by `from`'s chart parametrisation; the nearest valid texel where it falls outside). -1 elsewhere
/// in `to`'s chart; outside that chart, entries are left as they were when the vector already has one
/// entry per texel of `to` (so a caller mapping patch after patch does not pay for the whole atlas each
/// time). Both patches must be the same surface (possibly seen from the other side).
void mapPatchTexels(const LightmapAtlas& from, int fromPatch, const LightmapAtlas& to, int toPatch,
                    std::vector<int32_t>& sourceOfTexel);

/// One cell, ready to solve again and again: its atlas, where its texels go in the global atlas, and its
/// portal patches.
struct CellState {
  CellScene cs;
  LightmapAtlas atlas;
  std::vector<int> patchOfTriangle;                   ///< per cell-scene triangle: its patch, or -1
  std::vector<std::pair<int32_t, int32_t>> toGlobal;  ///< (global texel, cell texel)
  /// Per CellScene::portals entry, the patch of each of its two triangles (the same one twice when the
  /// atlas charts the portal as one quad; two loose triangles when its corners are not a rectangle).
  std::vector<std::array<int, 2>> portalPatches;
  std::vector<glm::vec3> pending;  ///< exitance to shoot at the next solve (W/m²)
  std::vector<glm::vec3> carried;  ///< the part of `pending` already counted in the radiosity
  /// Directional portals: per texel, the arrival moments of `pending` (radiosity/solve/emission_lobes.h),
  /// fitted into its emission lobes at the next solve; empty with diffuse portals.
  std::vector<glm::vec4> pendingMoments;
  /// Binned portals: per texel holding pending light that crossed a portal, its arrival bins
  /// (radiosity/solve/emission_bins.h), weighted so that each channel sums to that of its pending exitance.
  std::map<int32_t, ArrivalBins> pendingBins;
  bool boundary = false;  ///< an on-demand boundary cell: coarse atlas, texels not written
};

/// Per patch of `s.atlas`, 1 for a portal patch.
std::vector<char> portalPatchFlags(const CellState& s);

/// Per portal and direction: (texel in the receiving cell, texel in the sending cell).
struct PortalLink {
  int portal = -1;
  int from = -1, to = -1;  ///< cells
  /// The portal's patches in each cell, per triangle (CellState::portalPatches): a portal whose corners are
  /// not a rectangle is two loose triangles, and each is half of what it collects and sends.
  std::array<int, 2> fromPatches{-1, -1}, toPatches{-1, -1};
  std::vector<std::pair<int32_t, int32_t>> texels;
};

/// `params` for cell scene `cs`'s atlas: per-triangle densities (AtlasParams::triangleDensity, one per
/// scene triangle) carried to its own triangles; its portals get `params.density` × `portalDensityScale`
/// (CellSolveParams::portalDensityScale; with texelsPerQuad, the quads' own count).
AtlasParams cellAtlasParams(const AtlasParams& params, const CellScene& cs, float portalDensityScale = 1.0f);

/// Every cell's scene and atlas (cells side by side), its own emitters pending. Boundary cells
/// (CellSolveParams::boundaryCells) get params.boundaryAtlas. `localIndex` receives, per scene triangle,
/// its index in its cell's scene (-1 for none).
std::vector<CellState> buildCellAtlases(const Scene& scene, const CellGraph& graph,
                                        const CellSolveParams& params, std::vector<int32_t>& localIndex,
                                        Context& ctx);

/// CellState::toGlobal for every cell that is written. A global chart may be a grid of quads
/// (radiosity/lightmap/quad_grids.h) that the cells cut apart, so each texel goes by the triangle under it
/// to that triangle's cell patch. Warns when a patch is charted differently in its cell.
void mapCellTexels(std::vector<CellState>& cells, const std::vector<int>& cellOfTriangle,
                   const std::vector<int32_t>& localIndex, const LightmapAtlas& global, Context& ctx);

/// buildCellAtlases, then mapCellTexels onto `global` (timed as "cells: atlases"): the cells of a whole
/// solve, a job plan or a gather.
std::vector<CellState> buildMappedCellAtlases(const Scene& scene, const CellGraph& graph,
                                              const CellSolveParams& params,
                                              const std::vector<int>& cellOfTriangle,
                                              const LightmapAtlas& global, Context& ctx);

/// Both directions of every portal, with the texel of the sending side under each receiving texel.
/// Throws InputError when a portal has no patch in one of its cells (a degenerate quad).
std::vector<PortalLink> linkPortals(const CellGraph& graph, const std::vector<CellState>& cells);

}  // namespace cpgi
