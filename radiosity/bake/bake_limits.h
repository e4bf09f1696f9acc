// What a bake may take, over every stage (issue 46 item 3): the outputs' share of --time-limit, kept back
// from the solve so that the views and the files fit before the limit, and the memory of the stages the
// atlas's per-texel figure leaves out (the ray scene, the sky gather, the views), checked with it against
// --max-memory. Not for callers outside radiosity/bake/.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/bake/cpu_clocks.h"
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
/// machine unloaded, which CpuShare turns into wall seconds as the load moves.
double probeTexelCpuSeconds();

/// The share of a core one thread of this process gets, measured directly: CPU seconds over wall seconds,
/// the larger of the thread that made the clocks (the bake's own thread, which works in every stage, serial
/// or parallel) and the process's every thread over every core (a stage whose own thread waits on the GL
/// driver's). Over the last kCpuShareWindow seconds and over the whole bake, the lower (a load that rose is
/// seen within the window; one that fell only once the bake's mean says so). 1 on an idle machine; 0.05 at
/// load 40 on 2 cores; 0.015-0.02 where the bake ran beside 16 busy loops and three other engineers' work
/// (bench/RESULTS.md, "Never past --time-limit when the bake gets 2 % of a core"). Not capped: the outputs'
/// reserve and the set-up's estimate are wall seconds = CPU seconds / share.
class CpuShare {
 public:
  /// From `start` (the bake's start, before its loading, BakeRun::cpu) on `clocks`; `cores` (0: the task
  /// arena's) is what the process's CPU is shared over.
  explicit CpuShare(CpuClocks clocks = cpuClocks(), std::optional<CpuReading> start = std::nullopt,
                    int cores = 0);
  /// In (0, 1]; 0 before kLeastCpuSeconds of CPU say anything.
  double share() const;
  /// The wall seconds a CPU second of one thread takes now: 1 / share(), or 1 before one is measured.
  double ratio() const;
  /// ratio(), or 0 before a share is measured.
  double observed() const;

 private:
  double shareBetween(const CpuReading& a, const CpuReading& b) const;
  CpuClocks clocks_;
  CpuReading start_;
  int cores_;
  mutable std::mutex mutex_;
  mutable std::vector<CpuReading> readings_;  ///< one a call of share(), the window's starts
};
/// The window of CpuShare's recent share (wall seconds).
inline constexpr double kCpuShareWindow = 10.0;
/// The CPU seconds a share is read from: a few of the scheduler's slices.
inline constexpr double kLeastCpuSeconds = 0.02;
/// CPU seconds of every thread of this process so far (user + system).
double processCpuSeconds();
/// Seconds from now to `until` (none: a day; past: negative).
double secondsLeft(std::chrono::steady_clock::time_point until);

/// This machine's costs as it runs now, the outputs' estimates' units.
struct MachineCosts {
  double ray = 0.0;       ///< probeRaySeconds
  double texel = 0.0;     ///< probeTexelSeconds
  double texelCpu = 0.0;  ///< probeTexelCpuSeconds
  /// CpuShare::observed (wall seconds per CPU second): with one, the files are estimated at texelCpu × load
  /// (with room to spare); without, at the wall probe `texel`.
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
  double load = 0.0;                ///< CpuShare::observed when estimated (0: none yet)
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
  /// The views' size when the one asked for was made smaller to fit (viewsThatFit); none: as asked.
  std::optional<ViewParams> smallerViews;
};
OutputPlan planOutputs(double secondsLeft, const OutputEstimate& e, bool viewsAsked,
                       const EngineOutputParams& engine);

/// The narrowest view a time-limit makes a bake's views, in pixels: enough to see which rooms are lit.
inline constexpr int kLimitedViewWidth = 160;
/// The views of `cameras` a bake renders in `seconds` at `costs`: at one ray a pixel and the widest of
/// `asked`'s width shrunk by fifths whose estimate fits, down to kLimitedViewWidth (or `asked`'s, if
/// narrower) however long that takes. The aspect is kept; a time-limited bake's user sees what was baked.
ViewParams viewsThatFit(const Scene& scene, const std::vector<Camera>& cameras, const ViewParams& asked,
                        double seconds, const MachineCosts& costs);

/// The least a bake can write: its least layout and its required files and page (planOutputs) at `texels`,
/// as estimated at the share of a core measured so far.
struct LeastBake {
  double seconds = 0.0;        ///< wall seconds, the layout's included
  double layoutSeconds = 0.0;  ///< of which the least layout's
  size_t texels = 0;           ///< the least layout's texels
  double share = 0.0;          ///< CpuShare::share when estimated (0: not yet measured)
  double spentSeconds = 0.0;   ///< of the limit before it (the loading, when the bake read its scene)
};
/// A --time-limit whose time left after `least.spentSeconds` is under `least.seconds` is refused in one line
/// (InputError on --time-limit) before anything else runs, with the least limit that would do at this load:
/// a bake that cannot write its lightmap in time would end past the limit.
void requireTimeForMinimum(double timeLimit, const LeastBake& least);

/// The most of --time-limit the directional gather and the probes' estimate keeps back from the solve:
/// the rest is the solve's, and what they do not finish by their deadline is left out (said).
inline constexpr double kGatherTimeShare = 0.5;

/// The share of the time before the outputs' that the density pilot may take: it lays out a quarter of
/// the texel budget, and the output's sky gather, lamps and solve come after it.
inline constexpr double kPilotTimeShare = 0.25;

/// `deadline` moved `seconds` earlier (no deadline stays none).
std::chrono::steady_clock::time_point keepBack(std::chrono::steady_clock::time_point deadline,
                                               double seconds);

/// What a layout of the output's atlas costs on this machine as it runs, measured on one attempt: its
/// charts (laid out and packed again at every scale) and its texels (filled, with their gutters).
struct LayoutCost {
  double chartSeconds = 0.0;  ///< wall seconds of the charts
  double texelSeconds = 0.0;  ///< wall seconds a texel (0: not measured)
  size_t texels = 0;          ///< the attempt's atlas, width × height
  size_t charts = 0;          ///< its charts
};
/// From a layout that stopped: its charts' seconds, its fill's rate (none when it filled nothing).
LayoutCost stoppedLayoutCost(const AtlasLayoutStopped& stopped);
/// From a layout laid out whole in `seconds`: every second counted both as its charts' and its texels'
/// (their split not measured), which only ever prices a coarser layout higher.
LayoutCost wholeLayoutCost(double seconds, size_t texels, size_t charts);
/// The most a stopped layout is coarsened: 1/32 of the texels per metre, the least layout, which runs whole.
inline constexpr int kMostCoarsening = 32;
/// The texels (width × height) of a layout at 1/`factor` of the texels per metre of `cost`'s: its texels
/// over factor², and every chart at least at `params`' least size with its gutter.
size_t coarseTexels(const LayoutCost& cost, const AtlasParams& params, int factor);
/// The wall seconds of that layout at `cost`'s rates, with room to spare (the gutters of a fill stopped
/// before them, the load moving).
double coarseLayoutSeconds(const LayoutCost& cost, const AtlasParams& params, int factor);
/// The share of the time left that a layout and its files may be planned in: the stages between them (the
/// costs' probes again, the rooms, the sky's first pass, the lamps) cannot stop part-way either, and the
/// share of a core moves. oa_dm7 at 120 s beside 16 busy loops and two other bakes chose 1/4 on the whole
/// time left at 2 % of a core and wrote its files at 1.3 %, 32 s past the limit.
inline constexpr double kRelayoutTimeShare = 0.5;
/// The finest factor (2, 4, 8, 16) whose layout and its required outputs (`outputsSeconds` of its texels)
/// fit in kRelayoutTimeShare of `secondsLeft`; kMostCoarsening when none does or the fill's rate was not
/// measured.
int coarseningThatFits(const LayoutCost& cost, const AtlasParams& params, double secondsLeft,
                       const std::function<double(size_t)>& outputsSeconds);
/// The CPU seconds of the least layout of `scene` (kMostCoarsening of `params`: its charts, about one a
/// triangle, and their texels), on this machine unloaded (bench/RESULTS.md, "Never past --time-limit when
/// the bake gets 2 % of a core"), for the least a bake writes.
double leastLayoutCpuSeconds(const Scene& scene, size_t texels);

/// The memory of a bake at its peak, by what takes it (bytes). The atlas is laid out before its solve at
/// the size it keeps (fitTexelBudget), so the solve's buffers are the peak: the stages before them (the
/// pilot's quarter of the texels, the layout's 56 bytes a texel) and the rooms' decomposition (limited to
/// what this leaves of --max-memory) take less.
struct BakeMemory {
  /// What the process holds whatever the atlas: the program and its libraries, the GL driver's context
  /// (llvmpipe's threads and caches), the scene and its set-up's own copies (kProcessBytes and
  /// kSceneBytesPerTriangle).
  double base = 0.0;
  double atlas = 0.0;  ///< kBakeBytesPerTexel a texel of the atlas (its padding included)
  /// With --method cells, the cells' own atlases and their solves' buffers: the atlas's texels again.
  double cells = 0.0;
  /// The layout's own peak, before the solve's buffers: kLayoutBytesPerTexel a texel of the largest atlas
  /// laid out (BakeInput::laidOutTexels), which a time limit can have laid out again coarser.
  double layout = 0.0;
  double itemBuffers = 0.0;  ///< every visibility region's item and depth layer
  double rayScene = 0.0;     ///< the Embree scene the lamps' rays, the sky, the ambient term and views use
  double skyGather = 0.0;    ///< the sky gather's sums and texel list, with a sky
  double views = 0.0;        ///< the largest view picture (they are made one at a time)
  /// --directional's gather (its four coefficients and the baked radiance a texel, a ray scene of its own)
  /// or --probes' (their voxels over the scene's bounds at ProbeParams::voxel), the larger: one runs after
  /// the other.
  double gathers = 0.0;
  double total() const {
    return base + std::max(layout, atlas + cells + itemBuffers + rayScene + skyGather + views + gathers);
  }
};
/// For an atlas of `atlasTexels` (width × height) of which `validTexels` lie on surfaces.
BakeMemory bakeMemory(const BakeSettings& s, const Scene& scene, size_t atlasTexels, size_t validTexels,
                      double largestViewBytes);
BakeMemory bakeMemory(const BakeSettings& s, const Scene& scene, const LightmapAtlas& atlas,
                      double largestViewBytes);
/// The largest of `cameras`' pictures at `views` (they are made one at a time).
double largestViewBytes(const std::vector<Camera>& cameras, const ViewParams& views);

/// What a texel of an atlas being laid out takes: its arrays (56 bytes) and a gutter tap with its ray.
inline constexpr double kLayoutBytesPerTexel = 128.0;
/// An atlas's width × height over its valid texels, at most, on the scenes benched (a loose triangle's
/// chart is half empty, every chart has its gutter, shelves leave room under short charts): what a texel
/// budget (valid texels) is counted at before the layout says.
inline constexpr double kAtlasTexelsPerValidTexel = 3.5;
/// The least texel budget --max-memory lowers --max-texels to (a 128 × 128 lightmap); under it the bake is
/// refused.
inline constexpr size_t kLeastTexelBudget = 16384;
/// `s` within --max-memory (s.atlas.params.memoryLimit) before anything is laid out: with --density auto
/// and a texel budget, the bake at that budget (its atlas kAtlasTexelsPerValidTexel times it) estimated by
/// bakeMemory, and the budget lowered to what fits (said in one warning); under kLeastTexelBudget, one
/// InputError on `maximum memory`. Other bakes are checked once their atlas is laid out (requireBakeMemory).
BakeSettings withinMemory(const BakeSettings& s, const Scene& scene, const std::vector<Camera>& cameras,
                          Context& ctx);

/// Checks bakeMemory against the limit (s.atlas.params.memoryLimit). When the views are what passes it,
/// their size is lowered (the aspect kept) to fit, said in one warning, and the view parameters to use
/// returned; otherwise one InputError naming the largest share and what lowers it.
ViewParams requireBakeMemory(const BakeSettings& s, const Scene& scene, const std::vector<Camera>& cameras,
                             const LightmapAtlas& atlas, Context& ctx);

}  // namespace cpgi::bake_steps
