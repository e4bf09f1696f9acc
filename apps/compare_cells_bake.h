// `cpgi compare-cells --bake`: what two decompositions of one scene change in the light. Each is baked
// with `--method cells` (radiosity/cells/cell_solver.h) on the scene's global atlas, and both are measured
// against one path-traced reference on that atlas (design.md §5).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/reference/reference_tracer.h"

namespace cpgi::cli {

/// One decomposition to bake: the scene its graph indexes (the automatic one may have split triangles on
/// portal planes) and the graph.
struct CellsToBake {
  std::string source;  ///< how the user named it (auto, a file, a folder), for the report
  Scene scene;
  CellGraph graph;
};

struct CellBakeComparison {
  AtlasParams atlas;
  /// unshotFraction is the whole scene's target, as in `bake --method cells`; the rest the bake's defaults
  /// (radiosity/bake/bake_settings.h: lamp rays kBakeLampRays)
  SolverParams solver = BakeSettings{}.solver.params;
  int maxRounds = BakeSettings{}.cells.params.maxRounds;
  PortalLight portals = BakeSettings{}.cells.params.portals;  ///< as the bake's: kBakePortalLight
  ReferenceParams reference;
};

/// Bakes `a` and `b` with the cell solver and traces the reference on their atlas; when the two scenes give
/// different atlases (triangles split by one decomposition and not the other) each bake gets its own
/// reference on its own atlas, and "same_atlas" says so. Returns the JSON of the `bake` key of
/// `compare-cells --json`: "references" (texels, seconds, spp, noise, noise_nonemissive), "a" and "b"
/// (seconds, solve_seconds, shots, rounds, unshot_fraction, rel_rmse, rel_rmse_nonemissive,
/// rel_mean_error, rel_mean_error_nonemissive, reference, reference_noise, reference_noise_nonemissive)
/// and "difference_points" (100 × (a − b) of rel_rmse and rel_rmse_nonemissive).
/// Throws InputError when a scene has no surface or a graph is unusable, and InputError(scene, ...) when a
/// bake, a reference or a figure is not finite (as bake and reference refuse to write one: no exit 0 with a
/// null in the figures); SystemError without OpenGL.
nlohmann::json compareCellBakes(const std::string& scene, const CellsToBake& a, const CellsToBake& b,
                                const CellBakeComparison& params, Context& ctx);

/// Throws InputError(scene, ...) naming the first number of `figures` (by its JSON path, e.g.
/// "a.rel_rmse_nonemissive") that is inf or NaN; nulls put there on purpose pass.
void requireFiniteFigures(const std::string& scene, const nlohmann::json& figures);

/// The same figures as lines of text for the terminal.
void printCellBakes(const nlohmann::json& bake);

}  // namespace cpgi::cli
