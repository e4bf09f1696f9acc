// Scenes often model a wall as a grid of equal tiles (seed3's room B: ~1100 quads of 0.28 m). One chart
// per tile makes one shooter per tile, and progressive refinement then spends most of its shots on tiles
// that each hold a sliver of the light. Coplanar quads of one material that tile a rectangle edge to
// edge are merged into one chart here: the same texels at the same points (each quad keeps its own
// N×N or its density's texels), but one shooter with a residual pyramid across the whole rectangle and
// no seam between tiles.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/quads.h"
#include "core/scene.h"

namespace cpgi {

struct QuadGrid {
  glm::ivec2 size{1};           ///< quads along the grid's u and v edges
  std::vector<uint32_t> quads;  ///< row-major: v rows of u quads
  /// The merged rectangle in the Quad convention: corners[1] − corners[0] = size.x × a tile's u edge,
  /// corners[3] − corners[0] = size.y × its v edge, (u × v) along the normal.
  std::array<glm::vec3, 4> corners{};
};

/// Greedy maximal rectangles of equal quads (same material, plane and edges, neighbours' corners within
/// 0.1 mm) among the quads with `usable[q]` set, at most `maxQuads` along either edge. Every usable quad
/// lands in exactly one grid (a lone quad is a 1×1 grid), in its own orientation when alone. Deterministic:
/// grids come in the order of their first quad. With `group` (one entry per quad), only quads of the same
/// group merge: quads solved at another texel density (AtlasParams::triangleDensity) must not take a
/// whole grid with them.
std::vector<QuadGrid> findQuadGrids(const QuadSet& quads, const std::vector<char>& usable, const Scene& scene,
                                    int maxQuads, const std::vector<uint32_t>* group = nullptr);

}  // namespace cpgi
