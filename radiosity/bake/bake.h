// bake(): the whole bake of design.md §3 as a library call (Recast's driver, Cycles' Session): the scene's
// atlas (with --density auto, laid out from a pilot shot of the lamps), the solve, global or cell by cell
// through portals, its stop per cell, the ambient term for what the stop left unshot, and the result set
// (lightmap.exr, lightmap.png, baked.glb, view-*, report.json, report.html). `cpgi bake` parses its flags
// into BakeSettings (bake_settings.h), calls loadBakeScene and bake(), and prints what comes back.
//
//   BakeSettings s;                       // the command line's default bake
//   s.input.scene = "seed1.glb";
//   s.output.folder = "out/seed1";        // empty: nothing written, the lightmap comes back in BakeResult
//   Context ctx;
//   const BakeResult r = bake(s, ctx);    // loadBakeScene + bake
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "core/scene_io.h"
#include "radiosity/bake/bake_settings.h"
#include "radiosity/bake/cpu_clocks.h"
#include "radiosity/cpu/ray_shot_engine.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/gpu/gl_shot_engine.h"
#include "radiosity/lightmap/atlas.h"

namespace cpgi {

/// A bake's input: the scene as read (sky applied) and the cells it is baked with.
struct BakeScene {
  /// With source "auto" or room volumes the scene split on the portals' planes (what `graph` indexes).
  LoadedScene loaded;
  /// With BakeMethod::Cells: the cells of settings.cells.source; else the scene's own (loaded.cells).
  CellGraph graph;
};

/// Throws InputError(scenePath, ...) naming `emit` and `dark` when nothing lights the scene, unless
/// allowDark (bake and reference alike).
void requireLight(const LoadedScene& loaded, const std::string& scenePath, bool allowDark);

/// What a caller driving bake() sets besides the settings.
struct BakeRun {
  /// When the bake started (the load included): Limits::timeLimit counts from here.
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  /// The GL context to draw with (a cell-job server keeps one between jobs); null: bake() opens one and
  /// closes it at the end, after which a context the caller kept is current again (EglContext). A process
  /// that bakes more than once should still keep one and pass it here: opening a context costs time.
  const EglContext* gl = nullptr;
  /// Called once the atlas is laid out and the memory checked, before the solve, with the bake's size in
  /// one line ("bake: N texels in P patches (...), about M MB; ...") for a caller to show (bakeNotes).
  std::function<void(const std::string&)> sized;
  /// The clocks the bake's share of a core is read on (real ones; tests give fake ones) and their reading
  /// at `start`: the loading's CPU over its wall is the first share the bake's estimates see.
  CpuClocks clocks = cpuClocks();
  CpuReading cpuAtStart = clocks();
};

/// Step 1: reads settings.input.scene with its load options, applies settings.sky to it (core/sky.h),
/// refuses a scene nothing lights (unless input.allowDark) and, with BakeMethod::Cells, resolves the cells
/// of settings.cells.source (cell_source.h). Warnings go to ctx. Throws InputError. Limits::timeLimit counts
/// from run.start: a load it interrupts (between the file's meshes and images) and a decomposition into
/// cells it interrupts are each an InputError naming the time limit.
BakeScene loadBakeScene(const BakeSettings& settings, Context& ctx, const BakeRun& run = {});

struct BakeResult {
  LightmapAtlas atlas;                 ///< the output's atlas
  std::vector<glm::vec3> radiosity;    ///< per atlas texel, W/m² (R, G, B), the ambient term included
  std::vector<float> texelCell;        ///< per atlas texel, the index into cellNames; -1: none
  std::vector<std::string> cellNames;  ///< the cells (or automatic rooms) of texelCell
  nlohmann::json report;               ///< report.json (design.md §3 and bake's own keys)
  int shots = 0;
  double unshotFraction = 0.0;  ///< of the emitted power, at the stop
  bool partial = false;         ///< stopped by Limits::timeLimit (the solve, or the views)
  double seconds = 0.0;         ///< from BakeRun::start to the files written
};

/// Steps 2–4 on a loaded scene: the atlas, the solve (BakeMethod::Cells: on `cells`, which index
/// `scene`; Global: `cells` are the scene's own, kept in baked.glb and the "cell" channel, or none), the
/// ambient term, and the result set in settings.output.folder unless that is empty. Throws InputError for
/// settings the scene cannot take (memory, a scene that would not converge, an on-demand bake of the
/// global method).
BakeResult bake(const Scene& scene, const CellGraph& cells, const BakeSettings& settings, Context& ctx,
                const BakeRun& run = {});

/// loadBakeScene, then bake() on what it read; a limit whose time left after the loading cannot hold the
/// least the bake writes at the share of a core the loading got is refused in one line (InputError on
/// --time-limit), nothing written.
BakeResult bake(const BakeSettings& settings, Context& ctx, const BakeRun& run = {});

/// The backend of a two-level bake's interreflection: whether `solver` shoots it by Embree rays on the CPU
/// rather than by item buffers on `gl` (Auto: rays where the device rasterizes in software,
/// EglContext::softwareRasterizer: it draws item buffers on the same CPU cores the rays use).
bool indirectByRays(IndirectSolver solver, const EglContext& gl);

/// The shot engines of one bake (radiosity/solve/shot_engine.h), chosen once from what the machine offers
/// (Cycles' one device choice). Backend::Auto and Gl: the GL engine for the lamps' shots and every solve,
/// and for the interreflection of a two-level solve the rays engine where indirectByRays says so; Auto
/// where no GL context can be made, and Rays: the rays engine for everything. The GL context is opened at
/// the first need (or `given`, kept by the caller).
class BakeEngines {
 public:
  BakeEngines(Backend backend, IndirectSolver indirect, const EglContext* given, Context& ctx);
  ~BakeEngines();
  /// The engines, the GL context made if it is to be used.
  const ShotEngines& engines();
  /// The GL context, when the bake draws with one (after engines()); null for rays alone.
  const EglContext* gl() const { return gl_; }

 private:
  Backend backend_;
  IndirectSolver indirect_;
  Context& ctx_;
  const EglContext* gl_;
  std::unique_ptr<EglContext> opened_;
  std::unique_ptr<GlShotEngine> glEngine_;
  RayShotEngine rays_;
  std::optional<ShotEngines> engines_;
};

/// The two notes a bake leaves around a live progress line, as a wrapper of `inner` (null stays null):
/// the bake's size (BakeRun::sized's line, once `size` holds it) at the solver's first report; and, for a
/// global solve, the first time estimate once the solver reports one (Progress::secondsLeft, from the
/// first shots' cost and the decay of the unshot power), with what Limits::timeLimit will do to it.
/// `note` prints a line that stays.
Context::ProgressFn bakeNotes(Context::ProgressFn inner, const BakeSettings& settings,
                              std::chrono::steady_clock::time_point start, std::shared_ptr<std::string> size,
                              std::function<void(const std::string&)> note);

}  // namespace cpgi
