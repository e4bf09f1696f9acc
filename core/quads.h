// The thesis's patches are quads (a whole wall is one patch). Scenes arrive as triangles, so planar
// rectangular pairs of triangles are recognised here; everything else stays a loose triangle.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace cpgi {

/// A rectangle made of two triangles of the same material and node.
struct Quad {
  std::array<uint32_t, 2> triangles{};  ///< indices into Scene::triangles
  /// corners[0] is the origin; corners[1] - corners[0] is the u edge, corners[3] - corners[0] the v edge;
  /// (u × v) points along the triangles' normal.
  std::array<glm::vec3, 4> corners{};
  glm::vec3 normal{0.0f};
  float width() const { return glm::length(corners[1] - corners[0]); }
  float height() const { return glm::length(corners[3] - corners[0]); }
  float area() const { return width() * height(); }
};

struct QuadSet {
  std::vector<Quad> quads;
  std::vector<int32_t> quadOfTriangle;  ///< per scene triangle: its quad, or -1 for a loose triangle
  size_t looseTriangles() const;
};

/// Pairs triangles that share their longest edge into rectangles.
/// @param angleTolerance  cosine slack for "right angle" and "coplanar" (default ~0.06°)
QuadSet findQuads(const Scene& scene, float angleTolerance = 1e-3f);

}  // namespace cpgi
