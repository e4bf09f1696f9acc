// Stage 6c: one portal per opening (issue 46). Fitting and the leak pass leave an opening between two
// cells in pieces: a doorway whose interface the watershed broke at a lintel's step, the fringe rounds'
// strips along a jamb, a window cut by a mullion one voxel wide. Pieces of the same two cells that lie in
// one plane (within a voxel or two) and touch or nearly touch in it become one quad: the rectangle round
// them in the largest one's frame, when it is not much larger than the pieces (two doors of one wall with
// the wall between them stay two). A pair whose merged quads would leave a voxel face between its cells
// uncovered is merged again one piece at a time, keeping only the merges that uncover none.
#pragma once

#include "core/context.h"
#include "decomposition/portals.h"

namespace cpgi::decomp {

struct PortalMergeParams {
  /// Pieces whose normals differ by more than this, degrees, are not merged. 0 disables the stage.
  float maxAngleDegrees = 20.0f;
  /// The most a piece's corners may lie off the other's plane, and the widest gap between the two in
  /// that plane, voxels.
  float maxGapVoxels = 2.0f;
  /// The merged rectangle's area at most this many times the pieces' own: a doorway in two pieces fills
  /// its rectangle; two doors with a wall between them do not.
  float maxFill = 1.5f;
};

struct MergedPortals {
  int merged = 0;     ///< pieces folded into another
  int pairsKept = 0;  ///< pairs merged again piece by piece: merging all uncovered a face
};

/// Merges the pieces of `set`'s portals between the same two cells as above, in place (each merged
/// portal keeps the largest piece's plane and cells, the widest constriction, the sum of faces); its
/// leakingFaces is recounted. Run after closeLeaks.
MergedPortals mergePortalPieces(PortalSet& set, const GridFrame& frame, const PortalMergeParams& params,
                                Context& ctx);

}  // namespace cpgi::decomp
