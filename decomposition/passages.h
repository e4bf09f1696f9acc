// How narrow a level's rooms get where people walk: the free width across the floors at a person's waist,
// for the automatic voxel (decompose.h, chooseGrid). A grid sized from the bounds alone gives a large
// level a voxel of 0.6–1 m whatever its corridors are (issue 46: ctf_inyard's 3.5 m passages at 0.6 m are
// six voxels across, short of the eight a door needs to become a portal); the passages say how fine the
// grid must be, memory how fine it may be.
#pragma once

#include "core/scene.h"

namespace cpgi::decomp {

struct PassageParams {
  int samples = 512;          ///< points spread over the floors by area (floors: normal within 25° of +y)
  float height = 1.0f;        ///< metres above the floor the widths are measured at
  float minClearance = 1.8f;  ///< metres: a point whose ceiling is lower is no place a person walks
  double quantile = 0.1;      ///< the share of the floor narrower than the width returned
};

struct PassageWidths {
  /// The `quantile` of the free widths over the floors, metres: at each point the narrowest of four
  /// horizontal chords through it (along x, z and the two diagonals) that meet a wall at both ends. 0 when
  /// fewer than a tenth of the points have such a chord (an open landscape: no passage to measure).
  double narrow = 0.0;
  int measured = 0;  ///< points with a chord wall to wall
};

/// The passages of the part of `scene` inside `box` (the grid's extent): only the floors whose centre
/// lies in it, rays against every triangle that spans the ray's height.
PassageWidths measurePassages(const Scene& scene, const Bounds& box, const PassageParams& params = {});

}  // namespace cpgi::decomp
