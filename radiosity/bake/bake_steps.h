// The steps of bake() (bake.h), shared by bake.cpp, its report (bake_report.cpp) and the cell jobs
// (bake_jobs.cpp), which run the same steps a job at a time. Not for callers outside radiosity/bake/.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/quads.h"
#include "core/scene.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_limits.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/auto_density.h"
#include "radiosity/solve/two_level_solve.h"

namespace cpgi::bake_steps {

using Clock = std::chrono::steady_clock;

/// When Limits::timeLimit ends a bake started at `start` (no limit: time_point::max()).
Clock::time_point deadlineOf(const BakeSettings& s, Clock::time_point start);

/// `s` with Limits::maxMemory (0: 75 % of this machine's) in the atlas's and the decomposition's limits.
BakeSettings resolved(const BakeSettings& s);

/// On-demand bakes (radiosity/cells/cell_selection.h): the cells to bake; inactive for a whole bake.
struct OnDemand {
  bool active = false;
  CellSelection selection;
  BoundaryMode mode = BoundaryMode::Coarse;
  int aroundCell = -1;
};
OnDemand resolveOnDemand(const BakeSettings& s, const Scene& scene, const CellGraph& graph);

/// A bake's scene and what its steps build.
struct BakeInput {
  const Scene* scene = nullptr;
  const CellGraph* cells = nullptr;  ///< bake()'s `cells`
  OnDemand onDemand;
  QuadSet quads;
  LightmapAtlas atlas;
  std::optional<AutoDensityData> autoDensity;  ///< with --density auto
  /// With --density auto: per scene triangle, the texels per metre of the output's atlas and the cells'.
  std::vector<float> triangleDensity;
  /// The largest atlas laid out (width × height): the output's, or one a time limit had laid out again
  /// coarser (bake_steps.cpp, layOutWithin), whose arrays were made all the same.
  size_t laidOutTexels = 0;
  /// Read by this bake (bake(settings)): its time limit counts the loading, so the least it writes is
  /// checked against the time the loading left (requireTimeForMinimum).
  bool loadedHere = false;
};

/// When the atlas's steps stop (none: no limit).
struct AtlasLimits {
  Clock::time_point pilot = Clock::time_point::max();  ///< the density pilot shoots no more after it
  Clock::time_point layout =
      Clock::time_point::max();                      ///< a large layout still going is laid out again coarse
  Clock::time_point end = Clock::time_point::max();  ///< the bake's end (--time-limit)
  /// The seconds the required outputs of an atlas of so many texels (width × height) take; a coarse
  /// re-layout is made coarser until they fit before `end`. Empty: a sixteenth of the texels, whatever.
  std::function<double(size_t)> outputsSeconds;
};

/// The atlas; with --density auto and no densities yet, after a pilot shot of the lamps on `pilot` that
/// shoots no more after limits.pilot. A large layout still going at limits.layout is laid out again at a
/// sixteenth of the texels or fewer (limits.outputsSeconds), with a warning.
void buildBakeAtlas(const BakeSettings& s, BakeInput& in, ShotEngine* pilot, Context& ctx,
                    const AtlasLimits& limits = {});
/// The bytes the solve takes: the atlas's texels and the item buffers of every visibility region.
double solveBytes(const BakeSettings& s, const LightmapAtlas& atlas);
void requireSolveMemory(const BakeSettings& s, const LightmapAtlas& atlas);
/// Refuses a closed scene of albedo near 1 that the solve would shoot for hours (Limits::refuseEndless).
void requireConvergence(const BakeSettings& s, const Scene& scene, const LightmapAtlas& atlas);
/// The cells' parameters of a bake, its cell jobs and their gather alike.
CellSolveParams cellSolveParams(const BakeSettings& s, const BakeInput& in);
/// The solve density: 0 for one level (bake.cpp).
float chosenSolveDensity(const BakeSettings& s, const LightmapAtlas& atlas);
/// The size line of BakeRun::sized, with the bake's memory at its peak (`bytes`, bakeMemory).
std::string bakeSizeLine(const BakeSettings& s, const BakeInput& in, double bytes);

/// Steps 2–4 of bake() (`in` with its scene and cells set); with `gatherPlan`, the solve is the gather of
/// that cell-job plan's rounds (the plan's densities are read first).
BakeResult bakeLoaded(const BakeSettings& s, BakeInput& in, const BakeRun& run, Context& ctx,
                      const std::filesystem::path* gatherPlan = nullptr);

/// The figures report.json takes from the steps after the solve.
struct BakeFigures {
  std::vector<std::string> views;
  std::vector<std::string> skippedViews;  ///< cameras whose views the time limit left out
  int viewWidth = 0;                      ///< the views' width in pixels (a time limit can lower it)
  std::vector<std::string> cellNames;     ///< of lightmap.exr's "cell" channel
  glm::dvec3 ambient{0.0};                ///< mean ambient irradiance (W/m²)
  std::vector<double> ambientShares;      ///< per cell of cellNames (and one for no cell), ambientShares
  std::vector<double> ambientEscape;      ///< per entry of ambientShares, the share leaving the scene
  double seconds = 0.0;
  OutputEstimate outputs;  ///< the outputs' share kept back from the time limit
  nlohmann::json engine;   ///< report.json's "engine_lightmap" (LightmapOutputs::engine); null: none written
  /// Outputs the time limit stopped during their gather, so not written: "probes", "directional"
  std::vector<std::string> skippedOutputs;
  /// Optional outputs left out before they started, their estimate not fitting in the time left
  /// (planOutputs): "views", "probes", "directional"
  std::vector<std::string> outputsLeftOut;
};
/// report.json of a bake (bake_report.cpp).
nlohmann::json bakeReport(const BakeSettings& s, const BakeInput& in, const SolveResult& r,
                          const std::optional<TwoLevelData>& levels, const EglContext* gl,
                          const std::string& backend, const BakeFigures& f, const Context& ctx);

}  // namespace cpgi::bake_steps
