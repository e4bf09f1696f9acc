#include "radiosity/solve/refined_lamp_shot.h"

#include <algorithm>
#include <chrono>
#include <optional>

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

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The emitter patches' shots on `atlas` (they shoot before any reflector, so the first N shots are
// theirs; the punctual lights and the sky are shot inside on the CPU).
SolveResult shootEmitters(const Scene& scene, const LightmapAtlas& atlas, int emitters,
                          const SolverParams& settings, ShotEngine& engine, Context& ctx,
                          SolveControls controls, const ShotShape& shape = {}) {
  SolverParams lamps = settings;
  // The emitters' own shots, through item buffers: with lampRays the solver shoots the lamps by rays
  // first and then `emitters` reflectors, whose light the coarse solve shot again (seed3 two-level: the
  // lamps "shot" 676 W of 600 emitted, rooms A and B +28 % and +19 %, 74 W created).
  lamps.lampRays = 0;
  lamps.maxShots = emitters;
  lamps.unshotFraction = 1e-12;  // every lamp shoots, whatever the stop
  controls.readTransfer = true;
  controls.minShotPower = 0.0;
  return solveProgressive(scene, atlas, lamps, engine, ctx, controls, shape);
}

// Punctual lights and sky only: their exact shot is the whole first step.
SolveResult shootPunctualOnly(const Scene& scene, const LightmapAtlas& atlas, Context& ctx,
                              const SolveControls& controls) {
  SolveResult r;
  const DirectLight d = shootPunctualAndSky(scene, atlas, ctx, skyDeadline(controls), controls.skyOpenings);
  r.incident = d.irradiance;
  r.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  r.residual.assign(atlas.texelCount(), glm::vec3(0.0f));
  // The books as shootFirstOnCpu keeps them: what landed received, what the texels reflect unshot, the rest
  // absorbed (without them a bake stopped here said absorbed 0 and escaped all that was emitted).
  EnergyTotals& e = r.energy;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0) {
      r.residual[t] = atlas.albedo[t] * d.irradiance[t];
      r.radiosity[t] = atlas.emission[t] + r.residual[t];
      const glm::dvec3 got(d.irradiance[t]), back(r.residual[t]);
      e.received += (got.r + got.g + got.b) * atlas.area[t];
      e.unshot += (back.r + back.g + back.b) * atlas.area[t];
    }
  e.absorbed = e.received - e.unshot;
  e.emitted = e.shot = punctualEmitted(scene.lights, d.directionalLanded);
  r.history.push_back(e);
  r.unshotFraction = e.emitted > 0.0 ? e.unshot / e.emitted : 0.0;
  return r;
}

// The coarse shot's atlas: the output's texels per metre divided by `coarsening` on every triangle.
AtlasParams coarseLampAtlas(const LightmapAtlas& atlas, const AtlasParams& atlasParams,
                            const RefinedLampParams& p, size_t triangles) {
  AtlasParams coarse = atlasParams;
  coarse.texelsPerQuad = 0;
  coarse.density = p.minDensity;
  coarse.triangleDensity = outputDensity(atlas, triangles);
  // A triangle the output left out (zero area) has no density of its own; the coarse atlas takes any
  // positive one and leaves it out again (ctf_gate1 lit by its lamp shaders refused the bake here).
  for (float& d : coarse.triangleDensity)
    d = d > 0.0f ? std::min(d, std::max(d / p.coarsening, p.minDensity)) : p.minDensity;
  return coarse;
}

}  // namespace

SolveResult shootLampsRefined(const Scene& scene, const QuadSet& quads, const LightmapAtlas& atlas,
                              const AtlasParams& atlasParams, const RefinedLampParams& params,
                              const SolverParams& settings, ShotEngine& engine, Context& ctx,
                              const SolveControls& controls, RefinedLampData* data) {
  // The lamps by shadow rays on the CPU at every output texel, as a one-level solve shoots them
  // (SolverParams::lampRays), and on an engine without lamp shots. Through the GL item buffers, the few
  // eyes on a lamp see a door's jambs from a few points only: a room lit through a door came out 10 %
  // dark, the floor along the door 36 % (bench/RESULTS.md, "Lamps through doors at two levels").
  // Past the deadline, no engine's set-up either (a minute of GL on a loaded machine for the pilot of a
  // house): the rays' shot stops at once, its lamps unshot, the sky's first pass kept.
  const bool late = std::chrono::steady_clock::now() >= controls.deadline;
  if (settings.lampRays > 0 || !engine.features().lampShots || late) {
    const auto start = std::chrono::steady_clock::now();
    SolveResult byRays = shootFirstOnCpu(
        scene, atlas, settings.lampRays > 0 ? settings.lampRays : kLampRaysOnCpu, ctx, controls);
    if (data) *data = {0, atlas.validTexels(), 0.0, seconds(start)};
    return byRays;
  }
  const int emitters = emitterPatches(atlas);
  if (emitters == 0) {
    if (data) *data = {0, atlas.validTexels(), 0.0, 0.0};
    return shootPunctualOnly(scene, atlas, ctx, controls);
  }
  const auto start = std::chrono::steady_clock::now();
  const LightmapAtlas coarse =
      buildAtlas(scene, quads, coarseLampAtlas(atlas, atlasParams, params, scene.triangles.size()), ctx);
  if (4 * coarse.validTexels() > atlas.validTexels()) {  // not coarse enough to pay for a second shot
    SolveResult whole = shootEmitters(scene, atlas, emitters, settings, engine, ctx, controls);
    if (data) *data = {0, atlas.validTexels(), 0.0, seconds(start)};
    return whole;
  }

  // 1. The lamps on the coarse atlas, noting per texel where their light has an edge, a penumbra or the
  //    lamp near.
  SolveResult lit =
      shootEmitters(scene, coarse, emitters, settings, engine, ctx, controls, {.readLampFlags = true});
  const double coarseSeconds = seconds(start);

  // 2. The output texels that cannot take it interpolated.
  const std::optional<RayScene> solids =
      atlasParams.keepLightOnItsSideOfSolids ? std::optional<RayScene>(std::in_place, scene) : std::nullopt;
  const AtlasMapping mapping = mapAtlas(atlas, coarse, solids ? &*solids : nullptr);
  double litSum = 0.0, litArea = 0.0;
  for (size_t c = 0; c < coarse.texelCount(); ++c) {
    const float v = lit.incident[c].r + lit.incident[c].g + lit.incident[c].b;
    if (coarse.patch[c] >= 0 && v > 0.0f) litSum += double(v) * coarse.area[c], litArea += coarse.area[c];
  }
  const float floor = litArea > 0.0 ? params.floorShare * float(litSum / litArea) : 0.0f;
  // Past the deadline (the coarse shot then has no lamp flags either), none.
  const bool stopped = lit.timedOut || std::chrono::steady_clock::now() >= controls.deadline;
  const std::vector<uint8_t> refine =
      stopped ? std::vector<uint8_t>(atlas.texelCount(), 0)
              : texelsToRefine(mapping, atlas, coarse, lit.incident, lit.lampFlags, params.tolerance, floor);
  size_t refined = 0;
  for (uint8_t r : refine) refined += r;

  // 3. The lamps again on the output atlas at those texels, each shot scaled as on the coarse atlas.
  std::vector<glm::vec3> incident = upsample(mapping, atlas, coarse, lit.incident);
  const auto fineStart = std::chrono::steady_clock::now();
  if (refined > 0) {
    std::vector<float> scale(atlas.patches.size(), 1.0f);
    for (size_t s = 0; s < lit.shooters.size() && s < lit.shotScales.size(); ++s)
      scale[size_t(lit.shooters[s])] = lit.shotScales[s];
    const SolveResult fine = shootEmitters(scene, atlas, emitters, settings, engine, ctx, controls,
                                           {.receivers = refine, .patchShotScale = scale});
    // A fine shot the deadline stopped in its engine's set-up shot nothing: the coarse light stays.
    if (!(fine.timedOut && fine.shots == 0))
      for (size_t t = 0; t < incident.size(); ++t)
        if (refine[t]) incident[t] = fine.incident[t];
  }
  const double fineSeconds = seconds(fineStart);

  // 4. The books of the combined shot: what it delivered is what the texels hold, never more than shot.
  double received = 0.0;
  for (size_t t = 0; t < atlas.texelCount(); ++t)
    if (atlas.patch[t] >= 0)
      received += double(incident[t].r + incident[t].g + incident[t].b) * atlas.area[t];
  const double shot = lit.energy.shot;
  if (received > shot && received > 0.0) {
    const float down = float(shot / received);
    for (glm::vec3& e : incident) e *= down;
  }
  SolveResult out;
  out.incident = std::move(incident);
  out.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  out.residual.assign(atlas.texelCount(), glm::vec3(0.0f));
  EnergyTotals e = lit.energy;
  e.received = e.absorbed = e.unshot = 0.0;
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0) {
      out.incident[t] = glm::vec3(0.0f);
      continue;
    }
    out.residual[t] = atlas.albedo[t] * out.incident[t];
    out.radiosity[t] = atlas.emission[t] + out.residual[t];
    const glm::dvec3 in(out.incident[t]), kept(out.residual[t]);
    e.received += (in.r + in.g + in.b) * atlas.area[t];
    e.unshot += (kept.r + kept.g + kept.b) * atlas.area[t];
  }
  e.absorbed = e.received - e.unshot;
  out.energy = e;
  out.shots = lit.shots;
  out.shooters = lit.shooters;
  out.shotScales = lit.shotScales;
  out.history = lit.history;
  out.history.push_back(e);
  out.setupSeconds = lit.setupSeconds;
  out.timedOut = lit.timedOut;
  out.unshotFraction = e.emitted > 0.0 ? e.unshot / e.emitted : 0.0;
  out.seconds = seconds(start);
  if (data) *data = {coarse.validTexels(), refined, coarseSeconds, fineSeconds};
  return out;
}

}  // namespace cpgi
