#include "radiosity/cpu/ray_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"

namespace cpgi {
namespace {

// Whether a shot culls its receivers (occluder_cull.h). A test is one to three single rays that find the
// nearest hit; a segment it leaves out is one ray of a coherent stream that stops at any hit. From the
// furnished house (9.4 segments left out per test: 63.2 s for 1 500 shots culled, 55.4 s not) and
// oa_dm4 (19.7: 24.9 s against 29.3 s), a test costs about 14 segments. So the cull runs while the shots
// that tried it lately left out at least kPays segments per test (sums decaying by kKeep a shot); while
// they did not, one shot in kProbe tries it again. Shots vary: a rule on each shot alone turned the cull
// off after every poor one, and oa_dm4's bake took 225 s in its interreflection against 183 s culling
// always.
class CullControl {
 public:
  bool next() {
    ++shot_;
    return saved_ >= kPays * tests_ || shot_ % kProbe == 0;
  }
  void measured(const RayShotGain& g) {
    if (g.cullTests == 0) return;
    tests_ = kKeep * tests_ + double(g.cullTests);
    saved_ = kKeep * saved_ + double(g.cullSaved);
  }

 private:
  static constexpr double kPays = 10.0, kKeep = 0.9;
  static constexpr int kProbe = 8;
  double tests_ = 0.0, saved_ = 0.0;
  uint64_t shot_ = 0;
};

double channelSum(const glm::vec3& v) {
  return double(v.r) + double(v.g) + double(v.b);
}

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The solve's per-texel state over the atlas: radiosity, unshot residual, irradiance received.
struct RayState {
  std::vector<glm::vec3> radiosity, residual, incident;
};

}  // namespace

SolveResult solveByRays(const Scene& scene, const LightmapAtlas& atlas, const RaySolveParams& params,
                        Context& ctx, const RaySolveControls& controls) {
  if (!(params.unshotFraction > 0.0 && params.unshotFraction < 1.0) || params.maxShots < 1 ||
      params.farField < 1.0f || params.coverageRays < 1 || params.eyesPerRegion < 1 ||
      params.strongEyesPerRegion < 1)
    throw InputError("solver", "the ray solver's settings are out of range");
  if (!controls.priorIrradiance.empty() && controls.priorIrradiance.size() != atlas.texelCount())
    throw InputError("solver", "a prior shot needs one irradiance per atlas texel");
  const auto start = std::chrono::steady_clock::now();
  SolveResult result;
  result.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  if (atlas.patches.empty()) return result;

  const RayScene rays(scene);
  const RayShotScene shots(scene, atlas, rays);
  const std::vector<ShooterLayout> layouts =
      layoutShooters(scene, atlas, {params.regionSize, params.maxRegions});
  const int strongRegions = params.strongShotRegions > 0 ? params.strongShotRegions : params.maxRegions;
  const std::vector<ShooterLayout> strongLayouts =
      strongRegions == params.maxRegions ? std::vector<ShooterLayout>{}
                                         : layoutShooters(scene, atlas, {params.regionSize, strongRegions});
  result.setupSeconds = secondsSince(start);
  ctx.addTiming("solve: setup", result.setupSeconds);

  RayState st;
  st.radiosity.assign(atlas.texelCount(), glm::vec3(0.0f));
  st.residual = st.incident = st.radiosity;
  EnergyTotals e;
  double reflected = 0.0;
  for (uint32_t t : shots.texels) {
    glm::vec3 b = atlas.emission[t];
    if (!controls.priorIrradiance.empty()) {
      st.incident[t] = controls.priorIrradiance[t];
      const glm::vec3 r = atlas.albedo[t] * st.incident[t];
      reflected += channelSum(r) * atlas.area[t];
      b += r;
      e.received += channelSum(st.incident[t]) * atlas.area[t];
      e.absorbed += channelSum((glm::vec3(1.0f) - atlas.albedo[t]) * st.incident[t]) * atlas.area[t];
    }
    st.radiosity[t] = st.residual[t] = b;
    e.unshot += channelSum(b) * atlas.area[t];
  }
  e.emitted = e.unshot;
  if (!controls.priorIrradiance.empty()) {  // the prior's power was emitted and shot
    e.shot = controls.priorEmitted;
    e.emitted += e.shot - reflected;
  }
  result.history.push_back(e);

  std::vector<double> patchPower(atlas.patches.size(), 0.0);
  auto measurePatches = [&] {
    tbb::parallel_for(size_t(0), patchPower.size(), [&](size_t p) {
      double sum = 0.0;
      for (uint32_t t : shots.patchTexels[p]) sum += channelSum(st.residual[t]) * atlas.area[t];
      patchPower[p] = sum;
    });
  };
  measurePatches();
  // The stop as the GPU solver's: the unshot power against the emitted, or the light the surfaces
  // reflect when that is less.
  auto unshotShare = [&e] {
    const double scale = std::min(e.emitted, e.received - e.absorbed);
    return scale > 0.0 ? e.unshot / scale : 1.0;
  };
  const double strongAt = params.strongShotFraction * e.emitted;
  const RayShotParams shotParams{params.farField, params.coverageRays, params.eyesPerRegion},
      strongShotParams{params.farField, params.coverageRays, params.strongEyesPerRegion};
  double stopAt = params.unshotFraction, lastReport = -1.0;
  CullControl cull;
  ctx.progress("solve", 0.0, "shots 0 (by rays)");
  const auto shootStart = std::chrono::steady_clock::now();
  while (e.emitted > 0.0 && result.shots < params.maxShots) {
    const size_t shooter =
        size_t(std::max_element(patchPower.begin(), patchPower.end()) - patchPower.begin());
    const double shotPower = patchPower[shooter];
    if (!(shotPower > 0.0)) break;
    if (unshotShare() <= stopAt) {
      if (!controls.acceptStop) break;
      ++result.stopChecks;
      if (controls.acceptStop(st.radiosity, st.residual)) break;
      stopAt = unshotShare() * controls.stopRecheck;
    }
    if (std::chrono::steady_clock::now() >= controls.deadline) {
      result.timedOut = true;
      break;
    }
    const bool strong = shotPower >= strongAt && !strongLayouts.empty();
    const ShooterLayout& layout = (strong ? strongLayouts : layouts)[shooter];
    RayShotParams shot = shotPower >= strongAt ? strongShotParams : shotParams;
    shot.cull = cull.next();
    const RayShotGain gain = shootByRays(shots, int(shooter), layout, st.residual,
                                         controls.firstShotNumber + uint32_t(result.shots) + 1, shot);
    cull.measured(gain);
    // What the shot delivers: what it gathered, scaled to what its eyes saw covered where they see no
    // open space, and never more than its power (gpu_solver.cpp gives the reasons and tolerances).
    constexpr double kTolerance = 2e-3;
    const double target = gain.open < 1e-3
                              ? shotPower * std::min(gain.covered, 1.0)
                              : std::min(gain.gathered, shotPower * std::min(gain.covered + gain.open, 1.0));
    double scale = 1.0;
    if (gain.gathered > 0.0 &&
        (gain.gathered - target > 1e-5 * shotPower || target - gain.gathered > kTolerance * shotPower))
      scale = target / gain.gathered;
    e.worstShotGain = std::max(e.worstShotGain, gain.gathered / shotPower);
    double received = 0.0, absorbed = 0.0, reflectedNow = 0.0;
    for (size_t k = 0; k < shots.texels.size(); ++k) {
      const glm::vec3 g = gain.irradiance[k] * float(scale);
      if (g == glm::vec3(0.0f)) continue;
      const uint32_t t = shots.texels[k];
      const glm::vec3 r = atlas.albedo[t] * g;
      st.incident[t] += g, st.radiosity[t] += r, st.residual[t] += r;
      received += channelSum(g) * atlas.area[t];
      absorbed += channelSum(g - r) * atlas.area[t];
      reflectedNow += channelSum(r) * atlas.area[t];
    }
    for (uint32_t t : shots.patchTexels[shooter]) st.residual[t] = glm::vec3(0.0f);
    e.shot += shotPower;
    e.received += received;
    e.absorbed += absorbed;
    if (received > shotPower * (1.0 + kTolerance)) e.created += received - shotPower;
    measurePatches();
    e.unshot = 0.0;
    for (double w : patchPower) e.unshot += w;
    ++result.shots;
    result.shooters.push_back(int(shooter));
    result.shotScales.push_back(float(scale));
    result.history.push_back(e);
    const double elapsed = secondsSince(shootStart);
    if (elapsed - lastReport > 0.25) {
      char status[96];
      std::snprintf(status, sizeof status, "shots %d, unshot %.2f%% (by rays)", result.shots,
                    100.0 * unshotShare());
      ctx.progress("solve", std::clamp(std::log(std::max(unshotShare(), 1e-12)) / std::log(stopAt), 0.0, 1.0),
                   status);
      lastReport = elapsed;
    }
  }
  result.energy = e;
  if (e.created > 1e-4 * e.emitted) {
    char note[160];
    std::snprintf(note, sizeof note, "the ray solve created %.3g W of light (%.2f%% of the emitted)",
                  e.created, 100.0 * e.created / e.emitted);
    ctx.warn(note);
  }
  result.unshotFraction = e.emitted > 0.0 ? e.unshot / e.emitted : 0.0;
  ctx.addTiming("solve: shots", secondsSince(shootStart));
  result.radiosity = std::move(st.radiosity);
  if (controls.readTransfer)
    result.incident = std::move(st.incident), result.residual = std::move(st.residual);
  result.seconds = secondsSince(start);
  return result;
}

}  // namespace cpgi
