// The scene's convex planar pieces that no ray passes (each triangle, or the rectangle two triangles make:
// core/quads.h), and the test that one of them blocks a whole shaft between two convex polygons. A
// shaft so blocked needs no ray: every segment from one polygon to the other crosses the piece inside its
// edges, so each ray Embree would trace along one is hidden (its watertight robust traversal finds a
// triangle crossed that far inside). The lamps' shot by rays (lamp_light.h) skips with it the rays from a
// texel to a lamp behind a wall: in a building nearly every texel faces lamps in other rooms.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace cpgi {

class OccluderPieces {
 public:
  /// The pieces of every triangle of `scene`, for a RayScene built from the same scene. `margin` (metres,
  /// > 0): how far inside a piece's edges and off the shaft's ends a crossing must be to count, far above
  /// float rounding (a rectangle's triangles out of its plane by more than a tenth of it stay apart).
  OccluderPieces(const Scene& scene, double margin);

  /// The piece triangle `t` belongs to; -1 for a degenerate triangle (no ray ever hits one).
  int32_t pieceOf(int32_t t) const {
    return t >= 0 && size_t(t) < pieceOfTriangle_.size() ? pieceOfTriangle_[t] : -1;
  }
  size_t size() const { return pieces_.size(); }
  double margin() const { return margin_; }

  /// True when piece `piece` lies across every segment from a point of the convex polygon `from` to a
  /// point of the convex polygon `to` that stops `shortfall` metres or more before `to` (a shadow ray
  /// that must not hit its own lamp): both polygons at least `margin` off the piece's plane on opposite
  /// sides (`to` by `shortfall` more), every crossing at least `margin` inside the piece's edges. At most
  /// four corners each.
  bool blocks(int32_t piece, std::span<const glm::dvec3> from, std::span<const glm::dvec3> to,
              double shortfall) const;

 private:
  struct Piece {
    glm::dvec3 normal{0.0};  ///< unit; the plane is dot(normal, p) = offset
    double offset = 0.0;
    int edges = 0;
    /// Per edge, its inward unit normal in the plane and dot(inward, a point of the edge): inside where
    /// dot(inward[k], p) >= edgeOffset[k] for every k.
    glm::dvec3 inward[4];
    double edgeOffset[4] = {};
  };
  static Piece convexPiece(std::span<const glm::dvec3> corners, const glm::dvec3& normal);

  std::vector<Piece> pieces_;
  std::vector<int32_t> pieceOfTriangle_;
  double margin_ = 0.0;
};

}  // namespace cpgi
