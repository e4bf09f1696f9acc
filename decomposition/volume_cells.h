// Cells given only as room volumes (design.md §3: `cellvolume:NAME` meshes without `cell:` or `portal:`
// nodes, as an IFC export's IfcSpace rooms come): each closed volume is a cell, the empty space between
// volumes (the depth of a doorway, a slab under a stair's hole) is shared out between the volumes it
// touches, the empty space beyond them is the outside, and the decomposition's own stages 6 and 7 then fit
// a portal wherever two of them meet (an opening) and give every triangle to the cell it faces.
#pragma once

#include <cstdint>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "decomposition/decompose.h"

namespace cpgi::decomp {

/// Labels with `label` the empty voxels (inside or outside, not void or solid) whose centres the closed
/// mesh contains (parity of crossings along +x), leaving voxels already labelled (≥ 0) as they are: where
/// two volumes overlap, the first keeps the overlap.
void labelVolumeVoxels(const std::vector<Triangle>& mesh, const GridFrame& frame,
                       const std::vector<Space>& space, int32_t label, std::vector<int32_t>& out);

struct VolumeCellsParams {
  /// How far from its volume a room may claim empty space no volume holds, metres: at least the thickest
  /// wall or slab an opening goes through, so that two volumes on either side of a door meet in its
  /// middle. Unclaimed space further out that reaches the scene's bounds is the outside; between two
  /// volumes the space is shared by distance, whatever this reach.
  double reach = 0.6;
};

/// The decomposition given by `volumes`' cells (each with a non-empty `volume`; their triangles and the
/// graph's portals are ignored): cells keep their names and order, with "outside" added last when open
/// doors or windows join the rooms to it (a cell named "outside" with a volume of its own takes it
/// instead). Triangles are assigned as by decompose (split on portal planes where the pieces face
/// different cells, else by the majority of their samples), so the result is a full decomposition of
/// `scene`, ready to bake cell by cell.
/// @throws InputError as decompose does, and when no volume holds an empty voxel at the chosen voxel size.
Decomposition decomposeFromVolumes(const Scene& scene, const CellGraph& volumes,
                                   const DecomposeParams& params, const VolumeCellsParams& volumeParams,
                                   Context& ctx);

/// The automatic cells of `d` named after the room volumes of `rooms` (cellvolume: meshes, as an IFC
/// export's IfcSpace rooms come) that cover them: a cell takes the name of the volume that holds the most
/// of its empty voxels when that is at least `leastShare` of them; a second cell under the same volume is
/// NAME-2, and a name another cell holds already is never taken twice. Cells no volume covers keep their
/// names (roomNames: storey and size); the outside keeps "outside". The portals are renamed after their
/// cells. Returns how many cells were renamed.
int nameCellsByVolumes(Decomposition& d, const CellGraph& rooms, double leastShare = 0.5);

}  // namespace cpgi::decomp
