// The cell-portal graph (thesis ch. 7): cells are rooms, portals are planar quads joining two cells.
// Hand-made cells come from a glTF by the naming convention of design.md §3; the automatic
// decomposition produces the same structure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace cpgi {

/// One portal: a planar quad, corners in order around the boundary.
struct PortalQuad {
  std::string name;                    ///< the glTF node name, "portal:A:B"
  std::array<glm::vec3, 4> corners{};  ///< world space, metres, in boundary order
  glm::vec3 normal{0.0f};              ///< unit; points from cellA into cellB
  float area = 0.0f;                   ///< m²
  int cellA = -1;                      ///< index into CellGraph::cells
  int cellB = -1;
  glm::vec3 centre() const { return (corners[0] + corners[1] + corners[2] + corners[3]) * 0.25f; }
};

struct Cell {
  std::string name;
  std::vector<uint32_t> triangles;  ///< indices into Scene::triangles
  std::vector<Triangle> volume;     ///< optional closed mesh bounding the cell's empty space ("cellvolume:")
};

struct CellGraph {
  std::vector<Cell> cells;
  std::vector<PortalQuad> portals;

  bool empty() const { return cells.empty(); }
  int findCell(const std::string& name) const;
  /// Indices of the portals touching cell c.
  std::vector<int> portalsOf(int c) const;
  /// Cell index per scene triangle, -1 for a triangle in no cell.
  std::vector<int> cellOfTriangle(size_t triangleCount) const;
  /// True when every cell can be reached from cell 0 through portals.
  bool connected() const;
  /// True for rooms given only as volumes: cells, each with a volume, but no triangle in any and no
  /// portal (decomp::decomposeFromVolumes makes the rest).
  bool definedByVolumes() const;
};

/// Fills corners' normal and area from the corners (Newell's method, so slightly non-planar quads work).
void computePortalFrame(PortalQuad& portal);

/// Problems found by validateCells; each names the node at fault.
struct CellValidation {
  std::vector<std::string> errors;    ///< make the graph unusable (unknown cell, non-planar portal, ...)
  std::vector<std::string> warnings;  ///< worth telling (disconnected graph, triangles in no cell, ...)
};

/// Checks a graph against its scene: portals planar within `planarTolerance` metres, portal cells exist
/// and differ, every triangle in at most one cell, graph connected.
CellValidation validateCells(const Scene& scene, const CellGraph& graph, float planarTolerance = 1e-3f);

}  // namespace cpgi
