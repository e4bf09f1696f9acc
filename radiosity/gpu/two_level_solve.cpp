#include "radiosity/gpu/two_level_solve.h"

#include <chrono>

#include "radiosity/lightmap/atlas_resample.h"
#include "radiosity/lightmap/contact_density.h"
#include "radiosity/lightmap/direct_light.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/sky_light.h"

namespace cpgi {

namespace {

int emitterPatches(const LightmapAtlas& atlas) {
  std::vector<char> emits(atlas.patches.size(), 0);
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0 && atlas.emission[t] != glm::vec3(0.0f)) emits[size_t(atlas.patch[t])] = 1;
  int n = 0;
  for (char e : emits) n += e;
  return n;
}

// Step 1: the lamps' shots on the output atlas (emitter patches shoot before any reflector, so the first
// N shots are theirs; the punctual lights are shot inside on the CPU). What they leave is the direct light:
// `incident` its irradiance, `radiosity` E + ρ × it, `residual` the light still to reflect.
SolveResult shootLamps(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                       const EglContext& gl, Context& ctx, const SolveControls& controls) {
  const int emitters = emitterPatches(atlas);
  if (emitters == 0) {  // punctual lights and sky only: their exact shot is the whole first step
    SolveResult r;
    const DirectLight d = shootPunctualAndSky(scene, atlas, ctx);
    r.incident = d.irradiance;
    r.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
    r.residual.assign(atlas.texelCount(), glm::vec3(0.0f));
    for (size_t t = 0; t < atlas.texelCount(); ++t)
      if (atlas.patch[t] >= 0) {
        r.residual[t] = atlas.albedo[t] * d.irradiance[t];
        r.radiosity[t] = atlas.emission[t] + r.residual[t];
      }
    r.energy.emitted = r.energy.shot = punctualEmitted(scene.lights, d.directionalLanded);
    return r;
  }
  SolverParams lamps = settings;
  lamps.maxShots = emitters;
  lamps.unshotFraction = 1e-12;  // every lamp shoots, whatever the stop
  SolveControls c = controls;
  c.readTransfer = true;
  c.minShotPower = 0.0;
  return solveProgressive(scene, atlas, lamps, gl, ctx, c);
}

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

SolveResult solveTwoLevel(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                          const AtlasParams& atlasParams, const TwoLevelParams& levels,
                          const SolverParams& settings, const EglContext& gl, Context& ctx,
                          const SolveControls& controls, TwoLevelData* data) {
  const auto start = std::chrono::steady_clock::now();
  // The coarse atlas: its own emission is left out below (the lamps shoot on the output's).
  AtlasParams coarseParams = atlasParams;
  coarseParams.texelsPerQuad = 0;
  coarseParams.density = levels.solveDensity;
  size_t refined = 0;
  if (levels.refineContacts) {
    const std::vector<float> fine = outputDensity(atlas, scene.triangles.size());
    coarseParams.triangleDensity = contactDensity(scene, RayScene(scene), levels.solveDensity, fine);
    for (float d : coarseParams.triangleDensity) refined += d > levels.solveDensity;
  }
  LightmapAtlas coarse = buildAtlas(scene, quads, coarseParams, ctx);
  if (coarse.validTexels() >= atlas.validTexels()) {  // the output is as coarse already: one level
    SolveResult one = solveProgressive(scene, atlas, settings, gl, ctx, controls);
    if (data) *data = {atlas.validTexels(), refined, 0, 0.0, one.seconds};
    return one;
  }
  const AtlasMapping mapping = mapAtlas(atlas, coarse);
  const auto lampStart = std::chrono::steady_clock::now();
  SolveResult lit = shootLamps(scene, atlas, settings, gl, ctx, controls);
  const double lampSeconds = seconds(lampStart);

  // Step 2: the coarse atlas lit by the lamps' light averaged over its texels: the solve starts after that
  // first shot, with the emitted power of the lamps.
  std::fill(coarse.emission.begin(), coarse.emission.end(), glm::vec3(0.0f));
  const std::vector<glm::vec3> direct = downsample(mapping, atlas, coarse, lit.incident);
  const PriorShot prior{.irradiance = direct, .emitted = lit.energy.emitted};
  SolveControls c = controls;
  c.readTransfer = true;
  c.priorShot = &prior;
  const auto coarseStart = std::chrono::steady_clock::now();
  SolveResult indirect = solveProgressive(scene, coarse, settings, gl, ctx, c);
  const double coarseSeconds = seconds(coarseStart);

  // Step 3: the coarse solve's own irradiance (its incident less the lamps' light it started from) back
  // onto the output texels.
  std::vector<glm::vec3> gained = indirect.incident;
  for (size_t t = 0; t < gained.size(); ++t) gained[t] -= direct[t];
  const std::vector<glm::vec3> fineGained = upsample(mapping, atlas, coarse, gained);
  SolveResult out;
  out.radiosity = lit.radiosity;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0) out.radiosity[t] += atlas.albedo[t] * fineGained[t];
  if (controls.readTransfer) {
    out.incident = lit.incident;
    for (size_t t = 0; t < out.incident.size(); ++t) out.incident[t] += fineGained[t];
    out.residual = upsample(mapping, atlas, coarse, indirect.residual);
  }
  out.shots = lit.shots + indirect.shots;
  out.energy = indirect.energy;
  out.energy.created += lit.energy.created;
  out.energy.worstShotGain = std::max(out.energy.worstShotGain, lit.energy.worstShotGain);
  out.unshotFraction = indirect.unshotFraction;
  out.timedOut = lit.timedOut || indirect.timedOut;
  out.shooters = lit.shooters;
  out.history = lit.history;
  out.history.insert(out.history.end(), indirect.history.begin(), indirect.history.end());
  out.setupSeconds = lit.setupSeconds + indirect.setupSeconds;
  out.seconds = seconds(start);
  if (data) *data = {coarse.validTexels(), refined, lit.shots, lampSeconds, coarseSeconds};
  return out;
}

}  // namespace cpgi
