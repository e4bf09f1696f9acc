// Which cell a point on a surface belongs to, by the empty space in front of it: for labelling the texels
// of a scene that has no cells of its own (its lightmap's per-cell figures and ambient term follow the
// rooms of the automatic decomposition, issue 11 item 1) without splitting any of its triangles.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "decomposition/decompose.h"

namespace cpgi::decomp {

/// Per point, the cell of the first voxel holding a cell (Decomposition::voxelCell) along its normal,
/// from one to three voxels out (the voxels touching a surface are solid); −1 when there is none (a
/// surface facing into a wall's void, or outside the grid). `points` and `normals` are the same length.
std::vector<int> cellsFaced(const Decomposition& d, std::span<const glm::vec3> points,
                            std::span<const glm::vec3> normals);

}  // namespace cpgi::decomp
