// The cell-portal graph as JSON, for `cpgi info --json` and the decomposition's cells.json.
#pragma once

#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi {

/// {"cells": [{name, triangles, area_m2, bounds {min, max}, volume_triangles}],
///  "portals": [{name, cells [A, B], corners [4 × xyz], centre, normal (A into B), area_m2}],
///  "adjacency": {cell name: [neighbour names]}, "connected": bool, "uncelled_triangles": n}.
/// Lengths in metres, areas in m²; cell bounds and areas are over the cell's scene triangles.
nlohmann::json cellGraphToJson(const Scene& scene, const CellGraph& graph);

/// [x, y, z] as a JSON array.
nlohmann::json toJson(const glm::vec3& v);

}  // namespace cpgi
