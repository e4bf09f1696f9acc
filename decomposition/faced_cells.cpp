#include "decomposition/faced_cells.h"

#include <stdexcept>

namespace cpgi::decomp {

std::vector<int> cellsFaced(const Decomposition& d, std::span<const glm::vec3> points,
                            std::span<const glm::vec3> normals) {
  if (points.size() != normals.size()) throw std::invalid_argument("cellsFaced: one normal per point");
  std::vector<int> cell(points.size(), -1);
  if (d.voxelCell.size() != d.frame.count()) return cell;
  // Half-voxel steps: a texel centre half a voxel from a wall's face may still be in its solid shell.
  constexpr float kSteps[] = {1.0f, 1.5f, 2.0f, 2.5f, 3.0f};
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 n = glm::length(normals[i]) > 0.0f ? glm::normalize(normals[i]) : glm::vec3(0.0f);
    if (n == glm::vec3(0.0f)) continue;
    for (const float k : kSteps) {
      const glm::ivec3 v = d.frame.voxelOf(points[i] + n * (k * float(d.frame.voxel)));
      if (!d.frame.contains(v)) break;
      const int c = d.voxelCell[d.frame.index(v)];
      if (c >= 0) {
        cell[i] = c;
        break;
      }
    }
  }
  return cell;
}

}  // namespace cpgi::decomp
