// bake() (bake.h): steps 2–4 on a loaded scene; step 1 and the checks are bake_steps.cpp's, the report
// bake_report.cpp's.
#include "radiosity/bake/bake.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "core/error.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "decomposition/outside_portals.h"
#include "radiosity/bake/bake_limits.h"
#include "radiosity/bake/bake_steps.h"
#include "radiosity/bake/cell_source.h"
#include "radiosity/bake/light_probes.h"
#include "radiosity/bake/lightmap_report.h"
#include "radiosity/bake/report_page.h"
#include "radiosity/cells/cell_jobs.h"
#include "radiosity/lightmap/cell_channel.h"
#include "radiosity/lightmap/directional_lightmap.h"
#include "radiosity/lightmap/finite_result.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/sky_openings.h"
#include "radiosity/solve/ambient.h"
#include "radiosity/solve/ambient_transfer.h"

namespace cpgi {

bool indirectByRays(IndirectSolver solver, const EglContext& gl) {
  if (solver != IndirectSolver::Auto) return solver == IndirectSolver::Rays;
  return gl.softwareRasterizer();
}

BakeEngines::BakeEngines(Backend backend, IndirectSolver indirect, const EglContext* given, Context& ctx)
    : backend_(backend), indirect_(indirect), ctx_(ctx), gl_(given) {}

BakeEngines::~BakeEngines() = default;

const ShotEngines& BakeEngines::engines() {
  if (engines_) return *engines_;
  if (!gl_ && backend_ != Backend::Rays) {
    auto t = ctx_.time("egl");
    try {
      opened_ = std::make_unique<EglContext>(ctx_);
      gl_ = opened_.get();
    } catch (const SystemError& e) {
      if (backend_ == Backend::Gl) throw;
      ctx_.warn(std::string(e.what()) + "; baking by Embree rays on the CPU (--backend rays)");
    }
  }
  if (!gl_) {
    engines_.emplace(ShotEngines{rays_, rays_});
    return *engines_;
  }
  glEngine_ = std::make_unique<GlShotEngine>(*gl_);
  ShotEngine& gl = *glEngine_;
  engines_.emplace(ShotEngines{gl, indirectByRays(indirect_, *gl_) ? static_cast<ShotEngine&>(rays_) : gl});
  return *engines_;
}

namespace bake_steps {
namespace {

// Where the light leaving each cell's surfaces lands, or leaves the scene, for the ambient term and the
// stop per cell (radiosity/solve/ambient_transfer.h): the portals' areas alone kept the outside's light in
// it. Empty (the portals' areas) without the ambient term.
AmbientTransfer bakeAmbientTransfer(const BakeSettings& s, const BakeInput& in, const CellGraph& texelGraph,
                                    const ExrChannel& texelCells, Context& ctx) {
  if (!s.solver.ambient) return {};
  auto t = ctx.time("ambient transfer");
  ctx.progress("set-up", 0.0, "where each room's light lands");
  const RayScene rays(*in.scene);
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

// What the solve needs beside the settings: the cells of its texels and where their light goes.
struct SolveInput {
  const CellGraph& texelGraph;
  const ExrChannel& texelCells;
  const AmbientTransfer& transfer;
  const ShotEngines& engines;
  Clock::time_point deadline;
  const std::filesystem::path* gatherPlan;
  const CpuShare& load;  ///< the wall a CPU second takes now: the two-level set-up's estimate
};

// The openings the sky gather draws towards (sky_openings.h): the rooms' portals onto the outside, faced out
// of their rooms (a file's may face into them: decomposition/outside_portals.h; the automatic rooms' face
// from cell A into B already and keep no triangles to turn them by).
std::vector<SkyOpening> bakeSkyOpenings(const Scene& scene, const CellGraph& rooms) {
  CellGraph faced = rooms;
  decomp::orientOutsidePortals(scene, faced);
  return skyOpeningsOf(faced);
}

// Step 2: the solve, global or cell by cell (one result type: radiosity, energy, per-cell data).
// A global solve (on the output's atlas) reaching its unshot stop shoots on while in some cell of
// `texelCells` the ambient term would be more than the ambient share of the light (ambientShares).
SolveResult solveBake(const BakeSettings& s, const BakeInput& in, const SolveInput& x, Context& ctx,
                      std::optional<TwoLevelData>& levels) {
  auto t = ctx.time("solve");
  const bool cells = s.cells.method == BakeMethod::Cells;
  SolveControls controls{.readTransfer = s.solver.ambient, .deadline = x.deadline};  // the residual
  controls.skyOpenings = bakeSkyOpenings(*in.scene, x.texelGraph);
  controls.skyTimeShare = kBakeSkyTimeShare;
  controls.load = [&load = x.load] { return load.ratio(); };
  std::optional<RoomStop> roomStop;  // the time estimate asks the same rule cell by cell
  if (!cells && s.solver.ambientShare > 0.0) {
    const RoomStop& stop =
        roomStop.emplace(in.atlas, x.texelCells.values, x.texelGraph, &x.transfer, s.solver.ambientShare);
    controls.acceptStop = [&stop](const std::vector<glm::vec3>& radiosity,
                                  const std::vector<glm::vec3>& residual) {
      return stop.accepts(radiosity, residual);
    };
    controls.roomStop = {
        stop.texelCells(),
        [&stop](const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) {
          return stop.cellLight(radiosity, residual);
        },
        [&stop](const CellLight& light) { return stop.accepts(light); }};
  }
  CellSolveParams params = cellSolveParams(s, in);
  params.deadline = x.deadline;
  params.load = controls.load;
  // Cell jobs and on-demand cells are one level: a job's plan has one atlas, and an on-demand bake's
  // cells outside the selection are lit by the whole atlas's first shot.
  const bool oneLevel = cells && (x.gatherPlan || in.onDemand.active);
  if (const float solveDensity = chosenSolveDensity(s, in.atlas); solveDensity > 0.0f && !oneLevel) {
    levels.emplace();
    TwoLevelParams twoLevels{.solveDensity = solveDensity};
    twoLevels.lamps.coarsening = s.solver.lampCoarsening;
    if (s.solver.solveDensity == kAutoSolveDensity) twoLevels.maxSolveTexels = kAutoSolveTexels;
    if (cells)  // the cells on the coarse atlas, each solve on the reflections' engine
      return solveCellsTwoLevel(*in.scene, *in.cells, in.quads, in.atlas, twoLevels, params, x.engines, ctx,
                                &*levels);
    return solveTwoLevel(*in.scene, in.quads, in.atlas, s.atlas.params, twoLevels, s.solver.params, x.engines,
                         ctx, controls, &*levels);
  }
  if (!cells) return solveProgressive(*in.scene, in.atlas, s.solver.params, x.engines.lamps, ctx, controls);
  if (x.gatherPlan)
    return gatherCellJobs(*x.gatherPlan, readCellJobPlan(*x.gatherPlan), *in.scene, *in.cells, in.atlas,
                          params, ctx);
  return in.onDemand.active ? solveCellsOnDemand(*in.scene, *in.cells, in.onDemand.selection,
                                                 in.onDemand.mode, in.atlas, params, x.engines.lamps, ctx)
                            : solveCells(*in.scene, *in.cells, in.atlas, params, x.engines.lamps, ctx);
}

// Step 3: what the stop left unshot, as an ambient term that follows the cells (radiosity/solve/ambient.h),
// added to `r.radiosity` on the texels of `texelCells` that are written. Returns the mean ambient
// irradiance (W/m², RGB; 0 without the ambient term).
glm::dvec3 addBakeAmbient(const BakeSettings& s, const BakeInput& in, const SolveInput& x, SolveResult& r) {
  if (!s.solver.ambient) return glm::dvec3(0.0);
  const std::vector<glm::vec3> unlit = r.radiosity;
  const glm::dvec3 ambient = addAmbient(in.atlas, r.residual, glm::dvec3(r.energy.unshot / 3.0),
                                        x.texelCells.values, x.texelGraph, r.radiosity, &x.transfer);
  if (in.onDemand.active && r.perCell) {  // the cells an on-demand bake does not write stay black
    std::vector<uint8_t> written(x.texelGraph.cells.size(), 0);
    for (const CellEnergy& c : r.perCell->cells)
      if (const int k = x.texelGraph.findCell(c.name); k >= 0 && c.written) written[size_t(k)] = 1;
    for (size_t i = 0; i < unlit.size(); ++i) {
      const float k = x.texelCells.values[i];
      if (!(k >= 0.0f && written[size_t(k)])) r.radiosity[i] = unlit[i];
    }
  }
  return ambient;
}

// The one line a solve stopped by the time limit adds: how the emitted power stands, the light not yet
// carried included.
std::string stoppedEarlyNote(const BakeSettings& s, const SolveResult& r) {
  const EnergyTotals& e = r.energy;
  char line[400];
  std::snprintf(line, sizeof line,
                "solve: the time limit stopped it after %d shots: of %.4g W emitted, %.4g W absorbed, %.4g W "
                "escaped and %.4g W (%.1f %%) still unshot, %s",
                r.shots, e.emitted, e.absorbed, std::abs(e.escaped()) < 1e-9 * e.emitted ? 0.0 : e.escaped(),
                e.unshot, e.emitted > 0.0 ? 100.0 * e.unshot / e.emitted : 0.0,
                s.solver.ambient ? "spread over the rooms as the ambient term" : "left out (--no-ambient)");
  return line;
}

// The density pilot's share (kPilotTimeShare) of the time from now to `beforeOutputs`.
Clock::time_point pilotDeadline(Clock::time_point beforeOutputs) {
  if (beforeOutputs == Clock::time_point::max()) return beforeOutputs;
  const Clock::time_point now = Clock::now();
  if (beforeOutputs <= now) return beforeOutputs;
  return now + std::chrono::duration_cast<Clock::duration>((beforeOutputs - now) * kPilotTimeShare);
}

// With --density auto, a cell job's texel densities are those its plan recorded: every job lays its
// atlases out alike, and a pilot of its own could choose otherwise (another machine's GPU).
void usePlannedDensities(const BakeSettings& s, BakeInput& in, const std::filesystem::path& plan) {
  if (!s.atlas.densityAuto) return;
  in.triangleDensity = readCellJobPlan(plan).triangleDensity;
  if (in.triangleDensity.size() != in.scene->triangles.size())
    throw InputError((plan / "plan.json").string(),
                     "holds no texel density per triangle of " + s.input.scene + "; make the plan again");
}

// The seconds kept back from the solve for the outputs: all of their estimate but the directional gather's
// and the probes', of which at most kGatherTimeShare of the limit (a gather its deadline stops writes
// nothing, said in a warning).
double outputsKeptBack(const BakeSettings& s, const OutputEstimate& outputs) {
  const double gathers = s.limits.timeLimit > 0.0
                             ? std::min(outputs.gatherSeconds(), kGatherTimeShare * s.limits.timeLimit)
                             : outputs.gatherSeconds();
  return outputs.seconds() - outputs.gatherSeconds() + gathers;
}

// The time point `part` of `whole` of the way from now to `until` (none stays none; past stays past).
Clock::time_point shareOfTimeLeft(Clock::time_point until, double part, double whole) {
  const Clock::time_point now = Clock::now();
  if (until == Clock::time_point::max() || until <= now || !(whole > 0.0)) return until;
  return now +
         std::chrono::duration_cast<Clock::duration>((until - now) * std::clamp(part / whole, 0.0, 1.0));
}

// probes.json (bake --probes), its JSON for baked.glb in `probes`; returns report.json's entry. A gather
// the deadline stopped writes none (a room without its probes would take its neighbours' light).
nlohmann::json writeLightProbes(const BakeInput& in, const SolveResult& r, const EngineOutputParams& engine,
                                Clock::time_point deadline, OutputDir& out, nlohmann::json& probes,
                                BakeFigures& f, Context& ctx) {
  ProbeParams params;
  params.spacing = engine.probeSpacing;
  const LightProbes gathered =
      gatherLightProbes(*in.scene, *in.cells, in.atlas, r.radiosity, params, ctx, deadline);
  nlohmann::json report = {{"count", gathered.probes.size()},
                           {"spacing_m", params.spacing},
                           {"rays", gathered.rays},
                           {"seconds", gathered.seconds}};
  if (!gathered.complete) {
    const std::string why = "the time limit came after " + std::to_string(gathered.gathered) + " of " +
                            std::to_string(gathered.probes.size()) + " probes";
    ctx.warn("probes: " + why + "; probes.json is not written");
    f.skippedOutputs.push_back("probes");
    report["skipped"] = why;
    return report;
  }
  probes = lightProbesJson(gathered, *in.cells);
  writeFileAtomically(out.file("probes.json"), probes.dump());
  report["file"] = "probes.json";
  return report;
}

// The light written: the files of the result set (with a folder) and the figures of the report.
// Before `deadline`, the outputs' estimate kept back from each: the probes and the directional gather
// share the time the files and the page leave, by their estimates; the views stop with the page's left.
// Only the optional outputs of `plan` are started; those it left out are said in one warning.
void writeBake(const BakeSettings& s, const BakeInput& in, const SolveInput& x, const SolveResult& r,
               const ViewParams& views, const OutputEstimate& outputs, const OutputPlan& plan,
               Clock::time_point deadline, OutputDir* out, BakeFigures& f, Context& ctx) {
  auto t = ctx.time("write");
  if (!out) return;
  ctx.progress("write", 0.0, "lightmaps and glb files");
  // "emissive" marks lamp texels, as `cpgi reference` does, so compare-light can leave them out; "cell"
  // gives each texel its cell, for compare-light's per-cell figures.
  const ExrChannel emissive{"emissive", emissiveMask(in.atlas)};
  EngineOutputParams engine = s.output.engine;
  engine.directional = plan.directional;
  engine.probes = plan.probes;
  const ViewParams shown = plan.smallerViews.value_or(views);
  if (plan.smallerViews) {
    char line[300];
    std::snprintf(line, sizeof line,
                  "views: the time limit leaves too little for %d pixels wide at %d x %d rays a pixel: "
                  "rendered %d pixels wide at one ray a pixel",
                  views.width, views.supersample, views.supersample, shown.width);
    ctx.warn(line);
  }
  f.viewWidth = shown.width;
  if (!plan.skipped.empty()) {
    f.outputsLeftOut = plan.skipped;
    std::string names;
    for (const std::string& o : plan.skipped) names += (names.empty() ? "" : ", ") + o;
    ctx.warn("write: the time limit is too near for " + names +
             " (their estimate does not fit beside the lightmap's files and report); left out");
  }
  nlohmann::json probes, probesReport;
  if (engine.probes) {
    // The placement's voxels cannot stop part-way: without the time for them, none are placed.
    const Clock::time_point gathers = keepBack(deadline, outputs.filesSeconds + outputs.pageSeconds);
    Clock::time_point until = shareOfTimeLeft(gathers, outputs.probesSeconds, outputs.gatherSeconds());
    if (keepBack(until, outputs.probeVoxelSeconds) <= Clock::now()) until = Clock::now();
    probesReport = writeLightProbes(in, r, engine, until, *out, probes, f, ctx);
  }
  // The first view whatever the deadline: a few tenths of a second at kLimitedViewWidth.
  LightmapOutputs written = writeLightmapOutputs(
      *out, *in.scene, *in.cells, in.atlas, r.radiosity, {emissive, x.texelCells}, ctx, shown,
      plan.views ? keepBack(deadline, outputs.pageSeconds) : Clock::time_point::min(), engine, probes,
      plan.views ? 1 : 0);
  f.engine = std::move(written.engine);
  if (engine.probes) f.engine["probes"] = probesReport;
  // The gathers the plan left out are said where a stopped one is (engine_lightmap.*.skipped).
  const std::string notStarted = "left out before its gather: its estimate did not fit in the time left";
  if (s.output.engine.directional && !plan.directional) f.engine["directional"] = {{"skipped", notStarted}};
  if (s.output.engine.probes && !plan.probes) f.engine["probes"] = {{"skipped", notStarted}};
  f.views = std::move(written.views);
  f.skippedViews = std::move(written.skippedViews);
  f.skippedOutputs.insert(f.skippedOutputs.end(), written.skippedOutputs.begin(),
                          written.skippedOutputs.end());
}

// The texels of the least atlas a bake of `scene` can end with: a layout stopped by the time limit is laid
// out again at most kMostCoarsening times coarser (bake_steps.cpp, coarsenToFit), from the density asked or
// with --density auto the least it chooses; every chart keeps its least size with its gutter (about one
// chart for two triangles).
size_t leastTexels(const BakeSettings& s, const Scene& scene) {
  double texels = 0.0;
  if (s.atlas.densityAuto) {  // at least the pilot's even density, which a bake with no time for it takes
    texels = texelsByArea(scene, {}, pilotDensity(scene, s.atlas.autoDensity));
    if (s.atlas.autoDensity.maxTexels > 0) texels = std::min(texels, double(s.atlas.autoDensity.maxTexels));
  } else if (s.atlas.params.texelsPerQuad > 0)  // about one quad per two triangles
    texels = 0.5 * double(scene.triangles.size()) * std::pow(double(s.atlas.params.texelsPerQuad), 2.0);
  else
    texels = texelsByArea(scene, {}, s.atlas.params.density);
  const double chart = std::pow(double(s.atlas.params.minTexels + 2 * s.atlas.params.padding), 2.0);
  return size_t(texels / double(kMostCoarsening * kMostCoarsening) +
                0.5 * double(scene.triangles.size()) * chart);
}

// The least a bake of `scene` writes, at `costs` (the share of a core measured so far): the least layout
// and the lightmap's files and report of its texels, in wall seconds.
LeastBake leastBake(const BakeSettings& s, const Scene& scene, const MachineCosts& costs,
                    const CpuShare& load) {
  LeastBake least;
  least.texels = leastTexels(s, scene);
  const OutputEstimate files =
      estimateOutputs(scene, {}, s.output.views, least.texels, least.texels, costs, EngineOutputParams{});
  least.layoutSeconds = leastLayoutCpuSeconds(scene, least.texels) * load.ratio();
  least.seconds = least.layoutSeconds + files.filesSeconds + files.pageSeconds;
  least.share = load.share();
  return least;
}

// The optional outputs that fit in the time left after the solve, among those `early` planned before it,
// re-estimated at the load observed over the whole bake so far (the solve's included): the rays' cost
// scaled by how the load moved since `before`'s estimate, the files' by the load itself
// (estimateOutputs). Its `skipped` names those either plan left out.
OutputPlan plannedOutputs(const BakeSettings& s, const Scene& scene, const std::vector<Camera>& cameras,
                          const ViewParams& views, const LightmapAtlas& atlas, const OutputEstimate& before,
                          const OutputPlan& early, const CpuShare& load, Clock::time_point deadline) {
  EngineOutputParams asked = s.output.engine;
  asked.directional = early.directional, asked.probes = early.probes;
  MachineCosts now{.ray = before.raySeconds,
                   .texel = before.texelSeconds,
                   .texelCpu = before.texelCpuSeconds,
                   .load = load.observed()};
  if (before.load > 0.0) now.ray *= std::max(1.0, now.load / before.load);
  const OutputEstimate e =
      estimateOutputs(scene, cameras, views, atlas.validTexels(), atlas.texelCount(), now, asked);
  OutputPlan plan = planOutputs(secondsLeft(deadline), e, early.views, asked);
  // Views that do not fit as asked are made smaller, not left out: the user of a time-limited bake sees
  // what it baked (the first view whatever the deadline: writeBake).
  if (early.views && !plan.views && !cameras.empty()) {
    const double gathers =
        (plan.probes ? e.probesSeconds : 0.0) + (plan.directional ? e.directionalSeconds : 0.0);
    plan.smallerViews = viewsThatFit(scene, cameras, views,
                                     secondsLeft(deadline) - e.filesSeconds - e.pageSeconds - gathers, now);
    plan.views = true;
    std::erase(plan.skipped, "views");
  }
  std::vector<std::string> skipped;
  for (const char* o : {"views", "probes", "directional"})
    if (std::count(early.skipped.begin(), early.skipped.end(), o) ||
        std::count(plan.skipped.begin(), plan.skipped.end(), o))
      skipped.push_back(o);
  plan.skipped = std::move(skipped);
  return plan;
}

// The glb and the "cell" channel keep the cells baked with (the scene's own for a global bake); a scene
// without any is labelled by its automatic rooms, for the stop per cell, the per-cell figures and the
// ambient term. Their decomposition runs beside the bake's own buffers: it may take what they leave of the
// memory limit.
RoomLabels bakeRooms(const BakeSettings& s, const BakeInput& in, Clock::time_point deadline,
                     const CpuShare& load, Context& ctx) {
  const CellGraph& cells = *in.cells;
  if (!cells.empty() && !cells.definedByVolumes()) return {};
  ctx.progress("set-up", 0.0, "the rooms of the texels");
  const double bakeBytes = bakeMemory(s, *in.scene, in.atlas, 0.0).total();
  const double limit = double(s.cells.decompose.memoryLimit);
  const uint64_t roomsMemory = limit <= 0.0 ? 0 : (limit > bakeBytes ? uint64_t(limit - bakeBytes) : 1);
  return labelTexelsByRoom(*in.scene, s.input.scene, in.atlas, ctx, cells, deadline, roomsMemory,
                           load.ratio());
}

}  // namespace

BakeResult bakeLoaded(const BakeSettings& settings, BakeInput& in, const BakeRun& run, Context& ctx,
                      const std::filesystem::path* gatherPlan) {
  const std::vector<Camera> cameras = expectedCameras(*in.scene, *in.cells);
  // --max-memory before anything is laid out or written: the texel budget lowered to fit, or one line.
  const BakeSettings s = withinMemory(settings, *in.scene, cameras, ctx);
  const Clock::time_point deadline = deadlineOf(s, run.start);
  // The share of a core this bake gets, from its start (its loading included) as it goes.
  const CpuShare load(run.clocks, run.cpuAtStart);
  std::optional<OutputDir> out;
  if (!s.output.folder.empty()) out.emplace(s.output.folder, kLightmapResultNames);
  BakeEngines engines(s.solver.backend, s.solver.indirect, run.gl, ctx);
  if (gatherPlan) usePlannedDensities(s, in, *gatherPlan);
  // The outputs' share of the time limit is kept back from every stage that can stop early: for the pilot
  // estimated at the texel budget (and the pilot given a share of the rest), for the solve at the atlas
  // laid out.
  const bool limited = deadline != Clock::time_point::max();
  // Measured as the machine runs now, and again before the solve: the load moves in minutes.
  const auto measureCosts = [&] {
    auto t = ctx.time("time probes");
    return MachineCosts{.ray = limited ? probeRaySeconds(*in.scene) : 0.0,
                        .texel = limited ? probeTexelSeconds() : 0.0,
                        .texelCpu = limited ? probeTexelCpuSeconds() : 0.0,
                        .load = load.observed()};
  };
  const MachineCosts costs = measureCosts();
  const size_t budget = s.atlas.densityAuto ? s.atlas.autoDensity.maxTexels : 0;
  // The least: the least layout (a stopped one falls back to) and its files and page, against the time
  // the loading left when it was read here (else the whole limit).
  LeastBake least = leastBake(s, *in.scene, costs, load);
  least.spentSeconds = in.loadedHere ? s.limits.timeLimit - secondsLeft(deadline) : 0.0;
  requireTimeForMinimum(s.limits.timeLimit, least);
  const Clock::time_point beforeOutputs =
      keepBack(deadline, outputsKeptBack(s, estimateOutputs(*in.scene, cameras, s.output.views, budget,
                                                            budget, costs, s.output.engine)));
  // The pilot shoots before the layout; else the engines wait until the atlas fits the memory. A layout
  // still going when only the outputs' time and the least layout's are left is laid out again coarser, at
  // the scale its own measured rate fits in what is left (bake_steps.cpp, coarsenToFit).
  AtlasLimits atlasLimits{.pilot = pilotDeadline(beforeOutputs),
                          .layout = keepBack(beforeOutputs, least.layoutSeconds),
                          .end = deadline,
                          .outputsSeconds = {}};
  if (limited)
    atlasLimits.outputsSeconds = [&](size_t texels) {
      const OutputEstimate e = estimateOutputs(
          *in.scene, {}, s.output.views, texels, texels,
          MachineCosts{
              .ray = costs.ray, .texel = costs.texel, .texelCpu = costs.texelCpu, .load = load.observed()});
      return e.filesSeconds + e.pageSeconds;
    };
  buildBakeAtlas(s, in,
                 s.atlas.densityAuto && in.triangleDensity.empty() ? &engines.engines().lamps : nullptr, ctx,
                 atlasLimits);
  requireSolveMemory(s, in.atlas);  // the solve alone, named by its own parameters first
  requireSceneUVs(*in.scene, in.atlas, s.output.engine.uv, s.output.engine.perObject);  // before the solve
  const ViewParams views = requireBakeMemory(s, *in.scene, cameras, in.atlas, ctx);
  const OutputEstimate outputs = estimateOutputs(*in.scene, cameras, views, in.atlas.validTexels(),
                                                 in.atlas.texelCount(), measureCosts(), s.output.engine);
  // Every optional output's time is kept back from the solve, even when the end will leave it out: the
  // house's views (30 s of a 60 s limit at load 30), given to the solve, let its engine's set-up start,
  // which cannot stop and ran 99 s (bench/RESULTS.md, "Never past --time-limit on a loaded machine").
  OutputPlan asked;  // every optional output asked for, planned again after the solve
  asked.views = true, asked.probes = s.output.engine.probes, asked.directional = s.output.engine.directional;
  const Clock::time_point solveDeadline = keepBack(deadline, outputsKeptBack(s, outputs));
  requireConvergence(s, *in.scene, in.atlas);
  if (run.sized) {
    BakeMemory memory = bakeMemory(s, *in.scene, in.atlas, largestViewBytes(cameras, views));
    memory.layout = double(in.laidOutTexels) * kLayoutBytesPerTexel;
    run.sized(bakeSizeLine(s, in, memory.total()));
  }
  const CellGraph& cells = *in.cells;
  const RoomLabels rooms = bakeRooms(s, in, solveDeadline, load, ctx);
  const CellGraph& texelGraph = rooms.graph.empty() ? cells : rooms.graph;
  const ExrChannel texelCells = rooms.graph.empty() ? cellChannel(in.atlas, *in.scene, cells) : rooms.channel;
  const AmbientTransfer transfer = bakeAmbientTransfer(s, in, texelGraph, texelCells, ctx);
  const SolveInput x{texelGraph, texelCells, transfer, engines.engines(), solveDeadline, gatherPlan, load};
  std::optional<TwoLevelData> levels;
  SolveResult r = solveBake(s, in, x, ctx, levels);
  BakeFigures f;
  if (!r.residual.empty())
    f.ambientShares =
        ambientShares(in.atlas, r.residual, texelCells.values, texelGraph, r.radiosity, &transfer);
  f.cellNames = cellNames(texelGraph);
  f.ambientEscape = escapeShares(transfer);
  f.ambient = addBakeAmbient(s, in, x, r);
  // The loop's bound on the stop per room (radiosity/solve/progressive_loop.h) stopped it: say which rooms
  // stayed above their share.
  if (r.stopBounded) ctx.warn(roomsAboveShare(f.ambientShares, f.cellNames, s.solver.ambientShare));
  if (r.timedOut) ctx.warn(stoppedEarlyNote(s, r));
  const std::pair<const char*, double> totals[] = {{"emitted", r.energy.emitted},
                                                   {"shot", r.energy.shot},
                                                   {"received", r.energy.received},
                                                   {"absorbed", r.energy.absorbed},
                                                   {"unshot", r.energy.unshot}};
  requireFiniteResult(s.input.scene, in.atlas, r.radiosity, totals);
  writeBake(s, in, x, r, views, outputs,
            plannedOutputs(s, *in.scene, cameras, views, in.atlas, outputs, asked, load, deadline), deadline,
            out ? &*out : nullptr, f, ctx);
  f.seconds = std::chrono::duration<double>(Clock::now() - run.start).count();
  f.outputs = outputs;
  BakeResult result;
  result.report = bakeReport(s, in, r, levels, engines.gl(), engines.engines().lamps.name(), f, ctx);
  result.shots = r.shots;
  result.unshotFraction = r.unshotFraction;
  result.partial = r.timedOut || !f.skippedViews.empty() || !f.skippedOutputs.empty();
  result.seconds = f.seconds;
  if (out) {
    ctx.progress("write", 0.9, "report.json, report.html");
    writeReport(*out, result.report);
    writeBakeReportPage(*out, "bake of " + s.input.scene, result.report, *in.scene, cells, in.atlas,
                        r.radiosity);
    out->commit();
    ctx.progress("write", 1.0, "done");
  }
  result.texelCell = texelCells.values;
  result.cellNames = std::move(f.cellNames);
  result.radiosity = std::move(r.radiosity);
  result.atlas = std::move(in.atlas);
  return result;
}

}  // namespace bake_steps

BakeResult bake(const Scene& scene, const CellGraph& cells, const BakeSettings& settings, Context& ctx,
                const BakeRun& run) {
  const BakeSettings s = bake_steps::resolved(settings);
  bake_steps::BakeInput in;
  in.scene = &scene;
  in.cells = &cells;
  in.onDemand = bake_steps::resolveOnDemand(s, scene, cells);
  return bake_steps::bakeLoaded(s, in, run, ctx);
}

BakeResult bake(const BakeSettings& settings, Context& ctx, const BakeRun& run) {
  const BakeScene loaded = loadBakeScene(settings, ctx, run);
  const BakeSettings s = bake_steps::resolved(settings);
  bake_steps::BakeInput in;
  in.scene = &loaded.loaded.scene;
  in.cells = &loaded.graph;
  in.onDemand = bake_steps::resolveOnDemand(s, loaded.loaded.scene, loaded.graph);
  in.loadedHere = true;
  return bake_steps::bakeLoaded(s, in, run, ctx);
}

Context::ProgressFn bakeNotes(Context::ProgressFn inner, const BakeSettings& settings,
                              std::chrono::steady_clock::time_point start, std::shared_ptr<std::string> size,
                              std::function<void(const std::string&)> note) {
  if (!inner) return inner;
  auto said = std::make_shared<std::pair<bool, bool>>(false, false);  // size, estimate
  const bool global = settings.cells.method == BakeMethod::Global;
  return [inner, said, size, note, global, limit = settings.limits.timeLimit, start](const Progress& p) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!said->first && !size->empty()) {  // said once the atlas is laid out, before the set-up
      said->first = true;
      note(*size + " (" + formatDuration(std::max(elapsed, 1.0)) + " so far)");
    }
    if (global && !said->second && p.stage == "solve" && p.shots > 0 && p.secondsLeft >= 0.0) {
      said->second = true;
      std::ostringstream line;
      line << "bake: after " << p.shots << " shots, about " << formatDuration(p.secondsLeft)
           << " more to solve";
      if (limit > 0.0 && elapsed + p.secondsLeft > limit)
        line << "; the time limit stops it in " << formatDuration(std::max(0.0, limit - elapsed))
             << " with a partial result";
      note(line.str());
    }
    inner(p);
  };
}

}  // namespace cpgi
