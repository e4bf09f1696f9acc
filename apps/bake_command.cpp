// `cpgi bake SCENE -o DIR [--method global|cells] [--cells FILE|auto] [--portals diffuse|directional|binned]
// [--max-rounds N] [--only-cells A,B | --around X,Y,Z [--depth K]] [--boundary coarse|dark] [--jobs N]
// [atlas options] [solver options] [decomposition options for --cells auto] [--no-ambient]
// [--allow-dark] [--view-size WxH] [loading options]`: GPU progressive radiosity over a lightmap atlas
// (design.md §1, §3), over the whole scene at once or cell by cell through portals
// (radiosity/cells/cell_solver.h); both write the same atlas layout, plus an ambient term for the power the
// stop left unshot (radiosity/solve/ambient.h). Writes the lightmap files
// (radiosity/lightmap/lightmap_output.h: lightmap.exr with "area", "emissive" and "cell", lightmap.png,
// baked.glb with the cells, view-*.png/.exr), report.json and report.html (apps/report_page.h), all or
// nothing. The options are apps/options.h's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "apps/cell_job_serve.h"
#include "apps/cell_source.h"
#include "apps/commands.h"
#include "apps/lightmap_report.h"
#include "apps/options.h"
#include "apps/report_page.h"
#include "core/error.h"
#include "core/memory_limit.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/quads.h"
#include "core/scene_io.h"
#include "decomposition/decompose.h"
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/cells/cell_selection.h"
#include "radiosity/cells/cell_solver.h"
#include "radiosity/cpu/ray_shot_engine.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/bounce_limit.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/lightmap/finite_result.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/solve/ambient.h"
#include "radiosity/solve/auto_density.h"
#include "radiosity/solve/two_level_solve.h"

namespace cpgi::cli {
namespace {

struct BakeOptions {
  std::string scene;
  std::string output;
  std::string method = "global";
  std::string cells = "none";  ///< with --method cells: a glTF with cell:/portal: nodes, or "auto"
  std::string onlyCells;       ///< on demand: "A,B"
  std::string around;          ///< on demand: "X,Y,Z"
  int depth = 0;               ///< with `around`: portals away from the point's cell
  BoundaryMode boundary = BoundaryMode::Coarse;
  AtlasParams atlas;
  SolverParams solver = [] {
    SolverParams p;
    p.lampRays = kBakeLampRays;
    return p;
  }();
  /// portals (kBakePortalLight unless --portals), maxRounds, jobs; its atlas and solver are the two above
  CellSolveParams cellParams = [] {
    CellSolveParams p;
    p.portals = kBakePortalLight;
    return p;
  }();
  decomp::DecomposeParams decompose;           ///< for --cells auto
  bool noAmbient = false;                      ///< leave out the ambient term (radiosity/solve/ambient.h)
  double ambientShare = kDefaultAmbientShare;  ///< the stop per cell (ambientShares; cells: round_stop.h)
  LoadOptions load;                            ///< --strict, --allow-outside-files, --emit, --albedo
  bool allowDark = false;                      ///< go on when nothing lights the scene
  SkyRequest sky;                              ///< --sky, --sun, --ground (core/sky.h); none by default
  ViewParams views;                            ///< --view-size; each picture exposed for what its camera sees
  bool quiet = false;
  bool maxShotsGiven = false;  ///< --max-shots on the command line (else the solver's default bound)
  // Cell jobs (radiosity/cells/cell_jobs.h, docs/cell-jobs.md): --plan DIR prepares them instead of
  // solving; `cpgi cell-job` runs a round of some cells (jobRound, jobCells) or the gather through here.
  std::string plan;
  int jobRound = 0;
  std::string jobCells;
  std::string jobFirstShot;  ///< emitter groups to shoot, "0,3,4" or "all"
  bool jobFirstShotSum = false;
  bool jobServe = false;  ///< round jobs from stdin until it ends (apps/cell_job_serve.h)
  bool gather = false;
  double timeLimit = 0.0;  ///< --time-limit: seconds of wall clock from the start, 0 = none
  /// --solve-density: the indirect light solved on an atlas of this many texels per metre, the lamps'
  /// light on the output's (radiosity/solve/two_level_solve.h); 0: everything on the output's atlas;
  /// kAutoSolveDensity: chosen by chosenSolveDensity.
  float solveDensity = kAutoSolveDensity;
  /// --lamp-coarsening (with --solve-density): the lamps' shot first on an atlas this many times coarser,
  /// then at the output's texels only where its light varies (radiosity/solve/refined_lamp_shot.h).
  float lampCoarsening = RefinedLampParams{}.coarsening;
  /// --density auto (the default; a number or --texels-per-quad fixes the density): the output's texels
  /// per metre chosen per surface (radiosity/solve/auto_density.h).
  bool densityAuto = true;
  AutoDensityParams autoDensity;
  /// --indirect-solver: how a two-level solve shoots its interreflection: "gpu" (item buffers on the GL
  /// device), "rays" (Embree on the CPU, radiosity/cpu/ray_shot_engine.h) or "auto" (rays where the GL device
  /// is a software rasterizer, usesRays).
  std::string indirectSolver = "auto";
};

// Whether --indirect-solver asks for rays on this GL device: auto picks them where the device rasterizes
// in software (EglContext::softwareRasterizer), drawing item buffers on the same CPU cores the rays use.
bool usesRays(const BakeOptions& o, const EglContext& gl) {
  if (o.indirectSolver != "auto") return o.indirectSolver == "rays";
  return gl.softwareRasterizer();
}

// On-demand bakes (radiosity/cells/cell_selection.h): the cells to bake, or nothing for a whole bake.
struct OnDemand {
  bool active = false;
  CellSelection selection;
  BoundaryMode mode = BoundaryMode::Coarse;
  int aroundCell = -1;
};

OnDemand resolveOnDemand(const BakeOptions& o, const Scene& scene, const CellGraph& graph) {
  OnDemand d;
  if (o.onlyCells.empty() && o.around.empty()) return d;
  const std::string option = o.onlyCells.empty() ? "--around" : "--only-cells";
  if (o.method != "cells") throw InputError(option, "needs --method cells");
  d.active = true;
  d.mode = o.boundary;
  std::vector<int> baked;
  if (!o.onlyCells.empty()) {
    baked = cellsByName(graph, o.onlyCells, "--only-cells");
  } else {
    const glm::vec3 p = parsePoint(o.around, "--around");
    d.aroundCell = cellContaining(scene, graph, p);
    if (d.aroundCell < 0) throw InputError("--around", "the point " + o.around + " is in no cell");
    baked = cellsWithin(graph, d.aroundCell, o.depth);
  }
  d.selection = selectCells(graph, baked);
  return d;
}

// report.json's "on_demand": which cells were baked and what the others did (null for a whole bake).
nlohmann::json onDemandReport(const BakeOptions& o, const OnDemand& d, const CellGraph& graph,
                              const LightmapAtlas& atlas) {
  if (!d.active) return nullptr;
  auto names = [&](const std::vector<int>& cells) {
    nlohmann::json out = nlohmann::json::array();
    for (int c : cells) out.push_back(graph.cells[c].name);
    return out;
  };
  // Texels of the atlas that belong to baked cells: the only ones with light.
  std::vector<char> baked(graph.cells.size(), 0);
  for (int c : d.selection.baked) baked[c] = 1;
  size_t texels = 0;
  for (int c : cellOfTexels(atlas, graph, atlas.triangleUV.size())) texels += c >= 0 && baked[c];
  nlohmann::json j = {{"baked", names(d.selection.baked)},
                      {"boundary", names(d.selection.boundary)},
                      {"dark", names(d.selection.dark)},
                      {"boundary_mode", boundaryModeName(d.mode)},
                      {"baked_texels", texels}};
  j["boundary_role"] =
      d.mode == BoundaryMode::Coarse
          ? "solved on a coarse atlas, lighting the baked cells through their portals; not written"
          : "dark";
  if (!o.onlyCells.empty()) j["only_cells"] = o.onlyCells;
  if (d.aroundCell >= 0) {
    j["around"] = o.around;
    j["around_cell"] = graph.cells[d.aroundCell].name;
    j["depth"] = o.depth;
  }
  return j;
}

// Step 1: the scene, its cells (with --method cells), the on-demand choice and the atlas.
struct BakeInput {
  LoadedScene loaded;
  CellGraph graph;  ///< the cells baked with (--method cells), indexing loaded.scene
  OnDemand onDemand;
  QuadSet quads;
  LightmapAtlas atlas;
  std::optional<AutoDensityData> autoDensity;  ///< with --density auto
  /// With --density auto: per scene triangle, the texels per metre of the output's atlas and the cells'.
  std::vector<float> triangleDensity;
};

BakeInput loadBakeInput(const BakeOptions& o, Context& ctx) {
  BakeInput in;
  {
    auto t = ctx.time("load");
    in.loaded = loadScene(o.scene, o.load);
  }
  applySky(o.sky, in.loaded.scene);
  requireLight(in.loaded, o.scene, o.allowDark);
  for (const std::string& w : in.loaded.warnings) ctx.warn(w);
  if (o.method == "cells") {
    decomp::DecomposeParams decompose = o.decompose;
    decompose.memoryLimit = o.atlas.memoryLimit;  // one --max-memory for the whole bake
    in.graph = resolveCells(o.cells, o.scene, in.loaded, decompose, o.load, ctx);
  }
  in.onDemand = resolveOnDemand(o, in.loaded.scene, in.graph);
  return in;
}

// `gl`: with --density auto, for the pilot's shot of the lamps (unused, and may be null, when
// in.triangleDensity holds a plan's densities already). The pilot shoots no more after `deadline`
// (--time-limit counts it): its light so far lays the atlas out.
void buildBakeAtlas(
    const BakeOptions& o, BakeInput& in, const EglContext* gl, Context& ctx,
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max()) {
  {
    auto t = ctx.time("atlas");
    in.quads = findQuads(in.loaded.scene);
  }
  if (o.densityAuto && in.triangleDensity.empty()) {
    if (!gl) throw std::logic_error("buildBakeAtlas: --density auto's pilot needs a GL context");
    auto t = ctx.time("auto density");
    AutoDensityData data;
    GlShotEngine pilot(*gl);
    in.triangleDensity = chooseAutoDensity(in.loaded.scene, in.quads, o.atlas, o.autoDensity, o.solver, pilot,
                                           ctx, SolveControls{.deadline = deadline}, &data);
    in.autoDensity = data;
  }
  AtlasParams params = o.atlas;
  params.triangleDensity = in.triangleDensity;
  {
    auto t = ctx.time("atlas");
    TexelBudget budget;
    in.atlas = fitTexelBudget(in.loaded.scene, in.quads, params, o.densityAuto ? o.autoDensity.maxTexels : 0,
                              ctx, &budget);
    if (!budget.note.empty()) ctx.warn(budget.note), in.triangleDensity = params.triangleDensity;
  }
  if (in.atlas.patches.empty()) throw InputError(o.scene, "no surface to bake");
  if (!in.loaded.scene.hasLight()) ctx.warn(o.scene + ": nothing emits light; the lightmap is black");
}

// The atlas was checked alone when it was built; the solve adds its item buffers: per visibility region
// (up to the larger of --regions and --strong-regions, squared) an item and a depth layer of the buffer's
// pixels (8 bytes a pixel), and half as much again for what the GL driver keeps beside them.
double solveRegions(const BakeOptions& o) {
  return std::pow(std::max(o.solver.maxRegions, o.solver.strongShotRegions), 2);
}

double solveBytes(const BakeOptions& o, const LightmapAtlas& atlas) {
  const double pixels = double(o.solver.itemBuffer) * double(o.solver.itemBuffer) * solveRegions(o);
  return double(atlas.texelCount()) * kBakeBytesPerTexel + pixels * 12.0;
}

void requireSolveMemory(const BakeOptions& o, const LightmapAtlas& atlas) {
  const double regions = solveRegions(o);
  requireMemory(solveBytes(o, atlas), o.atlas.memoryLimit, "item buffer",
                "the solve (" + std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
                    " atlas texels, item buffers of " + std::to_string(o.solver.itemBuffer) + "^2 pixels x " +
                    std::to_string(int(regions)) + " regions)",
                "lower `item buffer` or raise `maximum memory`");
}

// In a closed scene of mean albedo ρ, light bounces about ln(unshot) / ln(ρ) times before the unshot
// share falls to --unshot, each bounce a round of shots over the lit patches: near ρ = 1 that is thousands
// of rounds (at 1, never), which the default --max-shots of 100,000 would let run for hours. Refused
// up front unless the user bounded the solve with --max-shots (an open scene lets light escape, so an
// albedo of 1 there would converge: the message says how to go on). A dark scene has nothing to shoot.
void requireConvergence(const BakeOptions& o, const Scene& scene, const LightmapAtlas& atlas) {
  if (o.maxShotsGiven || o.timeLimit > 0.0 || !scene.hasLight()) return;
  const BounceEstimate e = estimateBounces(atlas, o.solver.unshotFraction);
  if (!e.tooMany()) return;
  std::ostringstream s;
  s << e.describe() << " before `unshot fraction` " << o.solver.unshotFraction
    << " is unshot; lower the albedo, raise `unshot fraction`, or bound the solve with `maximum shots` N or "
       "`time limit` SECONDS";
  throw InputError(o.scene, s.str());
}

// The cells' parameters of a bake, its cell jobs and their gather alike: the same stop per cell and solver.
CellSolveParams cellSolveParams(const BakeOptions& o, const BakeInput& in) {
  CellSolveParams params = o.cellParams;
  params.maxAmbientShare = o.ambientShare;
  params.solver = o.solver;
  params.atlas = o.atlas;
  params.atlas.triangleDensity = in.triangleDensity;
  return params;
}

// With --density auto, a cell job's texel densities are those its plan recorded: every job lays its
// atlases out alike, and a pilot of its own could choose otherwise (another machine's GPU).
void usePlannedDensities(const BakeOptions& o, BakeInput& in) {
  if (!o.densityAuto) return;
  in.triangleDensity = readCellJobPlan(o.plan).triangleDensity;
  if (in.triangleDensity.size() != in.loaded.scene.triangles.size())
    throw InputError((std::filesystem::path(o.plan) / "plan.json").string(),
                     "holds no texel density per triangle of " + o.scene + "; make the plan again");
}

// --solve-density auto: one level up to this many output texels. A large atlas is where two levels pay
// (fewer receiver texels and half the item buffer per shot of the interreflection): the furnished
// house's 282 000 texels baked in 37 min in one level and in 11–12 min in two at 5 texels a metre
// (bench/RESULTS.md, "The furnished house"); seed1–3 at the default density, under this, stay as they
// were.
constexpr size_t kAutoTwoLevelTexels = 100'000;

// The solve density of a bake: the option's, or with auto half the output's density (at most 5 texels
// a metre: RESULTS.md, "Two levels") once the output has more than kAutoTwoLevelTexels texels. 0: one
// level. A cells bake solves in two levels only when asked (a value): auto keeps it in one, as its cell
// jobs are (their plan has one atlas).
float chosenSolveDensity(const BakeOptions& o, const LightmapAtlas& atlas) {
  if (o.method == "cells") return o.solveDensity > 0.0f ? o.solveDensity : 0.0f;
  if (o.solveDensity != kAutoSolveDensity) return o.solveDensity;
  constexpr float kAutoMost = 5.0f;
  // --density auto: the output is fine only where the lamps' light needs it; the bounced light never does.
  if (o.densityAuto) return kAutoMost;
  if (atlas.validTexels() <= kAutoTwoLevelTexels) return 0.0f;
  return o.atlas.texelsPerQuad > 0 ? kAutoMost : std::min(kAutoMost, o.atlas.density / 2.0f);
}

// Where the light leaving each cell's surfaces lands, or leaves the scene, for the ambient term and the
// stop per cell (radiosity/solve/ambient_transfer.h): the portals' areas alone kept the outside's light in
// it. Empty (the portals' areas) with --no-ambient.
AmbientTransfer bakeAmbientTransfer(const BakeOptions& o, const BakeInput& in, const CellGraph& texelGraph,
                                    const ExrChannel& texelCells, Context& ctx) {
  if (o.noAmbient) return {};
  auto t = ctx.time("ambient transfer");
  const RayScene rays(in.loaded.scene);
  return measureAmbientTransfer(in.atlas, rays, texelCells.values, texelGraph.cells.size());
}

// Per entry of the transfer, the share of the light leaving its surfaces that leaves the scene.
std::vector<double> escapeShares(const AmbientTransfer& transfer) {
  std::vector<double> escape;
  for (const std::vector<double>& row : transfer.share) {
    double landed = 0.0;
    for (double v : row) landed += v;
    escape.push_back(std::max(0.0, 1.0 - landed));
  }
  return escape;
}

// Step 2: the solve, global or cell by cell (one result type: radiosity, energy, per-cell data).
// A global solve (on the output's atlas) reaching its unshot stop shoots on while in some cell of
// `texelCells` the ambient term would be more than --ambient-share of the light (radiosity/solve/ambient.h,
// ambientShares).
SolveResult solveBake(const BakeOptions& o, const BakeInput& in, const CellGraph& texelGraph,
                      const ExrChannel& texelCells, const AmbientTransfer& transfer, const EglContext& gl,
                      std::chrono::steady_clock::time_point deadline, Context& ctx,
                      std::optional<TwoLevelData>& levels) {
  auto t = ctx.time("solve");
  GlShotEngine glEngine(gl);
  RayShotEngine rays;
  // The residual, for the ambient term.
  SolveControls controls{.readTransfer = !o.noAmbient, .deadline = deadline};
  if (o.method != "cells" && o.ambientShare > 0.0)
    controls.acceptStop = [&](const std::vector<glm::vec3>& radiosity,
                              const std::vector<glm::vec3>& residual) {
      const std::vector<double> shares =
          ambientShares(in.atlas, residual, texelCells.values, texelGraph, radiosity, &transfer);
      return *std::max_element(shares.begin(), shares.end()) <= o.ambientShare;
    };
  if (const float solveDensity = chosenSolveDensity(o, in.atlas); solveDensity > 0.0f) {
    levels.emplace();
    TwoLevelParams twoLevels{.solveDensity = solveDensity};
    twoLevels.lamps.coarsening = o.lampCoarsening;
    if (o.method == "cells") {  // the cells on the coarse atlas, each solve on the GL device
      CellSolveParams params = cellSolveParams(o, in);
      params.deadline = deadline;
      return solveCellsTwoLevel(in.loaded.scene, in.graph, in.quads, in.atlas, twoLevels, params, glEngine,
                                ctx, &*levels);
    }
    const ShotEngines engines{glEngine, usesRays(o, gl) ? static_cast<ShotEngine&>(rays) : glEngine};
    return solveTwoLevel(in.loaded.scene, in.quads, in.atlas, o.atlas, twoLevels, o.solver, engines, ctx,
                         controls, &*levels);
  }
  if (o.method != "cells")
    return solveProgressive(in.loaded.scene, in.atlas, o.solver, glEngine, ctx, controls);
  CellSolveParams params = cellSolveParams(o, in);
  params.deadline = deadline;
  if (o.gather) {
    const CellJobPlan plan = readCellJobPlan(o.plan);
    return gatherCellJobs(o.plan, plan, in.loaded.scene, in.graph, in.atlas, params, ctx);
  }
  return in.onDemand.active ? solveCellsOnDemand(in.loaded.scene, in.graph, in.onDemand.selection,
                                                 in.onDemand.mode, in.atlas, params, glEngine, ctx)
                            : solveCells(in.loaded.scene, in.graph, in.atlas, params, glEngine, ctx);
}

// Step 3: what the stop left unshot, as an ambient term that follows the cells (radiosity/solve/ambient.h),
// added to `s.radiosity` on the texels of `texelCells` that are written. Returns the mean ambient
// irradiance (W/m², RGB; 0 with --no-ambient).
glm::dvec3 addBakeAmbient(const BakeOptions& o, const BakeInput& in, const CellGraph& texelGraph,
                          const ExrChannel& texelCells, const AmbientTransfer& transfer, SolveResult& s) {
  if (o.noAmbient) return glm::dvec3(0.0);
  const std::vector<glm::vec3> unlit = s.radiosity;
  const glm::dvec3 ambient = addAmbient(in.atlas, s.residual, glm::dvec3(s.energy.unshot / 3.0),
                                        texelCells.values, texelGraph, s.radiosity, &transfer);
  if (in.onDemand.active && s.perCell) {  // the cells an on-demand bake does not write stay black
    std::vector<uint8_t> written(texelGraph.cells.size(), 0);
    for (const CellEnergy& c : s.perCell->cells)
      if (const int k = texelGraph.findCell(c.name); k >= 0 && c.written) written[size_t(k)] = 1;
    for (size_t i = 0; i < unlit.size(); ++i) {
      const float k = texelCells.values[i];
      if (!(k >= 0.0f && written[size_t(k)])) s.radiosity[i] = unlit[i];
    }
  }
  return ambient;
}

// report.json's keys of a cells bake: rounds, per-cell and per-portal energy, the on-demand choice.
void addCellsReport(const BakeOptions& o, const BakeInput& in, const CellSolveData& r,
                    nlohmann::json& report) {
  report["energy"].erase("shot_w");
  report["energy"].erase("received_w");
  report["rounds"] = r.rounds;
  report["jobs"] = o.cellParams.jobs;
  report["portal_mode"] = portalLightName(o.cellParams.portals);
  report["max_cell_texels"] = r.maxCellTexels;
  nlohmann::json cells = nlohmann::json::array(), portals = nlohmann::json::array();
  for (const CellEnergy& c : r.cells)
    cells.push_back({{"name", c.name},
                     {"emitted_w", c.emitted},
                     {"received_w", c.received},
                     {"absorbed_w", c.absorbed},
                     {"sent_w", c.sent},
                     {"unshot_w", c.unshot},
                     {"escaped_w", c.escaped},
                     {"created_w", c.created},
                     {"worst_shot_gain", c.worstShotGain},
                     {"solves", c.solves},
                     {"written", c.written},
                     {"shots", c.shots},
                     {"texels", c.texels},
                     {"solve_seconds", c.seconds}});
  for (const PortalEnergy& pe : r.portals) {
    // By name: an on-demand bake solves only some of the graph's portals.
    const auto q = std::find_if(in.graph.portals.begin(), in.graph.portals.end(),
                                [&](const PortalQuad& g) { return g.name == pe.name; });
    portals.push_back({{"name", pe.name},
                       {"cell_a", in.graph.cells[q->cellA].name},
                       {"cell_b", in.graph.cells[q->cellB].name},
                       {"a_to_b_w", pe.aToB},
                       {"b_to_a_w", pe.bToA}});
  }
  report["cell_energy"] = cells;
  report["portal_energy"] = portals;
  report["on_demand"] = onDemandReport(o, in.onDemand, in.graph, in.atlas);
}

// Step 4: report.json, the common keys (apps/lightmap_report.h) and the solver's.
struct BakeFigures {
  std::vector<std::string> views;
  std::vector<std::string> cellNames;  ///< of lightmap.exr's "cell" channel
  glm::dvec3 ambient{0.0};             ///< mean ambient irradiance (W/m²)
  std::vector<double> ambientShares;   ///< per cell of cellNames (and one for no cell), ambientShares
  std::vector<double>
      ambientEscape;  ///< per entry of ambientShares, the share of its light leaving the scene
  double seconds = 0.0;
};

// --density auto's choice: its settings, the pilot, and the output's texels by the density they got.
nlohmann::json autoDensityReport(const BakeOptions& o, const BakeInput& in) {
  if (!in.autoDensity) return nullptr;
  const AutoDensityParams& p = o.autoDensity;
  std::map<double, size_t> texels;  // by texels per metre along the chart's coarser axis, to 0.1
  for (const Patch& patch : in.atlas.patches) {
    const double edge = std::max(glm::length(patch.texelU), glm::length(patch.texelV));
    if (edge > 0.0) texels[std::round(10.0 / edge) / 10.0] += size_t(patch.w) * size_t(patch.h);
  }
  nlohmann::json byDensity = nlohmann::json::array();
  for (const auto& [density, count] : texels) byDensity.push_back({{"density", density}, {"texels", count}});
  return {{"pilot_density", p.pilotDensity},
          {"min_density", p.light.minDensity},
          {"max_density", p.light.maxDensity},
          {"tolerance", p.light.tolerance},
          {"floor_share", p.light.floorShare},
          {"contacts", p.contacts},
          {"max_contact_density", p.maxContactDensity},
          {"pilot_texels", in.autoDensity->pilotTexels},
          {"pilot_s", in.autoDensity->pilotSeconds},
          {"contact_triangles", in.autoDensity->contactTriangles},
          {"chart_texels_by_density", byDensity}};
}

nlohmann::json bakeReport(const BakeOptions& o, const BakeInput& in, const SolveResult& s,
                          const std::optional<TwoLevelData>& levels, const EglContext& gl,
                          const BakeFigures& f, const Context& ctx) {
  const bool cells = o.method == "cells";
  LightmapRun run{.method = o.method,
                  .scene = o.scene,
                  .seconds = f.seconds,
                  .solveSeconds = s.seconds,
                  .atlas = &in.atlas,
                  .atlasParams = o.atlas,
                  .triangles = in.loaded.scene.triangles.size(),
                  .quads = in.quads.quads.size(),
                  .shots = s.shots,
                  .unshotFraction = s.unshotFraction,
                  .cells = cells ? in.graph.cells.size() : size_t(1),
                  .portals = cells ? in.graph.portals.size() : size_t(0),
                  .views = f.views,
                  .cellNames = f.cellNames};
  nlohmann::json report = lightmapReport(run, ctx);
  report["unshot_target"] = o.solver.unshotFraction;
  report["visibility"] = visibilityName(o.solver.visibility);
  report["item_buffer"] = o.solver.itemBuffer;
  report["regions"] = o.solver.maxRegions;
  report["strong_shot_regions"] = o.solver.strongShotRegions;
  report["strong_shot_fraction"] = o.solver.strongShotFraction;
  report["region_size"] = o.solver.regionSize;
  report["jittered_eyes"] = o.solver.jitteredEyes;
  report["lamp_rays"] = o.solver.lampRays;
  // Two levels (radiosity/solve/two_level_solve.h): the lamps on the output's atlas, the rest on a coarser
  // one.
  report["solve_density"] =
      levels ? nlohmann::json(chosenSolveDensity(o, in.atlas)) : nlohmann::json(nullptr);
  report["solve_density_option"] =
      o.solveDensity == kAutoSolveDensity ? nlohmann::json("auto") : nlohmann::json(o.solveDensity);
  report["solve_texels"] = levels ? levels->solveTexels : in.atlas.validTexels();
  if (levels) {
    report["lamp_shots"] = levels->lampShots;
    report["refined_triangles"] = levels->refinedTriangles;
    report["lamp_coarsening"] = o.lampCoarsening;
    report["lamp_coarse_texels"] = levels->lampCoarseTexels;
    report["lamp_refined_texels"] = levels->lampRefinedTexels;
    report["lamp_solve_s"] = levels->lampSeconds;
    report["indirect_solve_s"] = levels->solveSeconds;
    report["indirect_item_buffer"] = levels->indirectItemBuffer;
    report["indirect_solver"] = levels->indirectBackend == "rays" ? "rays" : "gpu";
  }
  report["density_option"] = o.densityAuto ? nlohmann::json("auto") : nlohmann::json(nullptr);
  report["auto_density"] = autoDensityReport(o, in);
  if (o.densityAuto) report["atlas"]["density"] = "auto";
  report["renderer"] = gl.renderer();
  report["gl_version"] = gl.version();
  report["egl_platform"] = gl.platform();
  report["sky"] = skyReport(in.loaded.scene);
  report["energy"] = energyReport(s.energy);
  report["ambient_w_m2"] = {f.ambient.r, f.ambient.g, f.ambient.b};
  // The stop per cell: the target, how often the solve was asked to stop, and each cell's share at the end.
  report["ambient_share_target"] = levels ? nlohmann::json(nullptr) : nlohmann::json(o.ambientShare);
  report["stop_checks"] = s.stopChecks;
  report["stop_bounded"] = s.stopBounded;  // the loop's bound on the stop per room (progressive_loop.h)
  report["max_texels"] = o.densityAuto ? nlohmann::json(o.autoDensity.maxTexels) : nlohmann::json(nullptr);
  nlohmann::json shares = nlohmann::json::object();
  for (size_t c = 0; c < f.ambientShares.size(); ++c)
    shares[c < f.cellNames.size() ? f.cellNames[c] : std::string("(no cell)")] = f.ambientShares[c];
  report["ambient_share"] = shares;
  nlohmann::json escape = nlohmann::json::object();
  for (size_t c = 0; c < f.ambientEscape.size(); ++c)
    escape[c < f.cellNames.size() ? f.cellNames[c] : std::string("(no cell)")] = f.ambientEscape[c];
  report["ambient_escape"] = escape;
  // A bake stopped by --time-limit is valid but partial: what it left unshot is in energy.unshot_w (and
  // spread by the ambient term unless --no-ambient).
  report["time_limit_s"] = o.timeLimit > 0.0 ? nlohmann::json(o.timeLimit) : nlohmann::json(nullptr);
  report["partial"] = s.timedOut;
  if (s.timedOut) {
    std::ostringstream why;
    why << "time limit of " << o.timeLimit << " s reached after " << s.shots << " shots with "
        << s.unshotFraction * 100.0 << " % of the emitted power unshot (target "
        << o.solver.unshotFraction * 100.0 << " %)";
    report["partial_reason"] = why.str();
  }
  if (s.perCell) addCellsReport(o, in, *s.perCell, report);
  return report;
}

// The bake's own arguments (after "bake") without --plan: what every cell job re-reads from plan.json.
std::vector<std::string> bakeArguments() {
  const std::vector<std::string>& all = commandArguments();
  std::vector<std::string> args;
  auto it = std::find(all.begin(), all.end(), "bake");
  for (it = it == all.end() ? it : it + 1; it != all.end(); ++it) {
    if (*it == "--plan") {
      if (++it == all.end()) break;
      continue;
    }
    if (it->rfind("--plan=", 0) == 0) continue;
    args.push_back(*it);
  }
  return args;
}

// "0,3,4": the emitter groups a first-shot job shoots.
std::vector<int> groupIndices(const std::string& list) {
  std::vector<int> out;
  std::istringstream in(list);
  for (std::string item; std::getline(in, item, ',');) {
    size_t used = 0;
    int g = -1;
    try {
      g = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || g < 0)
      throw InputError("--first-shot", "not a list of emitter group numbers: " + list);
    out.push_back(g);
  }
  return out;
}

int bakeLoaded(const BakeOptions& o, BakeInput& in, const EglContext* given,
               std::chrono::steady_clock::time_point start, std::string& sizeLine, Context& ctx);

// The gather of a cell-job server (a {"gather": true} request): `cpgi cell-job PLAN --gather` on the scene,
// graph and EGL context the server loaded at its start, with a context of its own (the report's timings are
// the gather's) and no output on stdout (the server's answers are there).
void serveGather(const BakeOptions& served, BakeInput& in, const EglContext& gl) {
  BakeOptions o = served;
  o.jobServe = false, o.gather = true, o.quiet = true;
  Context ctx;
  std::string sizeLine;
  bakeLoaded(o, in, &gl, std::chrono::steady_clock::now(), sizeLine, ctx);
}

// --plan DIR: the cell jobs' plan, or (`cpgi cell-job`) the first shot of some emitter groups, its sum, or
// one round of some cells.
int runCellJobStage(const BakeOptions& o) {
  Context ctx;
  ctx.setProgress(stderrProgress(o.quiet));
  if (o.method != "cells") throw InputError("--plan", "needs --method cells");
  if (!o.onlyCells.empty() || !o.around.empty())
    throw InputError("--plan", "cell jobs bake the whole cell graph: leave out --only-cells and --around");
  BakeInput in = loadBakeInput(o, ctx);
  const bool planStep = !o.jobServe && o.jobRound <= 0 && o.jobFirstShot.empty() && !o.jobFirstShotSum;
  if (!planStep) usePlannedDensities(o, in);
  CellSolveParams params = cellSolveParams(o, in);
  if (o.jobServe) {
    const EglContext gl(ctx);
    bool atlasBuilt = false;  // rounds need only the cells' atlases; the first shot the whole scene's
    const auto globalAtlas = [&]() -> const LightmapAtlas& {
      if (!atlasBuilt) buildBakeAtlas(o, in, nullptr, ctx);  // with the plan's densities
      atlasBuilt = true;
      return in.atlas;
    };
    const auto gather = [&] {
      serveGather(o, in, gl);
      atlasBuilt = true;  // the gather built it again, the same
    };
    return serveCellJobs(o.plan, readCellJobPlan(o.plan).bakeArgs, in.loaded.scene, in.graph, params,
                         globalAtlas, gather, gl, ctx, std::cin, std::cout);
  }
  if (o.jobRound > 0) {
    const CellJobPlan plan = readCellJobPlan(o.plan);
    std::vector<int> run;
    if (o.jobCells.empty())
      for (int c = 0; c < int(in.graph.cells.size()); ++c) run.push_back(c);
    else
      run = cellsByName(in.graph, o.jobCells, "--cell");
    const EglContext gl(ctx);
    GlShotEngine engine(gl);
    runCellJobs(o.plan, plan, o.jobRound, run, in.loaded.scene, in.graph, params, engine, ctx);
    if (!o.quiet) std::cout << o.plan << ": round " << o.jobRound << " of " << run.size() << " cells done\n";
    return 0;
  }
  std::unique_ptr<EglContext> pilotGl;  // the plan step's pilot, with --density auto
  if (planStep && o.densityAuto) pilotGl = std::make_unique<EglContext>(ctx);
  buildBakeAtlas(o, in, pilotGl.get(), ctx);
  params.atlas.triangleDensity = in.triangleDensity;  // the plan step's pilot chose them just now
  if (!o.jobFirstShot.empty()) {
    const CellJobPlan plan = readCellJobPlan(o.plan);
    std::vector<int> groups;
    if (o.jobFirstShot == "all")
      for (int g = 0; g < int(plan.firstShotGroups.size()); ++g) groups.push_back(g);
    else
      groups = groupIndices(o.jobFirstShot);
    const EglContext gl(ctx);
    GlShotEngine engine(gl);
    runFirstShotJobs(o.plan, plan, groups, in.loaded.scene, in.graph, in.atlas, params, engine, ctx);
    if (!o.quiet) std::cout << o.plan << ": first shot of " << groups.size() << " emitter groups done\n";
    return 0;
  }
  if (o.jobFirstShotSum) {
    const CellJobPlan plan =
        sumFirstShotJobs(o.plan, readCellJobPlan(o.plan), in.loaded.scene, in.graph, in.atlas, params, ctx);
    if (!o.quiet)
      std::cout << o.plan << ": first shot summed; next: cpgi cell-job " << o.plan << " --round 1\n";
    return 0;
  }
  requireSolveMemory(o, in.atlas);
  requireConvergence(o, in.loaded.scene, in.atlas);
  const CellJobPlan plan =
      planCellJobs(o.plan, in.loaded.scene, in.graph, in.atlas, params, bakeArguments(), ctx);
  if (!o.quiet) {
    std::cout << o.plan << ": plan of " << plan.cells.size() << " cells and " << plan.firstShotGroups.size()
              << " emitter groups; next: cpgi cell-job " << o.plan << " --first-shot\n";
    for (const std::string& w : ctx.warnings()) std::cerr << "warning: " << w << "\n";
  }
  return 0;
}

// A line on stderr that stays, clear of a live progress line on a terminal.
void printNote(const std::string& text) {
  std::fprintf(stderr, "%s%s\n", ::isatty(STDERR_FILENO) ? "\r\033[K" : "", text.c_str());
  std::fflush(stderr);
}

// How large the bake is, and what decides how long it takes.
std::string bakeSizeLine(const BakeOptions& o, const BakeInput& in) {
  std::ostringstream line;
  line << "bake: " << in.atlas.validTexels() << " texels in " << in.atlas.patches.size() << " patches ("
       << in.loaded.scene.triangles.size() << " triangles";
  if (o.method == "cells")
    line << ", " << in.graph.cells.size() << " cells, " << in.graph.portals.size() << " portals";
  line << "), about " << int(std::ceil(solveBytes(o, in.atlas) / (1 << 20)))
       << " MB; the time is estimated from the first shots";
  if (o.timeLimit > 0.0) line << "; --time-limit " << o.timeLimit << " s stops it with a partial result";
  return line.str();
}

// Two lines that stay, around the progress line: the bake's size (`size`, once set) at the solver's first
// report, before its first shot and after its settings are checked (an error stays one line); and, for a
// global solve, the first time estimate, once its status carries one (measured from the first shots' cost
// and the decay of the unshot power), with what the time limit will do to it. The progress line goes on
// updating the estimate.
Context::ProgressFn withBakeNotes(Context::ProgressFn inner, const BakeOptions& o,
                                  std::chrono::steady_clock::time_point start,
                                  std::shared_ptr<std::string> size) {
  if (!inner) return inner;
  auto said = std::make_shared<std::pair<bool, bool>>(false, false);  // size, estimate
  return [inner, said, size, global = o.method == "global", limit = o.timeLimit, start](const Progress& p) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!said->first && p.stage == "solve" && !size->empty()) {
      said->first = true;
      printNote(*size + " (" + formatDuration(std::max(elapsed, 1.0)) + " so far)");
    }
    if (global && !said->second && p.stage == "solve" && p.shots > 0 && p.secondsLeft >= 0.0) {
      said->second = true;
      std::ostringstream line;
      line << "bake: after " << p.shots << " shots, about " << formatDuration(p.secondsLeft)
           << " more to solve";
      if (limit > 0.0 && elapsed + p.secondsLeft > limit)
        line << "; the time limit stops it in " << formatDuration(std::max(0.0, limit - elapsed))
             << " with a partial result";
      printNote(line.str());
    }
    inner(p);
  };
}

// Steps 2-4 of a bake whose scene is loaded (`in`, from loadBakeInput): the atlas, the solve (or a cell-job
// plan's gather), the ambient term and the files. `given`: the EGL context to draw with (a cell-job
// server's, kept from job to job), else one is opened here. `sizeLine` takes the bake's size for the
// progress notes. `in.atlas` is built again (the same for the same options).
int bakeLoaded(const BakeOptions& o, BakeInput& in, const EglContext* given,
               std::chrono::steady_clock::time_point start, std::string& sizeLine, Context& ctx) {
  const auto deadline = o.timeLimit > 0.0
                            ? start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                          std::chrono::duration<double>(o.timeLimit))
                            : std::chrono::steady_clock::time_point::max();
  OutputDir out(o.output, kLightmapResultNames);
  std::unique_ptr<EglContext> opened;
  const EglContext* gl = given;
  auto openGl = [&] {
    auto t = ctx.time("egl");
    opened = std::make_unique<EglContext>(ctx);
    gl = opened.get();
  };
  if (o.gather) usePlannedDensities(o, in);
  if (o.densityAuto && in.triangleDensity.empty() && !gl) openGl();  // the pilot shoots before the layout
  buildBakeAtlas(o, in, gl, ctx, deadline);
  requireSolveMemory(o, in.atlas);
  requireConvergence(o, in.loaded.scene, in.atlas);
  sizeLine = bakeSizeLine(o, in);
  if (!gl) openGl();
  // The glb and the "cell" channel keep the cells baked with (the scene's own for a global bake); a
  // scene without any is labelled by its automatic rooms, for the stop per cell, the per-cell figures and
  // the ambient term.
  const CellGraph& cells = o.method == "cells" ? in.graph : in.loaded.cells;
  const RoomLabels rooms = cells.empty() || cells.definedByVolumes()
                               ? labelTexelsByRoom(in.loaded.scene, o.scene, in.atlas, ctx, cells)
                               : RoomLabels{};
  const CellGraph& texelGraph = rooms.graph.empty() ? cells : rooms.graph;
  const ExrChannel texelCells =
      rooms.graph.empty() ? cellChannel(in.atlas, in.loaded.scene, cells) : rooms.channel;
  const AmbientTransfer transfer = bakeAmbientTransfer(o, in, texelGraph, texelCells, ctx);
  std::optional<TwoLevelData> levels;
  SolveResult s = solveBake(o, in, texelGraph, texelCells, transfer, *gl, deadline, ctx, levels);
  BakeFigures f;
  if (!s.residual.empty())
    f.ambientShares =
        ambientShares(in.atlas, s.residual, texelCells.values, texelGraph, s.radiosity, &transfer);
  f.cellNames = cellNames(texelGraph);
  if (s.stopBounded) ctx.warn(roomsAboveShare(f.ambientShares, f.cellNames, o.ambientShare));
  f.ambientEscape = escapeShares(transfer);
  f.ambient = addBakeAmbient(o, in, texelGraph, texelCells, transfer, s);
  const std::pair<const char*, double> totals[] = {{"emitted", s.energy.emitted},
                                                   {"shot", s.energy.shot},
                                                   {"received", s.energy.received},
                                                   {"absorbed", s.energy.absorbed},
                                                   {"unshot", s.energy.unshot}};
  requireFiniteResult(o.scene, in.atlas, s.radiosity, totals);
  {
    auto t = ctx.time("write");
    // "emissive" marks lamp texels, as `cpgi reference` does, so compare-light can leave them out; "cell"
    // gives each texel its cell, for compare-light's per-cell figures.
    const ExrChannel emissive{"emissive", emissiveMask(in.atlas)};
    f.views = writeLightmapOutputs(out, in.loaded.scene, cells, in.atlas, s.radiosity, {emissive, texelCells},
                                   ctx, o.views)
                  .views;
  }
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const nlohmann::json report = bakeReport(o, in, s, levels, *gl, f, ctx);
  writeReport(out, report);
  writeBakeReportPage(out, "bake of " + o.scene, report, in.loaded.scene, cells, in.atlas, s.radiosity);
  out.commit();
  if (!o.quiet) {
    std::cout << o.output << ": " << in.atlas.validTexels() << " texels, " << s.shots << " shots, unshot "
              << s.unshotFraction * 100.0 << " %, " << f.seconds << " s"
              << (s.timedOut ? " (partial: stopped at the time limit)" : "") << "\n";
    for (const std::string& w : ctx.warnings()) std::cerr << "warning: " << w << "\n";
  }
  return 0;
}

int runBake(const BakeOptions& o) {
  if (o.method == "cells" && o.solveDensity > 0.0f &&
      (!o.plan.empty() || !o.onlyCells.empty() || !o.around.empty()))
    throw InputError("--solve-density", "cell jobs and on-demand bakes solve in one level: leave it out");
  if (!o.plan.empty() && !o.gather) return runCellJobStage(o);
  const auto start = std::chrono::steady_clock::now();
  Context ctx;
  auto sizeLine = std::make_shared<std::string>();
  ctx.setProgress(withBakeNotes(stderrProgress(o.quiet), o, start, sizeLine));
  BakeInput in = loadBakeInput(o, ctx);
  return bakeLoaded(o, in, nullptr, start, *sizeLine, ctx);
}

void addOnDemandOptions(CLI::App& sub, BakeOptions& o) {
  auto* only =
      sub.add_option("--only-cells", o.onlyCells,
                     "With --method cells: bake only these cells (comma-separated names); the others "
                     "act through their portals (see --boundary)");
  auto* around =
      sub.add_option("--around", o.around,
                     "With --method cells: bake the cell holding the point X,Y,Z (metres) and those "
                     "within --depth portals of it");
  only->excludes(around);
  sub.add_option("--depth", o.depth, "With --around: portals away from the point's cell")
      ->check(CLI::Range(0, 1000000))
      ->needs(around)
      ->capture_default_str();
  addBoundaryOption(sub, o.boundary);
}

}  // namespace

void addBakeCommand(CLI::App& app, CommandFn& selected) {
  auto o = std::make_shared<BakeOptions>();
  CLI::App* sub =
      app.add_subcommand("bake", "Bake diffuse global illumination into a lightmap (GPU radiosity)");
  sub->add_option("scene", o->scene, "Scene (.glb, .gltf, .obj)")->required();
  sub->add_option("-o,--output", o->output, "Output folder")->required();
  sub->add_option("--method", o->method,
                  "global: one progressive radiosity solve over the whole scene; cells: cell by cell, light "
                  "handed on through portals (needs --cells)")
      ->check(CLI::IsMember({"global", "cells"}))
      ->capture_default_str();
  sub->add_option(
         "--cells", o->cells,
         "With --method cells: a glTF with cell:/portal: nodes or with rooms given as cellvolume: meshes "
         "alone (the scene itself when it has them), "
         "a decompose output folder, or auto (the automatic decomposition, with the decomposition "
         "options below)")
      ->capture_default_str();
  addCellOptions(*sub, o->cellParams);
  addOnDemandOptions(*sub, *o);
  sub->add_option(
      "--plan", o->plan,
      "With --method cells: do not solve; write the cell jobs' plan (cells, portals and the lamps' "
      "emitter groups) into this folder, for `cpgi cell-job` or cpgi-dask (docs/cell-jobs.md)");
  // Set by `cpgi cell-job` (apps/cell_job_command.cpp) on the plan's own arguments; not for users.
  sub->add_option("--job-round", o->jobRound)->group("")->check(CLI::Range(1, 1000000));
  sub->add_option("--job-cells", o->jobCells)->group("");
  sub->add_option("--job-first-shot", o->jobFirstShot)->group("");
  sub->add_flag("--job-first-shot-sum", o->jobFirstShotSum)->group("");
  sub->add_flag("--job-serve", o->jobServe)->group("");
  sub->add_flag("--gather", o->gather)->group("");
  addAtlasOptions(*sub, o->atlas, {}, &o->densityAuto);
  addSolverOptions(*sub, o->solver);
  addDecomposeOptions(*sub, o->decompose);
  addAmbientOption(*sub, o->noAmbient, o->ambientShare);
  addViewOptions(*sub, o->views);
  addLoadOptions(*sub, o->load);
  addDarkOption(*sub, o->allowDark);
  addSkyOptions(*sub, o->sky, true);
  addTimeLimitOption(*sub, o->timeLimit);
  addSolveDensityOption(*sub, o->solveDensity);
  addLampCoarseningOption(*sub, o->lampCoarsening);
  sub->add_option("--indirect-solver", o->indirectSolver,
                  "With two levels (--solve-density): shoot the interreflection on the coarse atlas by item "
                  "buffers on the GL device (gpu), by Embree rays on the CPU (rays), or by rays where the GL "
                  "device is a software rasterizer such as llvmpipe (auto)")
      ->check(CLI::IsMember({"auto", "gpu", "rays"}))
      ->default_str(o->indirectSolver);
  addDensityToleranceOption(*sub, o->autoDensity.light.tolerance);
  addMaxTexelsOption(*sub, o->autoDensity.maxTexels);
  sub->add_flag("-q,--quiet", o->quiet, "No progress or summary");
  sub->callback([&selected, o, sub] {
    o->maxShotsGiven = sub->count("--max-shots") > 0;
    selected = [o] { return runBake(*o); };
  });
}

}  // namespace cpgi::cli
