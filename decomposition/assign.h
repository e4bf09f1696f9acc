// Stage 7: every triangle goes to the cell it faces (Haumont et al. 2003, §3.5). Triangles whose parts
// face different cells across a portal (a floor running through a doorway) are split on the portal's
// plane first.
#pragma once

#include <cstdint>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "decomposition/classify.h"

namespace cpgi::decomp {

struct AssignParams {
  /// Samples per triangle edge are ceil(longest edge / (sampleSpacing · voxel)), at most maxSamplesPerEdge
  /// (the triangle is cut into that many² similar pieces and each piece's centroid votes).
  double sampleSpacing = 2.0;
  int maxSamplesPerEdge = 8;
  /// How often a piece may be split again (a triangle crossing several portal planes).
  int maxSplitDepth = 4;
  /// How far behind a face that sees no cell to look for one, metres (the thickest wall expected).
  double backSearch = 0.6;
};

struct Assignment {
  Scene scene;                        ///< the input with split triangles replaced by their pieces
  std::vector<int32_t> cellOfTriangle;  ///< per output triangle
  std::vector<uint32_t> sourceTriangle; ///< per output triangle: the input triangle it came from
  size_t splitTriangles = 0;          ///< input triangles that were split
  size_t fallbackTriangles = 0;       ///< triangles that faced no cell from either side (nearest cell used)
  /// Area of surface with one cell in front and another within one voxel behind: walls thinner than a
  /// voxel between cells (light may leak through them in a bake; the cells are still right).
  double thinWallArea = 0.0;
};

/// For each triangle, samples step along its normal (1 to 3 voxels) to the first labelled voxel; the
/// back side is tried when the front finds none (wrong winding, outside walls: up to backSearch deep),
/// and the nearest labelled voxel when neither does. A sample beyond the grid is in `outsideCell` (the
/// grid stops in open space, voxelize.h; -1 when the outside is no cell). Run after fitPortals, with its
/// relabelled cells.
Assignment assignTriangles(const Scene& scene, const GridFrame& frame, const std::vector<int32_t>& cell,
                           const std::vector<PortalQuad>& portals, int outsideCell, const AssignParams& params,
                           Context& ctx);

}  // namespace cpgi::decomp
