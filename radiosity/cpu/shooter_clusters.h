// Small coplanar patches shot together (issue 46 item 3): past a few thousand shots of a daylit game map
// each shot takes a patch holding about 1/10 000 of the light, the stop needs about one shot per patch, and
// a shot's price is its receivers (a ray and a form factor per coarse texel in front of the shooter), not
// its shooter: a 10 cm trim cost what a wall did. Neighbours on one plane, together no wider than a
// shooter's visibility region, are seen from one set of eyes as a region of a large patch is.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/lightmap/atlas.h"

namespace cpgi {

struct ShooterClusterParams {
  /// A cluster's patches fit in a box whose half-diagonal is at most this (m): half a visibility region
  /// (ShotSettings::regionSize), whose one set of eyes serves a large patch's receivers as well.
  float radius = 0.5f;
  /// Coplanar: normals within this cosine, planes within `planeGap` (m) of each other.
  float normalCosine = 0.9995f;
  float planeGap = 0.01f;
};

/// The patches' clusters: per patch, its cluster's index; per cluster, its patches (ascending). A patch
/// wider than the radius, an excluded one (non-zero in `exclude`, e.g. a cell's portal), or one without
/// area is a cluster of its own. Deterministic.
struct ShooterClusters {
  std::vector<int32_t> clusterOf;
  std::vector<std::vector<int32_t>> members;
};

ShooterClusters clusterShooters(const LightmapAtlas& atlas, const ShooterClusterParams& params,
                                std::span<const uint8_t> exclude = {});

}  // namespace cpgi
