#include "radiosity/gpu/two_level_solve.h"

#include <algorithm>
#include <chrono>

#include "radiosity/cpu/ray_solver.h"
#include "radiosity/gpu/refined_lamp_shot.h"
#include "radiosity/lightmap/atlas_resample.h"
#include "radiosity/lightmap/contact_density.h"
#include "radiosity/lightmap/ray_scene.h"

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

// The interreflection by rays (radiosity/cpu/ray_solver.h), with the GPU solve's settings and controls.
SolveResult solveIndirectByRays(const Scene& scene, const LightmapAtlas& coarse, const SolverParams& settings,
                                const SolveControls& c, Context& ctx) {
  RaySolveParams params;
  static_cast<ShotSettings&>(params) = settings;
  const RaySolveControls controls{.priorIrradiance = c.priorShot->irradiance,
                                  .priorEmitted = c.priorShot->emitted,
                                  .readTransfer = c.readTransfer,
                                  .acceptStop = c.acceptStop,
                                  .stopRecheck = kStopRecheck,
                                  .firstShotNumber = c.firstShotNumber,
                                  .deadline = c.deadline};
  return solveByRays(scene, coarse, params, ctx, controls);
}

}  // namespace

int indirectItemBuffer(int itemBuffer, float solveDensity) {
  const int scaled = int(float(itemBuffer) * std::min(solveDensity / 10.0f, 1.0f));
  return std::clamp(scaled - scaled % 2, std::min(itemBuffer, 64), itemBuffer);
}

SolveResult solveTwoLevel(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                          const AtlasParams& atlasParams, const TwoLevelParams& levels,
                          const SolverParams& settings, const EglContext& gl, Context& ctx,
                          const SolveControls& controls, TwoLevelData* data, const CoarseSolve& solveCoarse) {
  const auto start = std::chrono::steady_clock::now();
  // The coarse atlas: its own emission is left out below (the lamps shoot on the output's).
  AtlasParams coarseParams = atlasParams;
  coarseParams.texelsPerQuad = 0;
  coarseParams.density = levels.solveDensity;
  coarseParams.minTexels = std::min(levels.minTexels, coarseParams.minTexels);
  size_t refined = 0;
  if (levels.refineContacts) {
    std::vector<float> fine = outputDensity(atlas, scene.triangles.size());
    for (float& d : fine) d = std::min(d, std::max(levels.maxContactDensity, levels.solveDensity));
    coarseParams.triangleDensity = contactDensity(scene, RayScene(scene), levels.solveDensity, fine);
    for (float d : coarseParams.triangleDensity) refined += d > levels.solveDensity;
  }
  LightmapAtlas coarse = buildAtlas(scene, quads, coarseParams, ctx);
  if (coarse.validTexels() >= atlas.validTexels()) {  // the output is as coarse already: one level
    SolveResult one = solveCoarse
                          ? solveCoarse(atlas, atlasParams, controls)  // no prior: it shoots the lamps
                          : solveProgressive(scene, atlas, settings, gl, ctx, controls);
    if (data) *data = {atlas.validTexels(), refined, 0, 0.0, one.seconds, 0, 0, settings.itemBuffer};
    return one;
  }
  const AtlasMapping mapping = mapAtlas(atlas, coarse);
  const auto lampStart = std::chrono::steady_clock::now();
  // Step 1: the lamps' shots on the output atlas, at its own texels only where their light varies.
  RefinedLampData lampData;
  SolveControls lampControls = controls;
  lampControls.acceptStop = {};  // the stop is the interreflection's, asked below
  SolveResult lit = shootLampsRefined(scene, quads, atlas, atlasParams, levels.lamps, settings, gl, ctx,
                                      lampControls, &lampData);
  const double lampSeconds = seconds(lampStart);
  if (lit.timedOut) {
    // The deadline came during the lamps' shot: what they did not shoot is unshot, and no interreflection
    // starts from it (as a prior shot, the light the lamps never sent would count as shot and escaped).
    lit.seconds = seconds(start);
    if (data)
      *data = {coarse.validTexels(),
               refined,
               lit.shots,
               lampSeconds,
               0.0,
               lampData.coarseTexels,
               lampData.refinedTexels,
               settings.itemBuffer};
    return lit;
  }

  // Step 2: the coarse atlas lit by the lamps' light averaged over its texels: the solve starts after that
  // first shot, with the emitted power of the lamps.
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
  const auto coarseStart = std::chrono::steady_clock::now();
  SolverParams indirectSettings = settings;
  indirectSettings.itemBuffer = indirectItemBuffer(settings.itemBuffer, levels.solveDensity);
  // Rays need none of what a cell solve drives the GPU solver with (lobes, bounds per patch, masks).
  const bool byRays = !solveCoarse && levels.indirectByRays && !c.directionalEmission &&
                      c.minShotPower <= 0.0 && c.strongShotPower <= 0.0 && c.receivers.empty();
  SolveResult indirect = solveCoarse ? solveCoarse(coarse, coarseParams, c)
                         : byRays    ? solveIndirectByRays(scene, coarse, indirectSettings, c, ctx)
                                     : solveProgressive(scene, coarse, indirectSettings, gl, ctx, c);
  const double coarseSeconds = seconds(coarseStart);

  // Step 3: the coarse solve's own irradiance (its incident less the lamps' light it started from) back
  // onto the output texels, times their albedo; a coarse solve that returns no irradiance (a cell solve)
  // hands back its radiosity less the lamps' reflected light.
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
    if (controls.readTransfer) {
      out.incident = lit.incident;
      for (size_t t = 0; t < out.incident.size(); ++t) out.incident[t] += fineGained[t];
    }
  }
  if (controls.readTransfer && !indirect.residual.empty())
    out.residual = upsample(mapping, atlas, coarse, indirect.residual);
  out.perCell = indirect.perCell;
  out.shots = lit.shots + indirect.shots;
  out.energy = indirect.energy;
  out.energy.created += lit.energy.created;
  out.energy.worstShotGain = std::max(out.energy.worstShotGain, lit.energy.worstShotGain);
  out.unshotFraction = indirect.unshotFraction;
  out.stopChecks = indirect.stopChecks;
  out.timedOut = lit.timedOut || indirect.timedOut;
  out.shooters = lit.shooters;
  out.history = lit.history;
  out.history.insert(out.history.end(), indirect.history.begin(), indirect.history.end());
  out.setupSeconds = lit.setupSeconds + indirect.setupSeconds;
  out.seconds = seconds(start);
  if (data)
    *data = {coarse.validTexels(),
             refined,
             lit.shots,
             lampSeconds,
             coarseSeconds,
             lampData.coarseTexels,
             lampData.refinedTexels,
             indirectSettings.itemBuffer,
             byRays};
  return out;
}

}  // namespace cpgi
