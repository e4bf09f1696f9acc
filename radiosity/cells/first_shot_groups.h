// The lamps' first shot split into emitter groups (issue 16): each group's emitters shoot over the whole
// scene on their own, and the groups' irradiance is summed in a fixed order. A group is the emitters of one
// cell (or the scene's punctual lights), a fixed function of the scene and the cells, never of how many
// processes or machines shoot them: the single-process bake (cell_first_shot.h) and the cell jobs
// (cell_jobs.h, one job per group or several) shoot the same groups and add the same floats in the same
// order, so both give the same bits.
//
// Shot alone, a group differs from the emitters shot in one solve only where the solver looks at the whole
// solve: the eyes drawn per shot follow the shot's index in its solve, and a shot counts as strong against
// the power emitted in its solve (the fraction is scaled below so that a group's shots are strong where
// they were in the one solve).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/solve.h"

namespace cpgi {

/// The emitters of one group.
struct FirstShotGroup {
  int cell = -1;             ///< the cell of its emitters; -1: the scene's punctual lights (shot on the CPU)
  std::vector<int> patches;  ///< emitting patches of the global atlas (ascending); none for the lights
};

/// What one group's shot left over the whole scene: the irradiance of the global texels it reached.
struct FirstShotContribution {
  double emitted = 0.0;             ///< W (R + G + B) the group emitted, as the solver counts it
  int shots = 0;                    ///< GPU shots (one per emitting patch)
  double seconds = 0.0;             ///< wall time of the group's solve
  std::vector<uint32_t> texels;     ///< global texels with irradiance (ascending)
  std::vector<glm::vec3> incident;  ///< W/m², one per entry of `texels`
};

/// The global atlas with black receivers, and emitters only where `cellOfTriangle` puts them in a cell
/// (cells left out of an on-demand bake are dark): what every group shoots into.
LightmapAtlas firstShotReceivers(const LightmapAtlas& global, const std::vector<int>& cellOfTriangle);

/// The groups, in their fixed order: the punctual lights first (when the scene has any), then each cell
/// with an emitting patch, by cell index. A patch whose emitting texels lie in several cells belongs to
/// the lowest of them.
std::vector<FirstShotGroup> firstShotGroups(const Scene& scene, const LightmapAtlas& receivers,
                                            const std::vector<int>& cellOfTriangle);

/// Shoots group `g` of `groups` over the whole scene (`receivers` from firstShotReceivers) on the
/// context current on this thread.
FirstShotContribution shootFirstShotGroup(const Scene& scene, const LightmapAtlas& receivers,
                                          const std::vector<FirstShotGroup>& groups, size_t g,
                                          const SolverParams& settings, ShotEngine& engine, Context& ctx);

/// The groups' irradiance per global texel (`texels` of them) and their emitted power, added group after
/// group in the order given.
struct FirstShotSum {
  double emitted = 0.0;
  std::vector<glm::vec3> incident;
};
FirstShotSum sumFirstShot(const std::vector<FirstShotContribution>& parts, size_t texels);

}  // namespace cpgi
