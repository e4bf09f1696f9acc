// Which cells an on-demand bake solves (thesis ch. 10, "lighting on demand for the cells near the
// viewer"): cells picked by name, or the cell holding a point plus every cell within K portals of it.
//
// What the rest of the graph does. A bake of one room must still show the lamp of the room next door
// through the open door, and the light that lamp bounces off that room's walls, otherwise a room lit
// through its doors is black or much too dark and "bake only what I look at" is useless. So by default the
// *boundary* cells (one portal away from a chosen cell, not chosen themselves) are solved fully but on a
// coarse atlas (half the texels per edge, a quarter of the texels): their lamps and bounces reach the chosen
// cells through the boundary portals, light the chosen cells send out comes back through them, and their
// texels are not written. Cells farther away are dark: their portals towards the boundary cells are left
// open, so light going there is lost (counted as escaped). Measured on seed1 at 8² texels per quad
// (bench/RESULTS.md): room B, lit only through its doors, is 3.9 % (relative RMSE) from the whole cells bake
// with coarse neighbours and black with dark ones; rooms with their own lamp are within 0.3 % either way.
// `BoundaryMode::Dark` makes the boundary cells dark too (the chosen cells then see only their own
// lamps: useful to isolate a room, and cheapest).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

enum class BoundaryMode {
  Coarse,  ///< cells next to the chosen ones are solved on a coarse atlas and light them through portals
  Dark,    ///< only the chosen cells are solved; every other cell is dark
};

const char* boundaryModeName(BoundaryMode m);

/// The part each cell of a graph plays in an on-demand bake (indices into CellGraph::cells, ascending).
struct CellSelection {
  std::vector<int> baked;     ///< solved and written
  std::vector<int> boundary;  ///< not chosen, one portal from a chosen cell (solved coarsely in Coarse mode)
  std::vector<int> dark;      ///< neither: never solved
};

/// The cells named in a comma-separated list ("A,B"; spaces around names ignored), ascending, each once.
/// Throws InputError(parameter, ...) for an empty list or a name that is not a cell (listing the names);
/// `parameter` is what the caller calls the list.
std::vector<int> cellsByName(const CellGraph& graph, const std::string& list, const std::string& parameter);

/// The cell whose empty space holds `point`, or -1. Decided by rays in 64 directions spread over the
/// sphere against the scene's triangles and the portal quads: a ray that first meets the front face of a
/// cell's triangle votes for that cell, one that first meets a portal votes for the portal's cell on the
/// ray's origin side, one that meets a back face (the point is inside a wall or outside the building)
/// or nothing votes for no cell. The cell with more than half of the votes wins. Robust to gaps between
/// triangles and to portals seen through other portals; a point on a wall is ambiguous and gets -1.
int cellContaining(const Scene& scene, const CellGraph& graph, const glm::vec3& point);

/// Cells reachable from `start` through at most `depth` portals (start included), ascending.
std::vector<int> cellsWithin(const CellGraph& graph, int start, int depth);

/// Splits the graph's cells into baked (the given ones), boundary and dark.
CellSelection selectCells(const CellGraph& graph, const std::vector<int>& baked);

/// The cell of every texel of `atlas` (an atlas of the whole scene with `triangleCount` triangles): -1
/// for padding and for triangles in no cell. A merged grid chart may span cells, so each texel goes by
/// the quad under it.
std::vector<int> cellOfTexels(const LightmapAtlas& atlas, const CellGraph& graph, size_t triangleCount);

}  // namespace cpgi
