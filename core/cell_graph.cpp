#include "core/cell_graph.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace cpgi {

int CellGraph::findCell(const std::string& name) const {
  for (size_t i = 0; i < cells.size(); ++i)
    if (cells[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<int> CellGraph::portalsOf(int c) const {
  std::vector<int> out;
  for (size_t i = 0; i < portals.size(); ++i)
    if (portals[i].cellA == c || portals[i].cellB == c) out.push_back(static_cast<int>(i));
  return out;
}

std::vector<int> CellGraph::cellOfTriangle(size_t triangleCount) const {
  std::vector<int> out(triangleCount, -1);
  for (size_t c = 0; c < cells.size(); ++c)
    for (uint32_t t : cells[c].triangles)
      if (t < triangleCount) out[t] = static_cast<int>(c);
  return out;
}

bool CellGraph::connected() const {
  if (cells.empty()) return true;
  std::vector<char> seen(cells.size(), 0);
  std::queue<int> todo;
  todo.push(0);
  seen[0] = 1;
  while (!todo.empty()) {
    const int c = todo.front();
    todo.pop();
    for (int p : portalsOf(c)) {
      const int other = portals[p].cellA == c ? portals[p].cellB : portals[p].cellA;
      if (other >= 0 && !seen[other]) seen[other] = 1, todo.push(other);
    }
  }
  for (char s : seen)
    if (!s) return false;
  return true;
}

bool CellGraph::definedByVolumes() const {
  if (cells.empty() || !portals.empty()) return false;
  return std::all_of(cells.begin(), cells.end(),
                     [](const Cell& c) { return c.triangles.empty() && !c.volume.empty(); });
}

void computePortalFrame(PortalQuad& portal) {
  // Newell's method: the vector area of the polygon; robust for slightly non-planar quads.
  glm::vec3 n(0.0f);
  for (int i = 0; i < 4; ++i) n += glm::cross(portal.corners[i], portal.corners[(i + 1) % 4]);
  const float twiceArea = glm::length(n);
  portal.area = 0.5f * twiceArea;
  portal.normal = twiceArea > 0.0f ? n / twiceArea : glm::vec3(0.0f);
}

CellValidation validateCells(const Scene& scene, const CellGraph& graph, float planarTolerance) {
  CellValidation v;
  for (const PortalQuad& p : graph.portals) {
    const std::string node = p.name.empty() ? std::string("portal") : p.name;
    if (p.cellA < 0 || p.cellA >= static_cast<int>(graph.cells.size()) || p.cellB < 0 ||
        p.cellB >= static_cast<int>(graph.cells.size())) {
      v.errors.push_back(node + ": names a cell that does not exist");
      continue;
    }
    if (p.cellA == p.cellB)
      v.errors.push_back(node + ": joins cell " + graph.cells[p.cellA].name + " to itself");
    if (!(p.area > 0.0f)) {
      v.errors.push_back(node + ": has zero area");
      continue;
    }
    const glm::vec3 c = p.centre();
    float worst = 0.0f;
    for (const glm::vec3& q : p.corners) worst = std::max(worst, std::abs(glm::dot(q - c, p.normal)));
    if (worst > planarTolerance)
      v.errors.push_back(node + ": not planar (a corner is " + std::to_string(worst) + " m off its plane)");
  }

  std::vector<int> owner(scene.triangles.size(), -1);
  size_t outOfRange = 0, shared = 0;
  for (size_t c = 0; c < graph.cells.size(); ++c) {
    for (uint32_t t : graph.cells[c].triangles) {
      if (t >= scene.triangles.size()) {
        ++outOfRange;
        continue;
      }
      if (owner[t] >= 0 && owner[t] != static_cast<int>(c)) ++shared;
      owner[t] = static_cast<int>(c);
    }
  }
  if (outOfRange) v.errors.push_back(std::to_string(outOfRange) + " cell triangle indices out of range");
  if (shared) v.errors.push_back(std::to_string(shared) + " triangles belong to more than one cell");
  if (!graph.cells.empty()) {
    size_t orphans = 0;
    for (int o : owner) orphans += o < 0;
    if (orphans) v.warnings.push_back(std::to_string(orphans) + " triangles are in no cell");
    if (!graph.connected()) v.warnings.push_back("the cell graph is not connected");
    for (size_t c = 0; c < graph.cells.size(); ++c)
      if (graph.portalsOf(static_cast<int>(c)).empty() && graph.cells.size() > 1)
        v.warnings.push_back("cell:" + graph.cells[c].name + ": has no portal");
  }
  return v;
}

}  // namespace cpgi
