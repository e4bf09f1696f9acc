#include "radiosity/cells/cell_selection.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <sstream>

#include "core/error.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi {

const char* boundaryModeName(BoundaryMode m) {
  return m == BoundaryMode::Coarse ? "coarse" : "dark";
}

std::vector<int> cellsByName(const CellGraph& graph, const std::string& list, const std::string& parameter) {
  std::vector<int> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    const auto first = name.find_first_not_of(" \t"), last = name.find_last_not_of(" \t");
    name = first == std::string::npos ? std::string() : name.substr(first, last - first + 1);
    if (name.empty()) continue;
    const int c = graph.findCell(name);
    if (c < 0) {
      std::string names;
      for (const Cell& cell : graph.cells) names += (names.empty() ? "" : ", ") + cell.name;
      throw InputError(parameter, "no cell named '" + name + "' (cells: " + names + ")");
    }
    out.push_back(c);
  }
  if (out.empty()) throw InputError(parameter, "names no cell");
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

int cellContaining(const Scene& scene, const CellGraph& graph, const glm::vec3& point) {
  // The scene's triangles, then two per portal quad.
  Scene rays;
  rays.triangles = scene.triangles;
  for (const PortalQuad& q : graph.portals) {
    Triangle a, b;
    a.p = {q.corners[0], q.corners[1], q.corners[2]};
    b.p = {q.corners[0], q.corners[2], q.corners[3]};
    rays.triangles.push_back(a), rays.triangles.push_back(b);
  }
  const RayScene rayScene(rays);
  const std::vector<int> cellOf = graph.cellOfTriangle(scene.triangles.size());
  std::map<int, int> votes;
  constexpr int kRays = 64;
  const float golden = 3.14159265f * (3.0f - std::sqrt(5.0f));
  for (int i = 0; i < kRays; ++i) {
    // Fibonacci sphere: evenly spread, and no direction along an axis (axis-aligned rays would graze
    // the seams of axis-aligned walls).
    const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(kRays);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = golden * float(i);
    const glm::vec3 dir(r * std::cos(phi), r * std::sin(phi), z);
    const RayScene::Hit hit = rayScene.intersect(point, dir);
    int vote = -1;
    if (hit && size_t(hit.triangle) >= scene.triangles.size()) {
      const PortalQuad& q = graph.portals[(size_t(hit.triangle) - scene.triangles.size()) / 2];
      vote = glm::dot(dir, q.normal) > 0.0f ? q.cellA : q.cellB;  // the normal points from A into B
    } else if (hit && glm::dot(dir, scene.triangles[hit.triangle].geometricNormal()) < 0.0f) {
      vote = cellOf[hit.triangle];
    }
    ++votes[vote];
  }
  for (const auto& [cell, count] : votes)
    if (cell >= 0 && 2 * count > kRays) return cell;
  return -1;
}

std::vector<int> cellsWithin(const CellGraph& graph, int start, int depth) {
  std::vector<int> distance(graph.cells.size(), -1);
  std::queue<int> todo;
  distance[start] = 0;
  todo.push(start);
  while (!todo.empty()) {
    const int c = todo.front();
    todo.pop();
    if (distance[c] >= depth) continue;
    for (int p : graph.portalsOf(c)) {
      const int other = graph.portals[p].cellA == c ? graph.portals[p].cellB : graph.portals[p].cellA;
      if (other >= 0 && distance[other] < 0) distance[other] = distance[c] + 1, todo.push(other);
    }
  }
  std::vector<int> out;
  for (size_t c = 0; c < distance.size(); ++c)
    if (distance[c] >= 0) out.push_back(int(c));
  return out;
}

CellSelection selectCells(const CellGraph& graph, const std::vector<int>& baked) {
  std::vector<char> role(graph.cells.size(), 0);  // 0 dark, 1 boundary, 2 baked
  for (int c : baked) role[c] = 2;
  for (const PortalQuad& q : graph.portals) {
    if (q.cellA < 0 || q.cellB < 0) continue;
    if (role[q.cellA] == 2 && role[q.cellB] == 0) role[q.cellB] = 1;
    if (role[q.cellB] == 2 && role[q.cellA] == 0) role[q.cellA] = 1;
  }
  CellSelection s;
  for (size_t c = 0; c < role.size(); ++c)
    (role[c] == 2 ? s.baked : role[c] == 1 ? s.boundary : s.dark).push_back(int(c));
  return s;
}

std::vector<int> cellOfTexels(const LightmapAtlas& atlas, const CellGraph& graph, size_t triangleCount) {
  const std::vector<int> cellOf = graph.cellOfTriangle(triangleCount);
  std::vector<int> out(atlas.texelCount(), -1);
  for (size_t p = 0; p < atlas.patches.size(); ++p) {
    const Patch& P = atlas.patches[p];
    const int tw = std::max(1, P.w / P.grid.x), th = std::max(1, P.h / P.grid.y);
    for (int j = 0; j < P.h; ++j)
      for (int i = 0; i < P.w; ++i) {
        const size_t t = size_t(P.y + j) * atlas.width + P.x + i;
        if (atlas.patch[t] != int(p)) continue;
        const size_t m = P.quads.empty() ? 0 : size_t(j / th) * P.grid.x + size_t(i / tw);
        const size_t k = P.quads.empty() ? 0 : 2 * m;
        if (k < P.triangles.size() && size_t(P.triangles[k]) < triangleCount) out[t] = cellOf[P.triangles[k]];
      }
  }
  return out;
}

}  // namespace cpgi
