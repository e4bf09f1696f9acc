// The dense voxel lattice every decomposition stage shares. Voxel (x, y, z) is the cube of side `voxel`
// centred on origin + voxel·(x, y, z) (OpenVDB's index space: centres at integer coordinates), stored
// x fastest. Dense because the watershed visits every empty voxel anyway: a 30k-triangle house at 5 cm
// is ~10⁷ voxels, a few bytes each.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

namespace cpgi::decomp {

struct GridFrame {
  glm::dvec3 origin{0.0};  ///< world position of voxel (0,0,0)'s centre, metres
  double voxel = 0.1;      ///< edge length, metres
  glm::ivec3 dims{0};      ///< voxels along x, y, z

  size_t count() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
  size_t index(int x, int y, int z) const { return (size_t(z) * size_t(dims.y) + size_t(y)) * size_t(dims.x) + size_t(x); }
  size_t index(const glm::ivec3& c) const { return index(c.x, c.y, c.z); }
  glm::ivec3 coord(size_t i) const {
    const size_t sx = size_t(dims.x), sxy = sx * size_t(dims.y);
    return {int(i % sx), int((i / sx) % size_t(dims.y)), int(i / sxy)};
  }
  bool contains(const glm::ivec3& c) const {
    return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims.x && c.y < dims.y && c.z < dims.z;
  }
  glm::vec3 centre(const glm::ivec3& c) const { return glm::vec3(origin + voxel * glm::dvec3(c)); }
  glm::vec3 centre(size_t i) const { return centre(coord(i)); }
  /// The voxel whose cube holds p (may lie outside the grid; check with contains()).
  glm::ivec3 voxelOf(const glm::vec3& p) const {
    const glm::dvec3 q = (glm::dvec3(p) - origin) / voxel;
    return {int(std::floor(q.x + 0.5)), int(std::floor(q.y + 0.5)), int(std::floor(q.z + 0.5))};
  }
  double voxelVolume() const { return voxel * voxel * voxel; }
};

/// What a voxel holds after classification (classify.h).
enum class Space : uint8_t {
  Solid = 0,    ///< within half a voxel of a triangle, or sealed by the closing
  Inside = 1,   ///< enclosed empty space in front of the geometry: the space cells are made of
  Outside = 2,  ///< empty space reachable from the padded bounds
  Void = 3,     ///< enclosed empty space behind the geometry (inside a thick wall or a closed box)
};

/// The six face neighbours; the decomposition uses 6-connectivity for empty space throughout, so a solid
/// layer one voxel thick is a wall (a diagonal step cannot slip through it).
inline constexpr int kFaceNeighbours[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

}  // namespace cpgi::decomp
