// cells.json: the graph and the numbers behind it (design.md §3), for people and for the checks.
#pragma once

#include <nlohmann/json.hpp>

#include "core/context.h"
#include "decomposition/decompose.h"

namespace cpgi::decomp {

/// Keys: scene, parameters (every value used, the voxel size with how it was chosen), grid (dims, voxel
/// counts by class), cells [{name, volume_m3, bounds_m, peak_m, voxels, triangles}], portals [{name,
/// cells, corners, centre, normal, area_m2, half_width_m}], counts, timings_s {stage: seconds, with
/// "stage.part" entries for parts of a stage; total sums the stages},
/// warnings, and the checks (leaking_faces, thin_wall_area_m2, split_triangles).
nlohmann::json decompositionReport(const Decomposition& d, const DecomposeParams& params, const Context& ctx);

}  // namespace cpgi::decomp
