#include "radiosity/solve/solve.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>

#include "core/error.h"
#include "radiosity/lightmap/direct_light.h"
#include "radiosity/lightmap/lamp_light.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/sky_light.h"
#include "radiosity/solve/progressive_loop.h"

namespace cpgi {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void checkControls(const LightmapAtlas& atlas, const SolveControls& controls, const ShotShape& shape,
                   const EngineFeatures& can, const std::string& engine) {
  if (!shape.directionalEmission && !shape.emissionLobes.empty())
    throw InputError("solver", "emission lobes need ShotShape::directionalEmission");
  if (!shape.receivers.empty() && shape.receivers.size() != atlas.texelCount())
    throw InputError("solver", "receivers need one flag per atlas texel");
  if (!shape.receivers.empty() && shape.patchShotScale.size() != atlas.patches.size())
    throw InputError("solver", "a solve at some receivers needs one shot scale per patch");
  if (controls.priorShot && controls.priorShot->irradiance.size() != atlas.texelCount())
    throw InputError("solver", "a prior shot needs one irradiance per atlas texel");
  if (shape.directionalEmission && !can.directionalEmission)
    throw InputError(
        "solver",
        "directional emission (directional or binned portals) needs an engine that has it, not " + engine);
  if ((!shape.receivers.empty() || shape.readLampFlags) && !can.lampShots)
    throw InputError("solver", "a lamp shot at some receivers needs the GL backend, not " + engine);
}

// The first shot on the CPU: the scene's punctual lights and sky (the one hook of KHR_lights_punctual in
// the solve), or a first shot the caller made (it covers those lights too); then the lamps by rays
// (SolverParams::lampRays), not where a caller drives the lamps' shots itself (a prior shot, some
// receivers, the lamp flags) or emits with lobes.
struct DirectStart {
  DirectLight direct;
  LampLight lamps;
  double emitted = 0.0;
  bool any = false;
};

DirectStart shootFirst(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                       const SolveControls& controls, const ShotShape& shape, Context& ctx) {
  DirectStart s;
  if (controls.priorShot) {
    s.direct.irradiance.assign(controls.priorShot->irradiance.begin(), controls.priorShot->irradiance.end());
    s.emitted = controls.priorShot->emitted;
    s.any = true;
  } else if (!scene.lights.empty() || scene.sky.lights()) {
    s.direct = shootPunctualAndSky(scene, atlas, ctx, skyDeadline(controls), controls.skyOpenings);
    s.emitted = punctualEmitted(scene.lights, s.direct.directionalLanded);
    s.any = true;
  }
  if (settings.lampRays > 0 && !controls.priorShot && shape.receivers.empty() && !shape.readLampFlags &&
      !shape.directionalEmission) {
    const std::vector<char> flagged = lampPatches(scene, atlas);
    if (std::find(flagged.begin(), flagged.end(), 1) != flagged.end()) {
      s.lamps =
          shootLampsByRays(scene, RayScene(scene), atlas, flagged, settings.lampRays, ctx, controls.deadline);
      if (s.direct.irradiance.empty()) s.direct.irradiance.assign(atlas.texelCount(), glm::vec3(0.0f));
      for (size_t i = 0; i < s.direct.irradiance.size(); ++i) s.direct.irradiance[i] += s.lamps.irradiance[i];
      s.emitted += s.lamps.emitted;
      s.any = true;
    }
  }
  return s;
}

// The first shot's light as a solve's result (no engine): the lights' power emitted and shot; the
// reflected light and any emitter the rays did not spend unshot.
SolveResult firstShotResult(const LightmapAtlas& atlas, const DirectStart& first) {
  SolveResult r;
  r.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  r.residual = r.incident = r.radiosity;
  EnergyTotals& e = r.energy;
  double reflected = 0.0, unspent = 0.0;
  for (size_t t = 0; t < atlas.texelCount(); ++t) {
    if (atlas.patch[t] < 0) continue;
    const glm::vec3 in = first.any ? first.direct.irradiance[t] : glm::vec3(0.0f);
    const bool spent = !first.lamps.shot.empty() && first.lamps.shot[size_t(atlas.patch[t])];
    const glm::vec3 kept = spent ? glm::vec3(0.0f) : atlas.emission[t];
    r.incident[t] = in;
    r.residual[t] = atlas.albedo[t] * in + kept;
    r.radiosity[t] = atlas.emission[t] + atlas.albedo[t] * in;
    const glm::dvec3 got(in), back(atlas.albedo[t] * in), own(kept);
    e.received += (got.r + got.g + got.b) * atlas.area[t];
    reflected += (back.r + back.g + back.b) * atlas.area[t];
    unspent += (own.r + own.g + own.b) * atlas.area[t];
  }
  e.shot = first.emitted;
  e.emitted = first.emitted + unspent;
  e.unshot = reflected + unspent;
  e.absorbed = e.received - reflected;
  r.history.push_back(e);
  r.unshotFraction = e.emitted > 0.0 ? e.unshot / e.emitted : 0.0;
  return r;
}

// A solve whose engine's set-up the deadline stopped: the first shot's light (the lamps' and the sky's, or
// a prior shot's) as 0 shots leave it, the rest unshot, with the per-texel fields its shape asks for
// (zero arrivals and lamp flags) so that every caller reads a whole, partial result; said in one warning.
SolveResult stoppedInSetup(const LightmapAtlas& atlas, const DirectStart& direct, const ShotShape& shape,
                           double setupSeconds, const std::string& engine, Context& ctx) {
  SolveResult late = firstShotResult(atlas, direct);
  late.timedOut = true;
  late.setupSeconds = setupSeconds;
  late.seconds = setupSeconds;
  if (shape.directionalEmission && shape.arrivalMoments)
    late.arrivals.assign(atlas.texelCount(), glm::vec4(0.0f));
  if (shape.readLampFlags) late.lampFlags.assign(atlas.texelCount(), 0);
  ctx.addTiming("solve: setup", setupSeconds);
  char line[200];
  std::snprintf(
      line, sizeof line,
      "solve: the time limit came during the %s engine's set-up (stopped after %.3g s): 0 shots of it",
      engine.c_str(), setupSeconds);
  ctx.warn(line);
  return late;
}

// Per patch of `atlas`, the cell most of its texels' area lies in (`texelCell`, per texel; -1 for a patch
// without texels): the stop per room's cells as the time estimate's patches hold them.
std::vector<int> patchCells(const LightmapAtlas& atlas, const std::vector<int>& texelCell) {
  int32_t patches = 0;
  for (int32_t p : atlas.patch) patches = std::max(patches, p + 1);
  std::vector<std::map<int, double>> area(static_cast<size_t>(patches));
  for (size_t i = 0; i < atlas.patch.size(); ++i)
    if (atlas.patch[i] >= 0) area[size_t(atlas.patch[i])][texelCell[i]] += atlas.area[i];
  std::vector<int> cells(size_t(patches), -1);
  for (size_t p = 0; p < area.size(); ++p) {
    double most = -1.0;
    for (const auto& [cell, a] : area[p])
      if (a > most) most = a, cells[p] = cell;
  }
  return cells;
}

}  // namespace

SolveResult shootFirstOnCpu(const Scene& scene, const LightmapAtlas& atlas, int lampRays, Context& ctx,
                            const SolveControls& given) {
  if (lampRays <= 0) throw InputError("solver", "the lamps' first shot on the CPU needs lamp rays > 0");
  SolverParams settings;
  settings.lampRays = lampRays;
  SolveControls controls;
  controls.deadline = given.deadline, controls.skyOpenings = given.skyOpenings;
  controls.skyTimeShare = given.skyTimeShare;
  return firstShotResult(atlas, shootFirst(scene, atlas, settings, controls, ShotShape{}, ctx));
}

SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                             ShotEngine& engine, Context& ctx, const SolveControls& controls,
                             const ShotShape& shape) {
  checkControls(atlas, controls, shape, engine.features(), engine.name());
  const DirectStart direct = shootFirst(scene, atlas, settings, controls, shape, ctx);
  FirstShot first;
  if (direct.any) first.irradiance = direct.direct.irradiance, first.emitted = direct.emitted;
  if (!direct.lamps.shot.empty()) first.spentEmitters = direct.lamps.shot;
  // Past the deadline before the engine's set-up (a minute of GL for a house's pilot on a loaded machine):
  // the first shot's light alone, as 0 shots leave it, the emitters it did not spend unshot.
  if (!controls.priorShot && shape.receivers.empty() && !shape.directionalEmission &&
      std::chrono::steady_clock::now() >= controls.deadline) {
    SolveResult late = firstShotResult(atlas, direct);
    late.timedOut = true;
    return late;
  }

  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  ctx.progress("set-up", 0.0, "the " + std::string(engine.name()) + " engine");  // tens of seconds on a house
  std::unique_ptr<ShotBackend> backend =
      engine.backend(scene, atlas, settings, shape, first, ctx, controls.deadline);
  const double setupSeconds = secondsSince(start);
  // Its CPU seconds too (every thread's), what the set-up's estimate is fitted on (two_level_solve.h).
  ctx.addTiming("solve: setup (cpu)", double(std::clock() - cpuStart) / CLOCKS_PER_SEC);
  if (!backend && !atlas.patches.empty())  // the deadline stopped the set-up: the first shot's light alone
    return stoppedInSetup(atlas, direct, shape, setupSeconds, engine.name(), ctx);
  if (!backend) {
    SolveResult empty;
    empty.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
    return empty;
  }
  ctx.addTiming("solve: setup", setupSeconds);

  LoopControls loop;
  loop.acceptStop = controls.acceptStop;
  if (controls.roomStop.texelCell.size() == atlas.texelCount()) {
    loop.roomStop = controls.roomStop;
    loop.patchCell = patchCells(atlas, controls.roomStop.texelCell);
  }
  loop.minShotPower = controls.minShotPower;
  loop.strongShotPower = shape.strongShotPower;
  loop.emittersAreLamps = shape.emittersAreLamps;
  loop.patchShotScale = shape.patchShotScale;
  loop.lobedEmission = shape.directionalEmission;
  loop.deadline = controls.deadline;
  loop.refusedStopTexelShots = controls.refusedStopTexelShots;
  SolveResult result = runProgressiveLoop(*backend, settings, loop, ctx);
  result.setupSeconds = setupSeconds;
  backend->readBack(
      {controls.readTransfer, shape.directionalEmission && shape.arrivalMoments, shape.readLampFlags}, result,
      ctx);
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace cpgi
