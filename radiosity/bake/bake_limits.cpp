// The outputs' share of --time-limit and the memory of every stage (bake_limits.h).
#include "radiosity/bake/bake_limits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>

#include <pthread.h>
#include <time.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/image_io.h"
#include "core/memory_limit.h"
#include "decomposition/voxelize.h"
#include "radiosity/bake/light_probes.h"
#include "radiosity/lightmap/ray_scene.h"

namespace cpgi::bake_steps {
namespace {

// The outputs' costs in rays of probeRaySeconds on the 2-core llvmpipe machine the bakes are benched on
// (bench/RESULTS.md, "A bake inside its limits in every stage" and "Inside --time-limit on a loaded
// machine"), with 1.4-2x to spare: a view's ray (one per supersample, with its bilinear lookup, and its share
// of the pixel's writing: 0.9 probe rays on the IFC-like house, 1.2-1.75 on oa_dm7 and oa_dm4 at load 23,
// measured with 128 k probe rays; 2.8 at light load with 16 k, which one preemption could double) and a pixel
// through its EXR and PNG; a triangle through the glb and the page.
constexpr double kRaysPerViewRay = 2.0;
constexpr double kRaysPerViewPixel = 1.0;
// An atlas texel through the files and the page, in pixels of probeTexelSeconds' PNG encoding: 10.5 of
// them on oa_dm4 at load 23 (bench/RESULTS.md, "Inside --time-limit on a loaded machine"), with 1.4x to
// spare. Counted in rays, a map's cheap rays (a seventh of a house's) gave a quarter of its files' time.
constexpr double kProbesPerFileTexel = 10.0;
// Room to spare on the CPU seconds times the observed load: the load moves within the files' seconds.
constexpr double kLoadSpare = 1.5;
constexpr double kProbesPerPageTexel = 5.0;
constexpr int kProbeEdge = 512;
// A voxel of the probes' placement (voxelize, classify, distance) in the same pixels: about 0.9 on oa_dm4
// (53 M voxels over its bounds), with room to spare.
constexpr double kProbesPerVoxel = 1.5;
// The share of the lattice over the scene's bounds that lies in its empty space, clear of the surfaces:
// a tenth on oa_dm4 (5 419 of 60 000), half in a house.
constexpr double kProbeLatticeShare = 0.5;
constexpr double kRaysPerTriangle = 10.0;
// The probes last a few hundredths of a second on an idle machine, a few tenths on a loaded one: long
// enough to span many of the scheduler's slices, so that one preemption does not make the estimate.
constexpr int kProbeRays = 1 << 17;
// A gather's ray (directional lightmap, probes): a nearest hit and the baked radiance looked up there; its
// emitter samples a shadow ray each.
constexpr double kRaysPerGatherRay = 2.0;
// A layout's wall seconds from a first attempt's rates, with room to spare: a fill stopped before its
// gutters did not price them, and the load moves.
constexpr double kLayoutSpare = 2.0;
// The least layout's CPU seconds on an idle core: its charts (found, split, packed: about one a triangle)
// and its texels filled with their gutters (bench/RESULTS.md, "Never past --time-limit when the bake gets
// 2 % of a core"), with room to spare.
constexpr double kLayoutCpuPerTriangle = 4e-6;
constexpr double kLayoutCpuPerTexel = 2e-7;

// Embree's high-quality BVH with its triangles, and RayScene's own copy of them.
constexpr double kRaySceneBytesPerTriangle = 256.0;
// The sky gather: per valid texel its index, two sums (the pass's and the last whole pass's) and the
// irradiance it adds to.
constexpr double kSkyGatherBytesPerTexel = 8.0 + 16.0 + 12.0;

// The directional gather: four SH coefficients and the gathered irradiance (RGB floats), the baked
// radiance it reads (reflected light and the emitters' chances), and the dilated copy written.
constexpr double kDirectionalBytesPerTexel = 4 * 12.0 + 12.0 + 16.0 + 12.0;

// The process whatever its atlas, on the 2-core llvmpipe machine: a random plan's bake (a 71 MB atlas and
// item buffers) peaked at 264 MB, 228 MB of it before its pilot: the GL driver's context, the time
// probes' ray scene, the program.
constexpr double kProcessBytes = 256.0 * (1 << 20);
// A scene triangle through the bake's set-up: the scene, its quads, the charts' lists, the cells' and
// the sky openings' copies, beside the ray scenes counted on their own.
constexpr double kSceneBytesPerTriangle = 1024.0;

// The probes' voxels: the decomposition's grids (decompositionBytes) over the scene's bounds at
// ProbeParams::voxel (an upper bound: voxelize trims open ground), and the baked radiance they read.
double probeBytes(const Scene& scene, size_t atlasTexels) {
  if (scene.triangles.empty()) return 0.0;
  const double voxel = ProbeParams{}.voxel;
  const Bounds b = scene.bounds();
  const glm::dvec3 size = glm::max(glm::dvec3(b.hi - b.lo), glm::dvec3(0.0));
  const double voxels = (size.x / voxel + 5.0) * (size.y / voxel + 5.0) * (size.z / voxel + 5.0);
  double area = 0.0;
  for (const Triangle& t : scene.triangles) area += double(t.area());
  return decomp::decompositionBytes(voxels, voxel, area) + double(atlasTexels) * 16.0;
}

}  // namespace

double largestViewBytes(const std::vector<Camera>& cameras, const ViewParams& views) {
  double most = 0.0;
  for (const Camera& c : cameras) most = std::max(most, viewBytes(viewSize(c, views)));
  return most;
}

std::vector<Camera> expectedCameras(const Scene& scene, const CellGraph& cells) {
  if (!scene.cameras.empty()) return scene.cameras;
  std::vector<Camera> cameras;
  for (const Cell& c : cells.cells)
    if (c.name != "outside") cameras.push_back(Camera{.name = c.name});
  if (cameras.empty()) cameras.push_back(Camera{.name = "overview"});
  return cameras;
}

double probeRaySeconds(const Scene& scene) {
  if (scene.triangles.empty()) return 0.0;
  const RayScene rays(scene);
  const auto built = std::chrono::steady_clock::now();
  glm::vec3 lo(3.0e38f), hi(-3.0e38f);
  for (const Triangle& t : scene.triangles)
    for (const glm::vec3& p : t.p) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 middle = 0.5f * (lo + hi);
  // Directions spread over the sphere (a Fibonacci lattice), as a view's rays spread over a room.
  tbb::parallel_for(tbb::blocked_range<int>(0, kProbeRays, 256), [&](const tbb::blocked_range<int>& r) {
    for (int k = r.begin(); k < r.end(); ++k) {
      const float z = 1.0f - 2.0f * (float(k) + 0.5f) / float(kProbeRays);
      const float phi = 2.39996323f * float(k), ring = std::sqrt(std::max(0.0f, 1.0f - z * z));
      rays.intersect(middle, glm::vec3(ring * std::cos(phi), ring * std::sin(phi), z));
    }
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count() / kProbeRays;
}

double probeTexelSeconds() {
  // A smooth gradient with noise in its low bits, as a lightmap compresses.
  ImageRGB image{kProbeEdge, kProbeEdge, std::vector<glm::vec3>(size_t(kProbeEdge) * kProbeEdge)};
  for (int y = 0; y < kProbeEdge; ++y)
    for (int x = 0; x < kProbeEdge; ++x)
      image.pixels[size_t(y) * kProbeEdge + x] = glm::vec3(float(x) / kProbeEdge, float(y) / kProbeEdge,
                                                           float((x * 7919 + y * 104729) % 97) / 970.0f);
  const auto start = std::chrono::steady_clock::now();
  const std::string png = encodePng(image);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return png.empty() ? 0.0 : seconds / (double(kProbeEdge) * kProbeEdge);
}

double probeTexelCpuSeconds() {
  ImageRGB image{kProbeEdge, kProbeEdge, std::vector<glm::vec3>(size_t(kProbeEdge) * kProbeEdge)};
  for (int y = 0; y < kProbeEdge; ++y)
    for (int x = 0; x < kProbeEdge; ++x)
      image.pixels[size_t(y) * kProbeEdge + x] = glm::vec3(float(x) / kProbeEdge, float(y) / kProbeEdge,
                                                           float((x * 7919 + y * 104729) % 97) / 970.0f);
  timespec a{}, b{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &a);
  const std::string png = encodePng(image);
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &b);
  const double seconds = double(b.tv_sec - a.tv_sec) + 1e-9 * double(b.tv_nsec - a.tv_nsec);
  return png.empty() ? 0.0 : seconds / (double(kProbeEdge) * kProbeEdge);
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double secondsLeft(std::chrono::steady_clock::time_point until) {
  if (until == std::chrono::steady_clock::time_point::max()) return 86400.0;
  return std::chrono::duration<double>(until - std::chrono::steady_clock::now()).count();
}

}  // namespace cpgi::bake_steps

namespace cpgi {

CpuClocks cpuClocks() {
  clockid_t thread{};
  const bool known = pthread_getcpuclockid(pthread_self(), &thread) == 0;
  return [thread, known] {
    CpuReading r{std::chrono::steady_clock::now(), bake_steps::processCpuSeconds(), -1.0};
    timespec t{};
    // The thread may have ended (a server's worker): the process's clock alone then.
    if (known && clock_gettime(thread, &t) == 0) r.thread = double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    return r;
  };
}

}  // namespace cpgi

namespace cpgi::bake_steps {

CpuShare::CpuShare(CpuClocks clocks, std::optional<CpuReading> start, int cores)
    : clocks_(std::move(clocks)),
      start_(start ? *start : clocks_()),
      cores_(cores > 0 ? cores : std::max(1, tbb::this_task_arena::max_concurrency())) {}

double CpuShare::shareBetween(const CpuReading& a, const CpuReading& b) const {
  const double wall = std::chrono::duration<double>(b.wall - a.wall).count();
  const double process = b.process - a.process;
  if (!(process >= kLeastCpuSeconds) || !(wall > 0.0)) return 0.0;
  double share = process / (wall * double(cores_));
  if (a.thread >= 0.0 && b.thread >= 0.0) share = std::max(share, (b.thread - a.thread) / wall);
  // A thousandth of a core is as far as a bake's estimates need to see.
  return std::clamp(share, 1e-3, 1.0);
}

double CpuShare::share() const {
  const CpuReading now = clocks_();
  const std::lock_guard lock(mutex_);
  const double whole = shareBetween(start_, now);
  if (whole <= 0.0) return 0.0;
  // The newest reading at least a window old starts the recent share; the older ones are not needed again.
  double recent = 0.0;
  for (auto r = readings_.rbegin(); r != readings_.rend(); ++r)
    if (std::chrono::duration<double>(now.wall - r->wall).count() >= kCpuShareWindow) {
      recent = shareBetween(*r, now);
      readings_.erase(readings_.begin(), std::prev(r.base()));
      break;
    }
  readings_.push_back(now);
  return recent > 0.0 ? std::min(whole, recent) : whole;
}

double CpuShare::ratio() const {
  const double s = share();
  return s > 0.0 ? 1.0 / s : 1.0;
}

double CpuShare::observed() const {
  const double s = share();
  return s > 0.0 ? 1.0 / s : 0.0;
}

LayoutCost stoppedLayoutCost(const AtlasLayoutStopped& stopped) {
  return LayoutCost{
      .chartSeconds = stopped.chartSeconds,
      .texelSeconds = stopped.filledTexels > 0 ? stopped.fillSeconds / double(stopped.filledTexels) : 0.0,
      .texels = stopped.texels,
      .charts = stopped.charts};
}

LayoutCost wholeLayoutCost(double seconds, size_t texels, size_t charts) {
  return LayoutCost{.chartSeconds = seconds,
                    .texelSeconds = texels > 0 ? seconds / double(texels) : 0.0,
                    .texels = texels,
                    .charts = charts};
}

size_t coarseTexels(const LayoutCost& cost, const AtlasParams& params, int factor) {
  const double least = std::pow(double(params.minTexels + 2 * params.padding), 2.0);
  return size_t(double(cost.texels) / double(factor * factor) + double(cost.charts) * least);
}

double coarseLayoutSeconds(const LayoutCost& cost, const AtlasParams& params, int factor) {
  return kLayoutSpare * (cost.chartSeconds + double(coarseTexels(cost, params, factor)) * cost.texelSeconds);
}

int coarseningThatFits(const LayoutCost& cost, const AtlasParams& params, double secondsLeft,
                       const std::function<double(size_t)>& outputsSeconds) {
  if (!(cost.texelSeconds > 0.0)) return kMostCoarsening;
  for (int factor = 2; factor < kMostCoarsening; factor *= 2)
    if (coarseLayoutSeconds(cost, params, factor) + outputsSeconds(coarseTexels(cost, params, factor)) <=
        kRelayoutTimeShare * secondsLeft)
      return factor;
  return kMostCoarsening;
}

double leastLayoutCpuSeconds(const Scene& scene, size_t texels) {
  return kLayoutCpuPerTriangle * double(scene.triangles.size()) + kLayoutCpuPerTexel * double(texels);
}

OutputPlan planOutputs(double secondsLeft, const OutputEstimate& e, bool viewsAsked,
                       const EngineOutputParams& engine) {
  OutputPlan plan;
  double left = secondsLeft - e.filesSeconds - e.pageSeconds;
  // Kept in the reverse of the order they are dropped in.
  const auto keep = [&](bool asked, double seconds, bool& kept) {
    if (!asked) return;
    kept = seconds <= left;
    if (kept) left -= seconds;
  };
  keep(engine.directional, e.directionalSeconds, plan.directional);
  keep(engine.probes, e.probesSeconds, plan.probes);
  keep(viewsAsked && e.views > 0, e.viewSeconds, plan.views);
  if (viewsAsked && e.views > 0 && !plan.views) plan.skipped.push_back("views");
  if (engine.probes && !plan.probes) plan.skipped.push_back("probes");
  if (engine.directional && !plan.directional) plan.skipped.push_back("directional");
  return plan;
}

ViewParams viewsThatFit(const Scene& scene, const std::vector<Camera>& cameras, const ViewParams& asked,
                        double seconds, const MachineCosts& costs) {
  ViewParams v = asked;
  v.supersample = 1;
  const int least = std::min(asked.width, kLimitedViewWidth);
  const auto fits = [&] { return estimateOutputs(scene, cameras, v, 0, 0, costs).viewSeconds <= seconds; };
  while (!fits() && v.width > least) {
    const int width = std::max(least, v.width * 4 / 5);
    if (v.height > 0) v.height = std::max(kMinViewEdge, int(std::lround(double(v.height) * width / v.width)));
    v.width = width;
  }
  return v;
}

void requireTimeForMinimum(double timeLimit, const LeastBake& least) {
  if (!(timeLimit > 0.0) || timeLimit - least.spentSeconds >= least.seconds) return;
  char share[80] = "";
  if (least.share > 0.0) std::snprintf(share, sizeof share, " at %.2g %% of a core", 100.0 * least.share);
  char spent[80] = "";
  if (least.spentSeconds > 0.0)
    std::snprintf(spent, sizeof spent, " after %.3g s of loading", least.spentSeconds);
  char line[480];
  std::snprintf(line, sizeof line,
                "%.3g s is less than the least a bake of this scene writes here as the machine runs now%s: "
                "about %.3g s for its least layout and its lightmap's files and report at %zu texels%s; "
                "at this load it needs at least %.3g s; raise it",
                timeLimit, share, least.seconds, least.texels, spent, least.spentSeconds + least.seconds);
  throw InputError("--time-limit", line);
}

OutputEstimate estimateOutputs(const Scene& scene, const std::vector<Camera>& cameras,
                               const ViewParams& views, size_t texels, size_t atlasTexels,
                               const MachineCosts& costs, const EngineOutputParams& engine) {
  OutputEstimate e;
  e.views = cameras.size();
  const double raySeconds = costs.ray, texelSeconds = costs.texel;
  e.raySeconds = raySeconds;
  e.texelSeconds = texelSeconds;
  e.texelCpuSeconds = costs.texelCpu;
  e.load = costs.load;
  const int n = std::clamp(views.supersample, 1, 8);
  for (const Camera& c : cameras) {
    const ViewSize v = viewSize(c, views);
    const double pixels = double(v.width) * double(v.height);
    e.viewPixels += pixels;
    e.viewSeconds += pixels * (double(n * n) * kRaysPerViewRay + kRaysPerViewPixel) * raySeconds;
  }
  const double triangles = double(scene.triangles.size());
  // The files in texels at the PNG probe's CPU seconds times the load observed over the bake so far, with
  // room to spare; before any load is observed, at the probe's wall seconds. The wall probe alone is a
  // snapshot: at load 23 it read 44 times its CPU seconds, where the load over the bake was 11 and
  // oa_dm7's files (977 k texels) took 11.4 s, estimated at 80 by the snapshot.
  const double texelCost =
      costs.texelCpu > 0.0 && costs.load > 0.0 ? kLoadSpare * costs.texelCpu * costs.load : texelSeconds;
  e.filesSeconds =
      double(atlasTexels) * kProbesPerFileTexel * texelCost + triangles * kRaysPerTriangle * raySeconds;
  e.pageSeconds = double(std::max(texels, atlasTexels)) * kProbesPerPageTexel * texelCost +
                  triangles * kRaysPerTriangle * raySeconds;
  const GatherParams gather;  // the probes' and the directional lightmap's emitter samples
  if (engine.directional)
    e.directionalSeconds = double(texels) * double(engine.directionalRays + gather.emitterSamples) *
                           kRaysPerGatherRay * raySeconds;
  if (engine.probes && engine.probeSpacing > 0.0f) {
    // At most one probe per lattice point of the scene's bounds (the empty space is less).
    glm::vec3 lo(3.0e38f), hi(-3.0e38f);
    for (const Triangle& t : scene.triangles)
      for (const glm::vec3& p : t.p) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::dvec3 size = glm::max(glm::dvec3(hi - lo), glm::dvec3(0.0));
    const double points = (size.x / engine.probeSpacing + 1.0) * (size.y / engine.probeSpacing + 1.0) *
                          (size.z / engine.probeSpacing + 1.0);
    const ProbeParams probe;
    const glm::dvec3 voxels = size / double(probe.voxel) + 5.0;
    if (!scene.triangles.empty()) {
      e.probeVoxelSeconds = voxels.x * voxels.y * voxels.z * kProbesPerVoxel * texelCost;
      e.probesSeconds =
          e.probeVoxelSeconds + points * kProbeLatticeShare *
                                    double(probe.gather.rays + probe.gather.emitterSamples + 26) *
                                    kRaysPerGatherRay * raySeconds;
    }
  }
  return e;
}

std::chrono::steady_clock::time_point keepBack(std::chrono::steady_clock::time_point deadline,
                                               double seconds) {
  if (deadline == std::chrono::steady_clock::time_point::max()) return deadline;
  return deadline - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                        std::chrono::duration<double>(std::max(0.0, seconds)));
}

BakeMemory bakeMemory(const BakeSettings& s, const Scene& scene, const LightmapAtlas& atlas,
                      double largestViewBytes) {
  return bakeMemory(s, scene, atlas.texelCount(), atlas.validTexels(), largestViewBytes);
}

BakeMemory bakeMemory(const BakeSettings& s, const Scene& scene, size_t atlasTexels, size_t validTexels,
                      double largestViewBytes) {
  BakeMemory m;
  m.base = kProcessBytes + double(scene.triangles.size()) * kSceneBytesPerTriangle;
  m.atlas = double(atlasTexels) * kBakeBytesPerTexel;
  // The office's cells bake (233 k texels, a 179 MB atlas and item buffers) peaked at 568 MB in its
  // cells' set-up.
  if (s.cells.method == BakeMethod::Cells) m.cells = m.atlas;
  const double edge = s.solver.params.itemBuffer;
  const double regions = std::pow(std::max(s.solver.params.maxRegions, s.solver.params.strongShotRegions), 2);
  // An item and a depth layer (8 bytes a pixel) per region, and half as much again for the GL driver.
  m.itemBuffers = edge * edge * regions * 12.0;
  m.rayScene = double(scene.triangles.size()) * kRaySceneBytesPerTriangle;
  if (scene.sky.lights()) m.skyGather = double(validTexels) * kSkyGatherBytesPerTexel;
  m.views = largestViewBytes;
  const EngineOutputParams& engine = s.output.engine;
  const double rayScene = double(scene.triangles.size()) * kRaySceneBytesPerTriangle;
  if (engine.directional) m.gathers = double(atlasTexels) * kDirectionalBytesPerTexel + rayScene;
  if (engine.probes) m.gathers = std::max(m.gathers, probeBytes(scene, atlasTexels) + rayScene);
  return m;
}

BakeSettings withinMemory(const BakeSettings& settings, const Scene& scene,
                          const std::vector<Camera>& cameras, Context& ctx) {
  BakeSettings s = settings;
  const uint64_t limit = s.atlas.params.memoryLimit;
  const size_t budget = s.atlas.autoDensity.maxTexels;
  if (limit == 0 || !s.atlas.densityAuto || budget == 0) return s;
  const double views = largestViewBytes(cameras, s.output.views);
  const auto bytesAt = [&](size_t texels) {
    return bakeMemory(s, scene, size_t(double(texels) * kAtlasTexelsPerValidTexel), texels, views);
  };
  const BakeMemory asked = bytesAt(budget);
  if (asked.total() <= double(limit)) return s;
  // The bytes are affine in the budget: the largest that fits, from the fixed part and the per-texel one.
  const double fixed = bytesAt(0).total(), perTexel = (asked.total() - fixed) / double(budget);
  const size_t fits = double(limit) > fixed ? size_t((double(limit) - fixed) / perTexel) : 0;
  if (fits < kLeastTexelBudget) {
    std::ostringstream what;
    what << "the bake at the least texel budget of " << kLeastTexelBudget
         << " (the program and the GL driver " << formatBytes(asked.base) << ", item buffers "
         << formatBytes(asked.itemBuffers) << ", ray scene " << formatBytes(asked.rayScene)
         << ", largest view " << formatBytes(asked.views) << ")";
    requireMemory(bytesAt(kLeastTexelBudget).total(), limit, "maximum memory", what.str(),
                  "lower `item buffer` or `view size`, or raise `maximum memory`");
  }
  const size_t lowered = std::max(kLeastTexelBudget, fits);
  s.atlas.autoDensity.maxTexels = lowered;
  char line[300];
  std::snprintf(line, sizeof line,
                "memory: the texel budget lowered from %zu to %zu texels to fit --max-memory %s (the bake at "
                "%zu: about %s)",
                budget, lowered, formatBytes(double(limit)).c_str(), budget,
                formatBytes(asked.total()).c_str());
  ctx.warn(line);
  return s;
}

ViewParams requireBakeMemory(const BakeSettings& s, const Scene& scene, const std::vector<Camera>& cameras,
                             const LightmapAtlas& atlas, Context& ctx) {
  const uint64_t limit = s.atlas.params.memoryLimit;
  ViewParams views = s.output.views;
  const BakeMemory m = bakeMemory(s, scene, atlas, largestViewBytes(cameras, views));
  if (limit == 0 || m.total() <= double(limit)) return views;
  // The views shrink to what the rest leaves, when that still holds a picture of the smallest size.
  const double rest = m.total() - m.views;
  const double smallest = viewBytes(ViewSize{kMinViewEdge, kMinViewEdge});
  if (m.views > 0.0 && double(limit) - rest >= smallest) {
    while (largestViewBytes(cameras, views) > double(limit) - rest && views.width > kMinViewEdge) {
      views.width = std::max(kMinViewEdge, views.width * 9 / 10);
      if (views.height > 0) views.height = std::max(kMinViewEdge, views.height * 9 / 10);
    }
    if (largestViewBytes(cameras, views) <= double(limit) - rest) {
      ctx.warn("views: pictures " + std::to_string(views.width) + " pixels wide to fit the memory limit of " +
               formatBytes(double(limit)) + " (the largest asked for " + formatBytes(m.views) + ")");
      return views;
    }
  }
  // Named by the largest share: what the user can lower. The views shrink by themselves, so they are named
  // only when the rest fits.
  struct Share {
    double bytes;
    std::string parameter, remedy;
  };
  const std::string texels = s.atlas.densityAuto ? "maximum texels" : atlas.sizeParameter;
  const std::string gather = s.output.engine.probes ? "--probes" : "--directional";
  const Share shares[] = {{m.atlas + m.skyGather, texels, "lower `" + texels + "`"},
                          {m.itemBuffers, "item buffer", "lower `item buffer`"},
                          {m.rayScene, "maximum memory", "bake a scene of fewer triangles"},
                          {rest > double(limit) ? 0.0 : m.views, "view size", "lower `view size`"},
                          {m.gathers, gather, "leave out " + gather}};
  const Share& largest =
      *std::max_element(shares, shares + 5, [](const Share& a, const Share& b) { return a.bytes < b.bytes; });
  std::ostringstream what;
  what << "the bake (atlas " << formatBytes(m.atlas) << ", item buffers " << formatBytes(m.itemBuffers)
       << ", ray scene " << formatBytes(m.rayScene) << ", sky gather " << formatBytes(m.skyGather)
       << ", largest view " << formatBytes(m.views);
  if (m.gathers > 0.0) what << ", " << gather << "' gather " << formatBytes(m.gathers);
  what << ")";
  requireMemory(m.total(), limit, largest.parameter, what.str(),
                largest.remedy + " or raise `maximum memory`");
  return views;
}

}  // namespace cpgi::bake_steps
