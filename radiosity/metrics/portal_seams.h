// The seam on a portal's plane (design.md §5, "Seams"; issue 47): texels on the two sides of a portal are
// solved in different cells while the floor runs through, and a cells bake can leave a bright line, a dark
// line or a step there. Along every portal, the mean of the floor texels in a band one texel wide on each
// side must differ by no more than the texel noise. Plain maths over spans of texels (their sample points,
// normals, values, weights), as the other metrics: the caller brings the atlas's positions.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace cpgi {

/// A portal as the seam measure sees it: a planar quad, corners in boundary order (world space, metres).
struct SeamPortal {
  std::string name;
  std::array<glm::vec3, 4> corners{};
};

/// The texels the seams are measured on, indexed alike (an atlas's row-major texels).
struct SeamTexels {
  std::span<const glm::vec3> position;  ///< each texel's sample point, metres
  std::span<const glm::vec3> normal;    ///< unit
  std::span<const glm::vec3> value;     ///< radiosity (RGB)
  std::span<const float> area;          ///< m², 0 for texels that do not count (padding, lamps, untraced)
};

/// One portal's seam: the floor band on each side. "Floor" is every texel facing up (within 8°) at the
/// portal's lowest edge's height (within 2 cm): a room's floor under a door in a thin wall, a door's
/// threshold in a thick one, a window's sill. The band on a side is the row of those texels nearest to the
/// portal's plane on that side (sample points within two texels, √area, of the plane and within 0.4 texel
/// of the nearest one), within the portal's width.
struct PortalSeam {
  std::string name;
  size_t texelsA = 0, texelsB = 0;  ///< in the band on the side of corners' normal's tail (A) and head (B)
  double meanA = 0.0, meanB = 0.0;  ///< area-weighted means of (R + G + B) / 3, W/m²
  /// (meanB − meanA) / ((meanA + meanB) / 2): the step across the plane, relative. NaN when not measured.
  double step = 0.0;
  /// The texel noise along the bands, relative to the same mean: from the differences of neighbouring
  /// texels along each band, σ² ≈ Σ (v_{k+1} − v_k)² / (2 (n − 1)), which a smooth change of the light along
  /// the portal leaves out; the two sides' σ² averaged. NaN when not measured.
  double noise = 0.0;
  /// Both bands hold at least two texels and some light (a door whose floor the atlas samples); false for
  /// a portal with nothing flat at its lowest edge (a window in a zero-thickness wall, a hatch).
  bool measured = false;
};

/// The seam of every portal over the texels `t` (sizes must agree; std::invalid_argument otherwise), `up`
/// the scene's up axis. Portals whose corners do not span a plane are returned unmeasured.
std::vector<PortalSeam> measurePortalSeams(const SeamTexels& t, const std::vector<SeamPortal>& portals,
                                           glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f));

}  // namespace cpgi
