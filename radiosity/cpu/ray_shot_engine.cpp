#include "radiosity/cpu/ray_shot_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "radiosity/cpu/ray_shot.h"
#include "radiosity/cpu/shooter_clusters.h"
#include "radiosity/lightmap/ray_scene.h"
#include "radiosity/lightmap/shooter_layout.h"
#include "radiosity/solve/shot_backend.h"

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

// The progressive loop's shots by rays (shot_backend.h): the atlas's state in memory, the next shooter the
// patch of largest unshot power, each shot's gather held until the loop has scaled it.
class RayShotBackend final : public ShotBackend {
 public:
  RayShotBackend(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& params,
                 const FirstShot& first, const ShotShape& shape)
      : atlas_(atlas),
        first_(first),
        scene_(scene),
        rays_(scene),
        shots_(scene, atlas, rays_),
        shotParams_{params.farField, params.coverageRays, params.eyesPerRegion},
        strongShotParams_{params.farField, params.coverageRays, params.strongEyesPerRegion},
        emission_{shape.directionalEmission ? shape.emissionLobes : std::span<const glm::vec4>{},
                  shape.emissionBins, shape.directionalEmission && shape.arrivalMoments},
        openings_(shape.openingPatches.begin(), shape.openingPatches.end()),
        openingPoints_(shape.openingPoints),
        firstShotNumber_(shape.firstShotNumber) {}

  // The shooters' layouts (most of the set-up: a second of CPU on a furnished house, minutes of wall at load
  // 30 before the triangles were binned), stopped between batches of patches at `deadline`: false then.
  bool layOut(const SolverParams& params, Context& ctx, std::chrono::steady_clock::time_point deadline) {
    ctx.progress("set-up", 0.25, "the rays engine: the shooters' eyes");
    layouts_ = layoutShooters(scene_, atlas_, {params.regionSize, params.maxRegions, openings_}, deadline);
    if (layouts_.size() < atlas_.patches.size()) return false;
    const int strongRegions = params.strongShotRegions > 0 ? params.strongShotRegions : params.maxRegions;
    if (strongRegions != params.maxRegions) {
      ctx.progress("set-up", 0.6, "the rays engine: the strong shots' eyes");
      strongLayouts_ =
          layoutShooters(scene_, atlas_, {params.regionSize, strongRegions, openings_}, deadline);
      if (strongLayouts_.size() < atlas_.patches.size()) return false;
    }
    // Directional shooters (the cells' portals) and the openings shoot alone: their lobes and bins are
    // per patch frame, their receivers' ends per opening.
    if (params.clusterRadius > 0.0f && emission_.lobes.empty()) {
      clusters_ = clusterShooters(atlas_, {.radius = params.clusterRadius}, openings_);
      ctx.progress("set-up", 0.8,
                   "the rays engine: " + std::to_string(atlas_.patches.size()) + " patches in " +
                       std::to_string(clusters_.members.size()) + " shooter clusters");
    }
    return std::chrono::steady_clock::now() < deadline;
  }

  // The atlas's emission unshot (less the emitters the first shot spent), plus the first shot's light (its
  // power emitted and shot; what it left reflected is unshot).
  EnergyTotals start() override {
    radiosity_.assign(atlas_.texelCount(), glm::vec3(0.0f));
    residual_ = incident_ = radiosity_;
    EnergyTotals e;
    double reflected = 0.0;
    const bool prior = !first_.irradiance.empty();
    for (uint32_t t : shots_.texels) {
      glm::vec3 b = atlas_.emission[t];
      if (prior) {
        incident_[t] = first_.irradiance[t];
        const glm::vec3 r = atlas_.albedo[t] * incident_[t];
        reflected += channelSum(r) * atlas_.area[t];
        b += r;
        e.received += channelSum(incident_[t]) * atlas_.area[t];
        e.absorbed += channelSum((glm::vec3(1.0f) - atlas_.albedo[t]) * incident_[t]) * atlas_.area[t];
      }
      radiosity_[t] = residual_[t] = b;
      if (!first_.spentEmitters.empty() && first_.spentEmitters[size_t(atlas_.patch[t])])
        residual_[t] -= atlas_.emission[t];
      e.unshot += channelSum(residual_[t]) * atlas_.area[t];
    }
    e.emitted = e.unshot;
    if (prior) {
      e.shot = first_.emitted;
      e.emitted += e.shot - reflected;
    }
    patchPower_.assign(atlas_.patches.size(), 0.0);
    measurePatches();
    sums_ = {e.unshot, e.received, e.absorbed};
    return e;
  }
  // The patch of most unshot power, with its cluster's patches that hold any (shooter_clusters.h).
  ShooterChoice next() override {
    const size_t p = size_t(std::max_element(patchPower_.begin(), patchPower_.end()) - patchPower_.begin());
    double power = p < patchPower_.size() ? patchPower_[p] : 0.0;
    if (power > 0.0 && !clusters_.members.empty())
      for (int32_t q : clusters_.members[size_t(clusters_.clusterOf[p])])
        if (size_t(q) != p) power += patchPower_[size_t(q)];
    return {int(p), power, false, power > 0.0};
  }
  ShotGathered shoot(const ShooterChoice& choice, bool strong, bool) override {
    const std::vector<ShooterLayout>& layouts = strong && !strongLayouts_.empty() ? strongLayouts_ : layouts_;
    members_.assign(1, {choice.patch, &layouts[size_t(choice.patch)]});
    if (!clusters_.members.empty())
      for (int32_t q : clusters_.members[size_t(clusters_.clusterOf[size_t(choice.patch)])])
        if (q != choice.patch && patchPower_[size_t(q)] > 0.0) members_.push_back({q, &layouts[size_t(q)]});
    RayShotParams shot = strong ? strongShotParams_ : shotParams_;
    shot.cull = cull_.next();
    shot.openings = openings_;
    shot.openingPoints = openingPoints_;
    gain_ = shootByRays(shots_, members_, residual_, firstShotNumber_ + ++shotNumber_, shot, emission_);
    if (emission_.arrivals) {  // unscaled, as the item buffers note them: only their direction is read
      if (arrivals_.empty()) arrivals_.assign(atlas_.texelCount(), glm::vec4(0.0f));
      for (size_t k = 0; k < shots_.texels.size(); ++k) arrivals_[shots_.texels[k]] += gain_.arrivals[k];
    }
    cull_.measured(gain_);
    return {gain_.gathered, gain_.covered, gain_.open};
  }
  // The receivers' unshot power grows by what they reflect, patch by patch, and the shooter's is spent:
  // summing every texel's residual again after each shot was a twentieth of a furnished house's solve.
  double deliver(float scale) override {
    double received = 0.0, absorbed = 0.0;
    for (size_t k = 0; k < shots_.texels.size(); ++k) {
      const glm::vec3 g = gain_.irradiance[k] * scale;
      if (g == glm::vec3(0.0f)) continue;
      const uint32_t t = shots_.texels[k];
      const glm::vec3 r = atlas_.albedo[t] * g;
      incident_[t] += g, radiosity_[t] += r, residual_[t] += r;
      received += channelSum(g) * atlas_.area[t];
      absorbed += channelSum(g - r) * atlas_.area[t];
      patchPower_[size_t(atlas_.patch[t])] += channelSum(r) * atlas_.area[t];
    }
    for (const ShotMember& m : members_) {
      for (uint32_t t : shots_.patchTexels[size_t(m.patch)]) residual_[t] = glm::vec3(0.0f);
      patchPower_[size_t(m.patch)] = 0.0;
    }
    sums_.received += received;
    sums_.absorbed += absorbed;
    sums_.unshot = 0.0;
    for (double w : patchPower_) sums_.unshot += w;
    return received;
  }
  TexelSums sums() const override { return sums_; }
  std::vector<glm::vec3> radiosity() override { return radiosity_; }
  std::vector<glm::vec3> residual() override { return residual_; }
  std::vector<double> patchUnshot() override { return patchPower_; }
  int shotEyes(int patch, bool strong) const override {
    const ShooterLayout& layout =
        (strong && !strongLayouts_.empty() ? strongLayouts_ : layouts_)[size_t(patch)];
    return int(layout.rects.size()) * (strong ? strongShotParams_ : shotParams_).eyesPerRegion;
  }
  void readBack(const ReadBack& what, SolveResult& result, Context&) override {
    result.radiosity = std::move(radiosity_);
    if (what.transfer) result.incident = std::move(incident_), result.residual = std::move(residual_);
    if (what.arrivals)
      result.arrivals = arrivals_.empty() ? std::vector<glm::vec4>(atlas_.texelCount(), glm::vec4(0.0f))
                                          : std::move(arrivals_);
  }

 private:
  void measurePatches() {
    tbb::parallel_for(size_t(0), patchPower_.size(), [&](size_t p) {
      double sum = 0.0;
      for (uint32_t t : shots_.patchTexels[p]) sum += channelSum(residual_[t]) * atlas_.area[t];
      patchPower_[p] = sum;
    });
  }

  const LightmapAtlas& atlas_;
  const FirstShot first_;
  const Scene& scene_;
  const RayScene rays_;
  const RayShotScene shots_;
  std::vector<ShooterLayout> layouts_;
  std::vector<ShooterLayout> strongLayouts_;  // empty when it would be layouts_
  const RayShotParams shotParams_, strongShotParams_;
  std::vector<glm::vec3> radiosity_, residual_, incident_;  // per atlas texel
  std::vector<double> patchPower_;                          // per patch, its unshot power
  TexelSums sums_;
  CullControl cull_;
  RayShotGain gain_;                 // the last shot's, until delivered
  std::vector<ShotMember> members_;  // its patches
  ShooterClusters clusters_;         // empty: every patch shoots alone
  const ShooterEmission emission_;   // ShotShape's lobes and bins
  std::vector<glm::vec4> arrivals_;  // per atlas texel, once a shot noted any
  std::vector<uint8_t> openings_;    // ShotShape::openingPatches
  int openingPoints_ = 4;            // ShotShape::openingPoints
  uint32_t firstShotNumber_ = 0;     // ShotShape::firstShotNumber
  uint32_t shotNumber_ = 0;
};

}  // namespace

std::unique_ptr<ShotBackend> RayShotEngine::backend(const Scene& scene, const LightmapAtlas& atlas,
                                                    const SolverParams& settings, const ShotShape& shape,
                                                    const FirstShot& first, Context& ctx,
                                                    std::chrono::steady_clock::time_point deadline) {
  if (!(settings.unshotFraction > 0.0 && settings.unshotFraction < 1.0) || settings.maxShots < 1 ||
      settings.farField < 1.0f || settings.coverageRays < 1 || settings.eyesPerRegion < 1 ||
      settings.strongEyesPerRegion < 1 || settings.maxRegions < 1 || settings.strongShotRegions < 0 ||
      !(settings.clusterRadius >= 0.0f))
    throw InputError("solver", "the ray solver's settings are out of range");
  if (atlas.patches.empty()) return nullptr;
  ctx.progress("set-up", 0.0, "the rays engine: the ray scene");
  auto backend = std::make_unique<RayShotBackend>(scene, atlas, settings, first, shape);
  if (!backend->layOut(settings, ctx, deadline)) return nullptr;  // the deadline came: no backend
  ctx.progress("set-up", 1.0, "the rays engine");
  return backend;
}

}  // namespace cpgi
