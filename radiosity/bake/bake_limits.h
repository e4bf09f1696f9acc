// What a bake may take, over every stage (issue 46 item 3): the outputs' share of --time-limit, kept back
// from the solve so that the views and the files fit before the limit, and the memory of the stages the
// atlas's per-texel figure leaves out (the ray scene, the sky gather, the views), checked with it against
// --max-memory. Not for callers outside radiosity/bake/.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/lightmap_output.h"
#include "radiosity/lightmap/views.h"

namespace cpgi::bake_steps {

/// The seconds of a ray on this machine as it runs now (its load included): the wall time of a few
/// thousand nearest-hit rays from the middle of the scene's bounds, traced on every core as the views are.
/// The outputs' estimates are counted in these rays.
double probeRaySeconds(const Scene& scene);

/// The seconds of a pixel of a PNG encoding on this machine as it runs now: the files and the page, mostly
/// one thread compressing and copying texels, are counted in these, whatever the scene's rays cost.
double probeTexelSeconds();

/// The CPU seconds (this thread's) of a pixel of probeTexelSeconds' PNG encoding: what a texel costs the
/// machine unloaded, which LoadMeter's ratio turns into wall seconds as the load moves.
double probeTexelCpuSeconds();

/// The ratio of wall time to the CPU time this process got since the meter started (its load): the
/// wall seconds × the cores the bake may use over the CPU seconds of every thread of the process. 1 on an
/// idle machine with every core busy for the bake; 5–20 at load 10–40 on 2 cores; more where the bake
/// waited (conservative: it only ever reserves more). At least 1, at most kMostLoadRatio.
class LoadMeter {
 public:
  LoadMeter();
  double ratio() const;
  /// ratio(), or 0 before the process has spent enough CPU to say (a tenth of a second).
  double observed() const;

 private:
  std::chrono::steady_clock::time_point wall_;
  double cpu_ = 0.0;
};
inline constexpr double kMostLoadRatio = 40.0;
/// CPU seconds of every thread of this process so far (user + system).
double processCpuSeconds();

/// This machine's costs as it runs now, the outputs' estimates' units.
struct MachineCosts {
  double ray = 0.0;       ///< probeRaySeconds
  double texel = 0.0;     ///< probeTexelSeconds
  double texelCpu = 0.0;  ///< probeTexelCpuSeconds
  /// LoadMeter::observed: with one, the files are estimated at texelCpu × load (with room to spare);
  /// without, at the wall probe `texel`.
  double load = 0.0;
};

/// The seconds a bake's outputs take after its solve, from their pixels and texels: the views and the
/// gathers costed in rays of probeRaySeconds, the files and the page in texels of probeTexelSeconds
/// (bench/RESULTS.md, "A bake inside its limits"), with room to spare.
struct OutputEstimate {
  size_t views = 0;                 ///< cameras whose pictures the bake renders
  double viewPixels = 0.0;          ///< their pixels, all views
  double viewSeconds = 0.0;         ///< rendering and writing them
  double filesSeconds = 0.0;        ///< lightmap.exr, lightmap.png, baked.glb before the views
  double pageSeconds = 0.0;         ///< report.json and report.html after them
  double directionalSeconds = 0.0;  ///< --directional's gather, before the files
  double probesSeconds = 0.0;       ///< --probes' voxels and gather, before the files
  double probeVoxelSeconds = 0.0;   ///< of which their placement's voxels, which cannot stop part-way
  double raySeconds = 0.0;          ///< the cost of a ray they are counted in (probeRaySeconds)
  double texelSeconds = 0.0;        ///< the cost of a texel the files are counted in (probeTexelSeconds)
  double texelCpuSeconds = 0.0;     ///< probeTexelCpuSeconds, at the load below
  double load = 0.0;                ///< LoadMeter::observed when estimated (0: none yet)
  double gatherSeconds() const { return directionalSeconds + probesSeconds; }
  double seconds() const { return viewSeconds + filesSeconds + pageSeconds + gatherSeconds(); }
};

/// The cameras the views will have: the scene's own, else one per cell of `cells` but the outside (one
/// overview without cells), as defaultCameras makes them.
std::vector<Camera> expectedCameras(const Scene& scene, const CellGraph& cells);

/// The outputs of a bake of `texels` atlas texels (lightmap.exr counts the atlas's width × height,
/// `atlasTexels`) with the views of `cameras` at `views`' size, and `engine`'s directional gather and
/// probes when asked for.
OutputEstimate estimateOutputs(const Scene& scene, const std::vector<Camera>& cameras,
                               const ViewParams& views, size_t texels, size_t atlasTexels,
                               const MachineCosts& costs, const EngineOutputParams& engine = {});

/// The outputs to make in the time left, the required ones (the lightmap's files, baked.glb, report.json and
/// report.html: filesSeconds + pageSeconds) first; the optional ones asked for (`views`, `probes`,
/// `directional`) kept while their estimates fit beside them, dropped in that order (the views first: they
/// are pictures of the lightmap, which the engines' outputs are not). `skipped` names those dropped.
struct OutputPlan {
  bool views = false, probes = false, directional = false;
  std::vector<std::string> skipped;
};
OutputPlan planOutputs(double secondsLeft, const OutputEstimate& e, bool viewsAsked,
                       const EngineOutputParams& engine);

/// The least a bake can write: its required files and page (planOutputs) at `texels`, as estimated.
/// A --time-limit under it, with the machine's load, is refused in one line (InputError on --time-limit)
/// before anything else runs: a bake that cannot write its lightmap in time would end past the limit.
void requireTimeForMinimum(double timeLimit, double minimumSeconds, size_t texels);

/// The most of --time-limit the directional gather and the probes' estimate keeps back from the solve:
/// the rest is the solve's, and what they do not finish by their deadline is left out (said).
inline constexpr double kGatherTimeShare = 0.5;

/// The share of the time before the outputs' that the density pilot may take: it lays out a quarter of
/// the texel budget, and the output's sky gather, lamps and solve come after it.
inline constexpr double kPilotTimeShare = 0.25;

/// `deadline` moved `seconds` earlier (no deadline stays none).
std::chrono::steady_clock::time_point keepBack(std::chrono::steady_clock::time_point deadline,
                                               double seconds);

/// The memory of a bake at its peak, by what takes it (bytes).
struct BakeMemory {
  double atlas = 0.0;        ///< kBakeBytesPerTexel a texel of the atlas (its padding included)
  double itemBuffers = 0.0;  ///< every visibility region's item and depth layer
  double rayScene = 0.0;     ///< the Embree scene the lamps' rays, the sky, the ambient term and views use
  double skyGather = 0.0;    ///< the sky gather's sums and texel list, with a sky
  double views = 0.0;        ///< the largest view picture (they are made one at a time)
  /// --directional's gather (its four coefficients and the baked radiance a texel, a ray scene of its own)
  /// or --probes' (their voxels over the scene's bounds at ProbeParams::voxel), the larger: one runs after
  /// the other.
  double gathers = 0.0;
  double total() const { return atlas + itemBuffers + rayScene + skyGather + views + gathers; }
};
BakeMemory bakeMemory(const BakeSettings& s, const Scene& scene, const LightmapAtlas& atlas,
                      double largestViewBytes);

/// Checks bakeMemory against the limit (s.atlas.params.memoryLimit). When the views are what passes it,
/// their size is lowered (the aspect kept) to fit, said in one warning, and the view parameters to use
/// returned; otherwise one InputError naming the largest share and what lowers it.
ViewParams requireBakeMemory(const BakeSettings& s, const Scene& scene, const std::vector<Camera>& cameras,
                             const LightmapAtlas& atlas, Context& ctx);

}  // namespace cpgi::bake_steps
