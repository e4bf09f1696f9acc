#include "radiosity/lightmap/occluder_pieces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/quads.h"

namespace cpgi {

OccluderPieces::Piece OccluderPieces::convexPiece(std::span<const glm::dvec3> corners,
                                                  const glm::dvec3& normal) {
  Piece p;
  p.normal = normal;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& c : corners) centre += c / double(corners.size());
  p.offset = glm::dot(normal, centre);
  p.edges = int(corners.size());
  for (int k = 0; k < p.edges; ++k) {
    const glm::dvec3 a = corners[size_t(k)], b = corners[size_t((k + 1) % p.edges)];
    glm::dvec3 in = glm::normalize(glm::cross(normal, b - a));
    if (glm::dot(in, centre - a) < 0.0) in = -in;  // the corners go either way round
    p.inward[k] = in;
    p.edgeOffset[k] = glm::dot(in, a);
  }
  return p;
}

OccluderPieces::OccluderPieces(const Scene& scene, double margin) : margin_(margin) {
  if (!(margin > 0.0)) throw std::invalid_argument("OccluderPieces: the margin must be positive");
  pieceOfTriangle_.assign(scene.triangles.size(), -1);
  auto corner = [&](uint32_t t, int k) { return glm::dvec3(scene.triangles[t].p[k]); };
  // A rectangle is one piece only where its corners are its triangles' own vertices and lie in one plane
  // within a tenth of the margin: a crossing then lies on one of its two triangles wherever it is inside.
  const QuadSet quads = findQuads(scene);
  for (const Quad& q : quads.quads) {
    std::array<glm::dvec3, 4> c;
    bool vertices = true;
    for (int k = 0; k < 4; ++k) {
      c[size_t(k)] = glm::dvec3(q.corners[size_t(k)]);
      bool found = false;
      for (uint32_t t : q.triangles)
        for (int j = 0; j < 3; ++j) found = found || glm::dvec3(scene.triangles[t].p[j]) == c[size_t(k)];
      vertices = vertices && found;
    }
    const glm::dvec3 n = glm::cross(c[1] - c[0], c[3] - c[0]);
    if (!vertices || !(glm::length(n) > 0.0)) continue;
    const glm::dvec3 normal = glm::normalize(n);
    const double plane = glm::dot(normal, c[0]);
    bool flat = true;
    for (const glm::dvec3& x : c) flat = flat && std::abs(glm::dot(normal, x) - plane) <= 0.1 * margin;
    if (!flat) continue;
    for (uint32_t t : q.triangles) pieceOfTriangle_[t] = int32_t(pieces_.size());
    pieces_.push_back(convexPiece(c, normal));
  }
  for (size_t t = 0; t < scene.triangles.size(); ++t) {
    if (pieceOfTriangle_[t] >= 0) continue;
    const std::array<glm::dvec3, 3> c = {corner(uint32_t(t), 0), corner(uint32_t(t), 1),
                                         corner(uint32_t(t), 2)};
    const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    const double longest =
        std::max({glm::length(c[1] - c[0]), glm::length(c[2] - c[1]), glm::length(c[0] - c[2])});
    // A sliver thinner than the margin could not hold a crossing that far inside its edges anyway.
    if (!(glm::length(n) > margin * longest)) continue;
    pieceOfTriangle_[t] = int32_t(pieces_.size());
    pieces_.push_back(convexPiece(c, glm::normalize(n)));
  }
}

bool OccluderPieces::blocks(int32_t piece, std::span<const glm::dvec3> from, std::span<const glm::dvec3> to,
                            double shortfall) const {
  if (piece < 0 || size_t(piece) >= pieces_.size() || from.empty() || to.empty() || from.size() > 4 ||
      to.size() > 4)
    return false;
  const Piece& p = pieces_[size_t(piece)];
  std::array<double, 4> sideFrom{}, sideTo{};
  const double sign = glm::dot(p.normal, from[0]) - p.offset > 0.0 ? 1.0 : -1.0;
  for (size_t i = 0; i < from.size(); ++i) {
    sideFrom[i] = glm::dot(p.normal, from[i]) - p.offset;
    if (!(sign * sideFrom[i] > margin_)) return false;
  }
  for (size_t j = 0; j < to.size(); ++j) {
    sideTo[j] = glm::dot(p.normal, to[j]) - p.offset;
    if (!(-sign * sideTo[j] > margin_ + shortfall)) return false;
  }
  // The shaft (the hull of both polygons) meets the plane in the hull of its corner-to-corner segments'
  // crossings: all of them inside the piece puts the whole section inside, the piece being convex.
  for (size_t i = 0; i < from.size(); ++i)
    for (size_t j = 0; j < to.size(); ++j) {
      const glm::dvec3 x = from[i] + (sideFrom[i] / (sideFrom[i] - sideTo[j])) * (to[j] - from[i]);
      for (int k = 0; k < p.edges; ++k)
        if (!(glm::dot(p.inward[k], x) - p.edgeOffset[k] >= margin_)) return false;
    }
  return true;
}

}  // namespace cpgi
