#include "radiosity/solve/two_level_solve.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <optional>

#include "core/progress.h"
#include "radiosity/lightmap/atlas_resample.h"
#include "radiosity/lightmap/contact_density.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/solve/auto_density.h"
#include "radiosity/solve/refined_lamp_shot.h"

namespace cpgi {

namespace {

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The output's radiosity were the coarse solve to stop at `coarseRadiosity`: the lamps' own at the
// output's texels, and what the coarse texels gained beyond the lamps' light they started from (ρ × the
// direct light there), interpolated.
std::vector<glm::vec3> outputRadiosity(const AtlasMapping& mapping, const LightmapAtlas& atlas,
                                       const LightmapAtlas& coarse,
                                       const std::vector<glm::vec3>& lampRadiosity,
                                       const std::vector<glm::vec3>& direct,
                                       const std::vector<glm::vec3>& coarseRadiosity) {
  std::vector<glm::vec3> gained = coarseRadiosity;
  for (size_t t = 0; t < gained.size(); ++t) gained[t] -= coarse.albedo[t] * direct[t];
  std::vector<glm::vec3> out = upsample(mapping, atlas, coarse, gained);
  for (size_t t = 0; t < out.size(); ++t) out[t] += lampRadiosity[t];
  return out;
}

// The coarse solve's own irradiance (its incident less the lamps' light it started from) back onto the
// output texels, times their albedo, over the lamps' own light there; a coarse solve that returns no
// irradiance (a cell solve) hands back its radiosity less the lamps' reflected light.
SolveResult lightOnOutput(const AtlasMapping& mapping, const LightmapAtlas& atlas,
                          const LightmapAtlas& coarse, const SolveResult& lit,
                          const std::vector<glm::vec3>& direct, const SolveResult& indirect,
                          bool readTransfer) {
  SolveResult out;
  if (indirect.incident.empty()) {
    out.radiosity = outputRadiosity(mapping, atlas, coarse, lit.radiosity, direct, indirect.radiosity);
  } else {
    std::vector<glm::vec3> gained = indirect.incident;
    for (size_t t = 0; t < gained.size(); ++t) gained[t] -= direct[t];
    const std::vector<glm::vec3> fineGained = upsample(mapping, atlas, coarse, gained);
    out.radiosity = lit.radiosity;
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (atlas.patch[t] >= 0) out.radiosity[t] += atlas.albedo[t] * fineGained[t];
    if (readTransfer) {
      out.incident = lit.incident;
      for (size_t t = 0; t < out.incident.size(); ++t) out.incident[t] += fineGained[t];
    }
  }
  if (readTransfer && !indirect.residual.empty())
    out.residual = upsample(mapping, atlas, coarse, indirect.residual);
  return out;
}

// The coarse atlas of `params`, within `maxTexels` valid texels (0: any): over it, every density scaled by
// the square root of budget / texels, first by the area (a large level's atlas at the density asked takes
// seconds to lay out), then by the atlas built, twice at most (the charts' fewest texels do not scale).
LightmapAtlas coarseAtlas(const Scene& scene, const QuadSet& quads, AtlasParams& params, size_t maxTexels,
                          std::chrono::steady_clock::time_point deadline, Context& ctx) {
  auto scale = [&](double f) {
    params.density *= float(f);
    for (float& d : params.triangleDensity) d *= float(f);
  };
  const double byArea = texelsByArea(scene, params.triangleDensity, params.density);
  if (maxTexels > 0 && byArea > double(maxTexels)) scale(std::sqrt(double(maxTexels) / byArea));
  LightmapAtlas coarse = buildAtlas(scene, quads, params, ctx);
  // Past the deadline no shot runs on it: not laid out again.
  for (int k = 0; k < 2 && maxTexels > 0 && coarse.validTexels() > maxTexels &&
                  std::chrono::steady_clock::now() < deadline;
       ++k) {
    scale(std::sqrt(double(maxTexels) / double(coarse.validTexels())));
    coarse = buildAtlas(scene, quads, params, ctx);
  }
  return coarse;
}

// Per coarse texel, the cell (`texelCell`, per output texel) of most of the output area that falls in it
// (the no-cell entry, the largest, where none does): the stop per room's cells on the coarse solve.
std::vector<int> coarseCells(const AtlasMapping& mapping, const LightmapAtlas& atlas,
                             const LightmapAtlas& coarse, const std::vector<int>& texelCell) {
  std::vector<std::map<int, double>> area(coarse.texelCount());
  int none = 0;
  for (size_t i = 0; i < texelCell.size(); ++i) {
    none = std::max(none, texelCell[i]);
    const int64_t t = mapping.coarseTexel[i];
    if (t >= 0 && size_t(t) < area.size()) area[size_t(t)][texelCell[i]] += atlas.area[i];
  }
  std::vector<int> cells(coarse.texelCount(), none);
  for (size_t t = 0; t < area.size(); ++t) {
    double most = -1.0;
    for (const auto& [cell, a] : area[t])
      if (a > most) most = a, cells[t] = cell;
  }
  return cells;
}

// The stop per room on the coarse solve: the cells of its texels, and the cells' light from its radiosity
// and residual brought onto the output atlas, as its acceptStop is asked. Holds references to the rest.
RoomStopView coarseRoomStop(const RoomStopView& output, const AtlasMapping& mapping,
                            const LightmapAtlas& atlas, const LightmapAtlas& coarse,
                            const std::vector<glm::vec3>& litRadiosity,
                            const std::vector<glm::vec3>& direct) {
  RoomStopView view = output;
  view.texelCell = coarseCells(mapping, atlas, coarse, output.texelCell);
  view.cellLight = [&output, &mapping, &atlas, &coarse, &litRadiosity, &direct](
                       const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) {
    return output.cellLight(outputRadiosity(mapping, atlas, coarse, litRadiosity, direct, radiosity),
                            upsample(mapping, atlas, coarse, residual));
  };
  return view;
}

// The interreflection's set-up against the deadline: its estimate (wall seconds at the load observed) and
// whether it is too late to start it.
struct SetupCheck {
  bool late = false, notStarted = false;
  double estimate = 0.0, load = 1.0;
  void check(const SolveControls& controls, const SetupWork& work) {
    if (std::chrono::steady_clock::now() >= controls.deadline) {  // the deadline itself: no estimate to blame
      late = true;
      return;
    }
    load = controls.load ? std::max(1.0, controls.load()) : 1.0;
    estimate = setupCpuSeconds(work) * load;
    const auto end =
        std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                               std::chrono::duration<double>(estimate));
    if (controls.deadline != std::chrono::steady_clock::time_point::max() && end >= controls.deadline)
      late = notStarted = true;
  }
  std::string note(const std::string& engine, const SolveControls& controls) const {
    const double left =
        std::chrono::duration<double>(controls.deadline - std::chrono::steady_clock::now()).count();
    char line[300];
    std::snprintf(line, sizeof line,
                  "solve: the interreflection's set-up (its atlas and the %s engine), estimated at %.3g s at "
                  "load %.3g, would end past the time limit (%.3g s left): not started, the lamps' and the "
                  "sky's light alone",
                  engine.c_str(), estimate, load, std::max(0.0, left));
    return line;
  }
};

// The set-up's work before the coarse atlas is laid out: its texels by area at the solve density, at most
// the budget; as many patches as the output's (the same charts).
SetupWork expectedWork(const Scene& scene, const LightmapAtlas& atlas, const AtlasParams& coarseParams,
                       const TwoLevelParams& levels) {
  double texels = texelsByArea(scene, coarseParams.triangleDensity, coarseParams.density);
  if (levels.maxSolveTexels > 0) texels = std::min(texels, double(levels.maxSolveTexels));
  return {scene.triangles.size(), size_t(std::max(0.0, texels)), atlas.patches.size()};
}

// Steps 2 and 3: the interreflection on the coarse atlas, started from the lamps' light `lit` averaged
// over its texels, and its light back onto the output's texels (with `keepSides`, each from the coarse
// texels on its own side of a solid its face runs through). `figures` gets the coarse solve's.
SolveResult interreflect(const Scene& scene, const LightmapAtlas& atlas, LightmapAtlas& coarse,
                         const AtlasParams& coarseParams, bool keepSides, const SolveResult& lit,
                         const TwoLevelParams& levels, const SolverParams& settings,
                         const ShotEngines& engines, Context& ctx, const SolveControls& controls,
                         const CoarseSolve& solveCoarse, TwoLevelData& figures) {
  // Where a face runs through a solid, the coarse light of one side stays on that side's output texels.
  const std::optional<RayScene> solids =
      keepSides ? std::optional<RayScene>(std::in_place, scene) : std::nullopt;
  const AtlasMapping mapping = mapAtlas(atlas, coarse, solids ? &*solids : nullptr);
  // The coarse atlas lit by the lamps' light averaged over its texels: the solve starts after that first
  // shot, with the emitted power of the lamps.
  std::fill(coarse.emission.begin(), coarse.emission.end(), glm::vec3(0.0f));
  const std::vector<glm::vec3> direct = downsample(mapping, atlas, coarse, lit.incident);
  const PriorShot prior{.irradiance = direct, .emitted = lit.energy.emitted};
  SolveControls c = controls;
  c.readTransfer = true;
  c.priorShot = &prior;
  if (controls.acceptStop)
    c.acceptStop = [&](const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual) {
      return controls.acceptStop(outputRadiosity(mapping, atlas, coarse, lit.radiosity, direct, radiosity),
                                 upsample(mapping, atlas, coarse, residual));
    };
  if (controls.roomStop.accepts && controls.roomStop.texelCell.size() == atlas.texelCount())
    c.roomStop = coarseRoomStop(controls.roomStop, mapping, atlas, coarse, lit.radiosity, direct);
  const auto coarseStart = std::chrono::steady_clock::now();
  SolverParams indirectSettings = settings;
  indirectSettings.itemBuffer = indirectItemBuffer(settings.itemBuffer, levels.solveDensity);
  SolveResult indirect = solveCoarse
                             ? solveCoarse(coarse, coarseParams, c)
                             : solveProgressive(scene, coarse, indirectSettings, engines.reflections, ctx, c);
  figures.solveSeconds = seconds(coarseStart);
  figures.indirectItemBuffer = indirectSettings.itemBuffer;
  figures.indirectBackend = engines.reflections.name();

  // The coarse solve's light back onto the output texels.
  SolveResult out = lightOnOutput(mapping, atlas, coarse, lit, direct, indirect, controls.readTransfer);
  out.perCell = indirect.perCell;
  out.shots = lit.shots + indirect.shots;
  out.energy = indirect.energy;
  out.energy.created += lit.energy.created;
  out.energy.worstShotGain = std::max(out.energy.worstShotGain, lit.energy.worstShotGain);
  out.unshotFraction = indirect.unshotFraction;
  out.stopChecks = indirect.stopChecks;
  out.stopRefusedAt = indirect.stopRefusedAt;
  out.stopBounded = indirect.stopBounded;
  out.timedOut = lit.timedOut || indirect.timedOut;
  out.shooters = lit.shooters;
  out.history = lit.history;
  out.history.insert(out.history.end(), indirect.history.begin(), indirect.history.end());
  out.setupSeconds = lit.setupSeconds + indirect.setupSeconds;
  return out;
}

}  // namespace

int indirectItemBuffer(int itemBuffer, float solveDensity) {
  const int scaled = int(float(itemBuffer) * std::min(solveDensity / 10.0f, 1.0f));
  return std::clamp(scaled - scaled % 2, std::min(itemBuffer, 64), itemBuffer);
}

double setupCpuSeconds(const SetupWork& work) {
  // Fitted on the furnished house (36 398 triangles, 88 892 coarse texels, 18 480 patches: 1.32 CPU s, of
  // which 1.1 the engine's) and oa_dm7 (2 889 triangles, 200 460 texels: 0.40 CPU s), a little over both:
  // the wall it takes is this times the load ratio (wall × cores over CPU), which counts a set-up on both
  // cores as on one (estimated 13.8 s and 4.8 s at load 20–24, taken 10.6 and 3.9: bench/RESULTS.md).
  constexpr double kLeast = 0.05, kPerTriangle = 1e-5, kPerTexel = 2e-6, kPerPatch = 4e-5;
  return kLeast + kPerTriangle * double(work.triangles) + kPerTexel * double(work.texels) +
         kPerPatch * double(work.patches);
}

SolveResult solveTwoLevel(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                          const AtlasParams& atlasParams, const TwoLevelParams& levels,
                          const SolverParams& settings, const ShotEngines& engines, Context& ctx,
                          const SolveControls& controls, TwoLevelData* data, const CoarseSolve& solveCoarse) {
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  // The coarse atlas: its own emission is left out below (the lamps shoot on the output's).
  AtlasParams coarseParams = atlasParams;
  coarseParams.texelsPerQuad = 0;
  coarseParams.density = levels.solveDensity;
  coarseParams.minTexels = std::min(levels.minTexels, coarseParams.minTexels);
  // A coarse texel often straddles a solid its face runs through (a 20 cm reveal is one texel across) and
  // holds both sides' light: the output texels take only coarse texels they see (mapAtlas's rays).
  const bool keepSides = coarseParams.keepLightOnItsSideOfSolids;
  ctx.progress("set-up", 0.0, "the interreflection's atlas");
  size_t refined = 0;
  // Past the deadline already, or with too little time left for the set-up's estimate, the lamps' shot below
  // is all that runs (it stops at once past the deadline): no coarse atlas for it.
  SetupCheck setup{.late = std::chrono::steady_clock::now() >= controls.deadline};
  if (!setup.late) setup.check(controls, expectedWork(scene, atlas, coarseParams, levels));
  if (levels.refineContacts && !setup.late) {
    std::vector<float> fine = outputDensity(atlas, scene.triangles.size());
    for (float& d : fine) d = std::min(d, std::max(levels.maxContactDensity, levels.solveDensity));
    coarseParams.triangleDensity =
        contactDensity(scene, RayScene(scene), levels.solveDensity, fine, controls.deadline);
    for (float d : coarseParams.triangleDensity) refined += d > levels.solveDensity;
  }
  LightmapAtlas coarse =
      setup.late ? LightmapAtlas{}
                 : coarseAtlas(scene, quads, coarseParams, levels.maxSolveTexels, controls.deadline, ctx);
  if (!setup.late && std::chrono::steady_clock::now() < controls.deadline &&
      coarse.validTexels() >= atlas.validTexels()) {  // the output is as coarse already: one level
    SolveResult one = solveCoarse
                          ? solveCoarse(atlas, atlasParams, controls)  // no prior: it shoots the lamps
                          : solveProgressive(scene, atlas, settings, engines.lamps, ctx, controls);
    if (data) {
      *data = TwoLevelData{};
      data->solveTexels = atlas.validTexels(), data->refinedTriangles = refined;
      data->solveSeconds = one.seconds, data->indirectItemBuffer = settings.itemBuffer;
    }
    return one;
  }
  const double atlasSeconds = seconds(start);
  const double atlasCpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const auto lampStart = std::chrono::steady_clock::now();
  // Step 1: the lamps' shots on the output atlas, at its own texels only where their light varies.
  RefinedLampData lampData;
  SolveControls lampControls = controls;
  lampControls.acceptStop = {};  // the stop is the interreflection's, asked below
  SolveResult lit;
  {
    const ProgressStage stage(ctx, "lamps");  // the lamps' own pass, not the solve's 0 → 100 %
    lit = shootLampsRefined(scene, quads, atlas, atlasParams, levels.lamps, settings, engines.lamps, ctx,
                            lampControls, &lampData);
  }
  const double lampSeconds = seconds(lampStart);
  TwoLevelData figures;
  figures.solveTexels = coarse.validTexels(), figures.refinedTriangles = refined;
  figures.lampShots = lit.shots, figures.lampSeconds = lampSeconds;
  figures.lampCoarseTexels = lampData.coarseTexels, figures.lampRefinedTexels = lampData.refinedTexels;
  figures.indirectItemBuffer = settings.itemBuffer, figures.solveDensity = coarseParams.density;
  // The interreflection's set-up again at the coarse atlas's own work and the load now.
  if (!setup.late && !lit.timedOut)
    setup.check(controls, {scene.triangles.size(), coarse.validTexels(), coarse.patches.size()});
  if (setup.late || lit.timedOut || std::chrono::steady_clock::now() >= controls.deadline) {
    // The deadline came during the lamps' shot, or the set-up would not end by it: what they did not
    // shoot is unshot, and no interreflection starts from it (as a prior shot, the light the lamps never
    // sent would count as shot and escaped). What the lamps left reflected stays unshot.
    lit.timedOut = true;
    lit.seconds = seconds(start);
    figures.setupEstimate = setup.estimate;
    figures.setupSeconds = atlasSeconds;
    figures.setupCpuSeconds = atlasCpuSeconds;
    figures.setupStop = "not started";
    if (setup.notStarted) ctx.warn(setup.note(engines.reflections.name(), controls));
    if (data) *data = figures;
    return lit;
  }
  const double engineCpuBefore = ctx.totalSeconds("solve: setup (cpu)");
  SolveResult out = interreflect(scene, atlas, coarse, coarseParams, keepSides, lit, levels, settings,
                                 engines, ctx, controls, solveCoarse, figures);
  out.seconds = seconds(start);
  figures.setupEstimate = setup.estimate;
  figures.setupSeconds = atlasSeconds + out.setupSeconds - lit.setupSeconds;
  figures.setupCpuSeconds = atlasCpuSeconds + ctx.totalSeconds("solve: setup (cpu)") - engineCpuBefore;
  figures.setupStop = out.timedOut && out.shots == lit.shots ? "stopped" : "";
  if (data) *data = figures;
  return out;
}

}  // namespace cpgi
