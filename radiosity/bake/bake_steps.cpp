// Step 1 of a bake and the checks before its solve (bake_steps.h).
#include "radiosity/bake/bake_steps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/memory_limit.h"
#include "core/number_list.h"
#include "core/progress.h"
#include "core/sky.h"
#include "radiosity/bake/cell_source.h"
#include "radiosity/lightmap/bounce_limit.h"

namespace cpgi {

void requireLight(const LoadedScene& loaded, const std::string& scenePath, bool allowDark) {
  if (allowDark || loaded.scene.hasLight()) return;
  throw InputError(scenePath,
                   "no light in the scene (no emissive material, no KHR_lights_punctual light); light a "
                   "material with `emit` MATERIAL=W/m2, or pass `dark` for a black result");
}

BakeScene loadBakeScene(const BakeSettings& settings, Context& ctx, const BakeRun& run) {
  const BakeSettings s = bake_steps::resolved(settings);
  const bake_steps::Clock::time_point deadline = bake_steps::deadlineOf(s, run.start);
  BakeScene in;
  {
    auto t = ctx.time("load");
    ctx.progress("load", 0.0, s.input.scene);
    // A limit that passes while the scene is read leaves no time for any result: the reading stops
    // between its steps with one line (InputError "time limit").
    LoadOptions load = s.input.load;
    load.deadline = std::min(load.deadline, deadline);
    in.loaded = loadScene(s.input.scene, load);
  }
  applySky(s.sky, in.loaded.scene);
  requireLight(in.loaded, s.input.scene, s.input.allowDark);
  for (const std::string& w : in.loaded.warnings) ctx.warn(s.input.scene + ": " + w);
  if (s.cells.method == BakeMethod::Cells)
    in.graph = resolveCells(s.cells.source, s.input.scene, in.loaded, s.cells.decompose, s.input.load, ctx,
                            deadline);
  else
    in.graph = in.loaded.cells;
  return in;
}

namespace bake_steps {
namespace {

// --around's "X,Y,Z" (metres): three finite numbers, else InputError("--around", ...).
glm::vec3 aroundPoint(const std::string& text) {
  const std::vector<float> values = parseNumberList(text).value_or(std::vector<float>{});
  if (values.size() != 3 || std::count(text.begin(), text.end(), ',') != 2)
    throw InputError("--around", "'" + text + "' is not X,Y,Z (three numbers in metres)");
  return {values[0], values[1], values[2]};
}

}  // namespace

Clock::time_point deadlineOf(const BakeSettings& s, Clock::time_point start) {
  if (s.limits.timeLimit <= 0.0) return Clock::time_point::max();
  return start +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s.limits.timeLimit));
}

BakeSettings resolved(const BakeSettings& settings) {
  BakeSettings s = settings;
  const uint64_t limit = s.limits.maxMemory > 0 ? s.limits.maxMemory : defaultMemoryLimit();
  s.atlas.params.memoryLimit = limit;
  s.cells.decompose.memoryLimit = limit;  // one limit for the whole bake
  return s;
}

OnDemand resolveOnDemand(const BakeSettings& s, const Scene& scene, const CellGraph& graph) {
  OnDemand d;
  const BakeSettings::Cells& c = s.cells;
  if (c.onlyCells.empty() && c.around.empty()) return d;
  const std::string option = c.onlyCells.empty() ? "--around" : "--only-cells";
  if (c.method != BakeMethod::Cells) throw InputError(option, "needs --method cells");
  if (s.solver.solveDensity > 0.0f)
    throw InputError("--solve-density", "cell jobs and on-demand bakes solve in one level: leave it out");
  d.active = true;
  d.mode = c.boundary;
  std::vector<int> baked;
  if (!c.onlyCells.empty()) {
    baked = cellsByName(graph, c.onlyCells, "--only-cells");
  } else {
    const glm::vec3 p = aroundPoint(c.around);
    d.aroundCell = cellContaining(scene, graph, p);
    if (d.aroundCell < 0) throw InputError("--around", "the point " + c.around + " is in no cell");
    baked = cellsWithin(graph, d.aroundCell, c.depth);
  }
  d.selection = selectCells(graph, baked);
  return d;
}

namespace {

// `params` at 1/`factor` of its texels per metre (texels per quad at least 2).
AtlasParams coarser(const AtlasParams& params, int factor) {
  AtlasParams coarse = params;
  coarse.texelsPerQuad = params.texelsPerQuad > 0 ? std::max(2, params.texelsPerQuad / factor) : 0;
  coarse.density = params.density / float(factor);
  for (float& d : coarse.triangleDensity) d /= float(factor);
  return coarse;
}

// Whether the required outputs of `atlas` would not be written by limits.end with the stages before them
// (kRelayoutTimeShare of the time left).
bool tooLateFor(const LightmapAtlas& atlas, const AtlasLimits& limits) {
  return limits.outputsSeconds &&
         limits.outputsSeconds(atlas.texelCount()) > kRelayoutTimeShare * secondsLeft(limits.end);
}

// `params` laid out at 1/`factor` of its texels per metre (fitTexelBudget), its own warnings (charts capped)
// not the user's resolution's; stops at `deadline`.
LightmapAtlas laidOutCoarser(const BakeSettings& s, BakeInput& in, const AtlasParams& asked, int factor,
                             AtlasParams& params, TexelBudget& budget, Clock::time_point deadline) {
  const size_t maxTexels = s.atlas.densityAuto ? s.atlas.autoDensity.maxTexels : 0;
  Context quiet;
  params = coarser(asked, factor);
  return fitTexelBudget(*in.scene, in.quads, params, maxTexels, quiet, &budget, deadline);
}

// After a layout stopped at limits.layout (or one whose files would not be written by limits.end): the
// coarsest scale its measured cost (`cost`) says fits with its files before limits.end, laid out once with a
// deadline that keeps their time back; else, or when that one stops too, the least layout
// (1/kMostCoarsening), which runs whole. So after the first attempt at most two more, each bounded by an
// estimate or the least. `params` becomes the last used; returns the factor.
int coarsenToFit(const BakeSettings& s, BakeInput& in, AtlasParams& params, TexelBudget& budget,
                 const AtlasLimits& limits, const LayoutCost& cost, LightmapAtlas& atlas) {
  const AtlasParams asked = params;
  const std::function<double(size_t)> outputs =
      limits.outputsSeconds ? limits.outputsSeconds : [](size_t) { return 0.0; };
  const int factor = coarseningThatFits(cost, asked, secondsLeft(limits.end), outputs);
  if (factor < kMostCoarsening) {
    try {
      const Clock::time_point until = keepBack(limits.end, outputs(coarseTexels(cost, asked, factor)));
      atlas = laidOutCoarser(s, in, asked, factor, params, budget, until);
      return factor;
    } catch (const AtlasLayoutStopped&) {  // slower than measured: the least, below
    }
  }
  atlas = laidOutCoarser(s, in, asked, kMostCoarsening, params, budget, Clock::time_point::max());
  return kMostCoarsening;
}

// The output's atlas within `limits.layout` (--time-limit): past it in the middle of a layout
// (AtlasLayoutStopped), or laid out whole but with files that would not be written by limits.end, laid out
// again coarser at the scale its measured cost fits in the time left (coarsenToFit). Said in one warning;
// the solve after it stops at once and the result is written as partial.
LightmapAtlas layOutWithin(const BakeSettings& s, BakeInput& in, AtlasParams& params, TexelBudget& budget,
                           Context& ctx, const AtlasLimits& limits) {
  const size_t maxTexels = s.atlas.densityAuto ? s.atlas.autoDensity.maxTexels : 0;
  char line[300];
  LightmapAtlas atlas;
  const Clock::time_point started = Clock::now();
  try {
    atlas = fitTexelBudget(*in.scene, in.quads, params, maxTexels, ctx, &budget, limits.layout);
  } catch (const AtlasLayoutStopped& stopped) {
    in.laidOutTexels = stopped.texels;
    const int factor = coarsenToFit(s, in, params, budget, limits, stoppedLayoutCost(stopped), atlas);
    std::snprintf(line, sizeof line,
                  "atlas: the time limit came while laying out the lightmap (%zu of %zu texels filled): laid "
                  "out again at 1/%d of the texels per metre, %zu texels",
                  stopped.filledTexels, stopped.texels, factor, atlas.validTexels());
    ctx.warn(line);
    return atlas;
  }
  in.laidOutTexels = atlas.texelCount();
  if (!tooLateFor(atlas, limits)) return atlas;
  const size_t laidOut = atlas.validTexels();
  const double seconds = std::chrono::duration<double>(Clock::now() - started).count();
  const int factor = coarsenToFit(s, in, params, budget, limits,
                                  wholeLayoutCost(seconds, atlas.texelCount(), atlas.patches.size()), atlas);
  std::snprintf(line, sizeof line,
                "atlas: the lightmap's files at %zu texels would not be written by the time limit: laid out "
                "again at 1/%d of the texels per metre, %zu texels",
                laidOut, factor, atlas.validTexels());
  ctx.warn(line);
  return atlas;
}

}  // namespace

void buildBakeAtlas(const BakeSettings& s, BakeInput& in, ShotEngine* pilot, Context& ctx,
                    const AtlasLimits& limits) {
  const Clock::time_point deadline = limits.pilot;
  {
    auto t = ctx.time("atlas");
    ctx.progress("atlas", 0.0, "patches");
    in.quads = findQuads(*in.scene);
  }
  if (s.atlas.densityAuto && in.triangleDensity.empty() && Clock::now() >= deadline) {
    // No time for the pilot: its atlas, the engine's set-up and the lamps' shot would all come after the
    // limit. The output is laid out at the pilot's own even density, within the texel budget.
    const float even = pilotDensity(*in.scene, s.atlas.autoDensity);
    in.triangleDensity.assign(in.scene->triangles.size(), even);
    char line[200];
    std::snprintf(
        line, sizeof line,
        "auto density: the time limit came before the density pilot; every surface at %.2f texels a "
        "metre",
        double(even));
    ctx.warn(line);
  } else if (s.atlas.densityAuto && in.triangleDensity.empty()) {
    if (!pilot) throw std::logic_error("buildBakeAtlas: --density auto's pilot needs a shot engine");
    auto t = ctx.time("auto density");
    // The pilot's own atlas and solve report as this stage, not as the bake's solve.
    const ProgressStage stage(ctx, "auto density", "a coarse pilot solve");
    AutoDensityData data;
    in.triangleDensity =
        chooseAutoDensity(*in.scene, in.quads, s.atlas.params, s.atlas.autoDensity, s.solver.params, *pilot,
                          ctx, SolveControls{.deadline = deadline}, &data);
    in.autoDensity = data;
  }
  AtlasParams params = s.atlas.params;
  params.triangleDensity = in.triangleDensity;
  {
    auto t = ctx.time("atlas");
    ctx.progress("atlas", 0.0, "layout");
    // --density auto within its texel budget (AutoDensityParams::maxTexels): the densities scaled down to
    // fit, said in one line.
    TexelBudget budget;
    in.atlas = layOutWithin(s, in, params, budget, ctx, limits);
    if (!budget.note.empty()) ctx.warn(budget.note);
    if (!in.triangleDensity.empty()) in.triangleDensity = params.triangleDensity;
  }
  if (in.atlas.patches.empty()) throw InputError(s.input.scene, "no surface to bake");
  if (!in.scene->hasLight()) ctx.warn(s.input.scene + ": nothing emits light; the lightmap is black");
}

// The atlas was checked alone when it was built; the solve adds its item buffers: per visibility region
// (up to the larger of --regions and --strong-regions, squared) an item and a depth layer of the buffer's
// pixels (8 bytes a pixel), and half as much again for what the GL driver keeps beside them.
static double solveRegions(const BakeSettings& s) {
  return std::pow(std::max(s.solver.params.maxRegions, s.solver.params.strongShotRegions), 2);
}

double solveBytes(const BakeSettings& s, const LightmapAtlas& atlas) {
  const double edge = s.solver.params.itemBuffer;
  return double(atlas.texelCount()) * kBakeBytesPerTexel + edge * edge * solveRegions(s) * 12.0;
}

void requireSolveMemory(const BakeSettings& s, const LightmapAtlas& atlas) {
  const double regions = solveRegions(s);
  requireMemory(solveBytes(s, atlas), s.atlas.params.memoryLimit, "item buffer",
                "the solve (" + std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
                    " atlas texels, item buffers of " + std::to_string(s.solver.params.itemBuffer) +
                    "^2 pixels x " + std::to_string(int(regions)) + " regions)",
                "lower `item buffer` or raise `maximum memory`");
}

// In a closed scene of mean albedo ρ, light bounces about ln(unshot) / ln(ρ) times before the unshot
// share falls to --unshot, each bounce a round of shots over the lit patches: near ρ = 1 that is thousands
// of rounds (at 1, never), which the default --max-shots of 100,000 would let run for hours. Refused
// up front unless the caller bounded the solve (an open scene lets light escape, so an albedo of 1 there
// would converge: the message says how to go on). A dark scene has nothing to shoot.
void requireConvergence(const BakeSettings& s, const Scene& scene, const LightmapAtlas& atlas) {
  if (!s.limits.refuseEndless || s.limits.timeLimit > 0.0 || !scene.hasLight()) return;
  const BounceEstimate e = estimateBounces(atlas, s.solver.params.unshotFraction);
  if (!e.tooMany()) return;
  std::ostringstream m;
  m << e.describe() << " before `unshot fraction` " << s.solver.params.unshotFraction
    << " is unshot; lower the albedo, raise `unshot fraction`, or bound the solve with `maximum shots` N or "
       "`time limit` SECONDS";
  throw InputError(s.input.scene, m.str());
}

CellSolveParams cellSolveParams(const BakeSettings& s, const BakeInput& in) {
  CellSolveParams params = s.cells.params;
  params.maxAmbientShare = s.solver.ambientShare;
  params.solver = s.solver.params;
  params.atlas = s.atlas.params;
  params.atlas.triangleDensity = in.triangleDensity;
  return params;
}

// --solve-density auto: one level up to this many output texels. A large atlas is where two levels pay
// (fewer receiver texels and half the item buffer per shot of the interreflection): the furnished
// house's 282 000 texels baked in 37 min in one level and in 11–12 min in two at 5 texels a metre
// (bench/RESULTS.md, "The furnished house"); seed1–3 at the default density, under this, stay as they
// were.
constexpr size_t kAutoTwoLevelTexels = 100'000;

// The option's, or with auto half the output's density (at most 5 texels a metre: RESULTS.md, "Two
// levels") once the output has more than kAutoTwoLevelTexels texels; a cells bake as a global one (its
// cell jobs and on-demand bakes solve in one level: bake.cpp, solveBake).
float chosenSolveDensity(const BakeSettings& s, const LightmapAtlas& atlas) {
  const float asked = s.solver.solveDensity;
  if (asked != kAutoSolveDensity) return asked;
  constexpr float kAutoMost = 5.0f;
  // --density auto: the output is fine only where the lamps' light needs it; the bounced light never does.
  if (s.atlas.densityAuto) return kAutoMost;
  if (atlas.validTexels() <= kAutoTwoLevelTexels) return 0.0f;
  return s.atlas.params.texelsPerQuad > 0 ? kAutoMost : std::min(kAutoMost, s.atlas.params.density / 2.0f);
}

std::string bakeSizeLine(const BakeSettings& s, const BakeInput& in, double bytes) {
  std::ostringstream line;
  line << "bake: " << in.atlas.validTexels() << " texels in " << in.atlas.patches.size() << " patches ("
       << in.scene->triangles.size() << " triangles";
  if (s.cells.method == BakeMethod::Cells)
    line << ", " << in.cells->cells.size() << " cells, " << in.cells->portals.size() << " portals";
  line << "), about " << int(std::ceil(bytes / (1 << 20)))
       << " MB at most; the time is estimated from the first shots";
  if (s.limits.timeLimit > 0.0)
    line << "; --time-limit " << s.limits.timeLimit << " s stops it with a partial result";
  return line.str();
}

}  // namespace bake_steps
}  // namespace cpgi
