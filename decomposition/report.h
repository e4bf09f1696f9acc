// cells.json: the graph and the numbers behind it (design.md §3), for people and for the checks.
#pragma once

#include <string>

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

/// The portal graph's parts in one line for a user: "graph: 3 parts — the main one of 12 cells joined by
/// portals, 2 closed rooms with no opening (s1-6m2, s2-21m2: lit by their own lamps alone)". A closed
/// room is a part of its own; a part apart is neither the main one nor a closed room (a fault).
std::string graphSummary(const Decomposition& d);

}  // namespace cpgi::decomp
