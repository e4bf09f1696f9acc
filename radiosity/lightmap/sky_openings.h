// The openings through which the inside of a building sees the sky (its exterior doors and open windows:
// the portals of the cell named "outside"), and the directions the sky gather (sky_light.h) draws towards
// them. A texel that sees the outside through a far door sees it in a few of its cosine directions (the
// house's kitchen wall through two aligned doors: 0.48 %, 1.2 rays of 256), so its estimate is 0, 1, 2 or
// 3 rays' worth: bright squares and a mottle. Directions drawn uniformly in each opening's solid angle
// (Ureña, Fajardo & King 2013, "An Area-Preserving Parametrization for Spherical Rectangles", as Cycles'
// portal lights sample interiors), combined with the cosine directions by the balance heuristic (Veach
// 1997), keep the estimate unbiased whatever the openings: a direction through one that an inner door
// clips is a ray spent, not a bias.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "core/cell_graph.h"

namespace cpgi {

/// A rectangle the sky is seen through: the bounding rectangle, in its plane, of a portal onto the outside.
struct SkyOpening {
  glm::dvec3 corner{0.0};  ///< world space, metres
  glm::dvec3 edgeU{0.0};   ///< from corner along one side, orthogonal to edgeV
  glm::dvec3 edgeV{0.0};
  glm::dvec3 outward{0.0};  ///< unit normal pointing out of the building
};

/// The openings of `graph`: each portal joining the cell named "outside" to another, as its bounding
/// rectangle in its plane (a portal need not be one) grown by `margin` metres on every side (an automatic
/// portal lies on voxels and can stop short of its door's jambs), facing away from the room. None when the
/// graph has no such cell.
std::vector<SkyOpening> skyOpeningsOf(const CellGraph& graph, double margin = 0.05);

/// A rectangle as seen from one point: its solid angle and the map of the unit square onto it that keeps
/// area (Ureña et al. 2013), so that sample(u, v) over uniform (u, v) is uniform in solid angle.
class SphericalRectangle {
 public:
  SphericalRectangle() = default;
  /// From `eye`, looking at `opening` from either side. solidAngle() is 0 for an eye in its plane.
  SphericalRectangle(const glm::dvec3& eye, const SkyOpening& opening);
  double solidAngle() const { return solidAngle_; }
  /// The unit direction from the eye to the point of the rectangle at (u, v) in [0, 1]².
  glm::dvec3 sample(double u, double v) const;

 private:
  glm::dvec3 eye_{0.0}, x_{0.0}, y_{0.0}, z_{0.0};
  double x0_ = 0, y0_ = 0, z0_ = 0, x1_ = 0, y1_ = 0, b0_ = 0, b1_ = 0, k_ = 0, solidAngle_ = 0;
};

/// Whether the ray from `eye` along unit `dir` crosses `opening` (ahead of the eye).
bool crosses(const SkyOpening& opening, const glm::dvec3& eye, const glm::dvec3& dir);

/// The openings a texel draws directions towards, and their odds: those it is inside of and that rise
/// above its tangent plane, at most kMostOpenings of them by their solid angle times the cosine towards
/// their centre (visibility unknown: an opening behind a wall costs rays only).
class TexelOpenings {
 public:
  static constexpr int kMostOpenings = 8;
  TexelOpenings(const std::vector<SkyOpening>& openings, const glm::dvec3& eye, const glm::dvec3& normal);
  bool empty() const { return count_ == 0; }
  /// A direction drawn by the openings' odds (`pick` in [0, 1)) and uniformly in that one's solid angle.
  glm::dvec3 sample(double pick, double u, double v) const;
  /// The density of sample()'s directions at unit `dir`, per steradian.
  double pdf(const glm::dvec3& dir) const;
  /// The spherical rectangles set up to choose them (the costly part): no more than the openings kept
  /// while the others' bound on their weight is under the least kept.
  int rectanglesSetUp() const { return rectangles_; }

 private:
  const std::vector<SkyOpening>* openings_;
  glm::dvec3 eye_;
  int count_ = 0;
  int rectangles_ = 0;
  std::array<int, kMostOpenings> index_{};
  std::array<double, kMostOpenings> odds_{}, cumulative_{}, solidAngle_{};
  std::array<SphericalRectangle, kMostOpenings> rect_;
};

}  // namespace cpgi
