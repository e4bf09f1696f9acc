// `cpgi bake SCENE -o DIR [--method global|cells] [--cells FILE|auto] [--portals diffuse|directional|binned]
// [--max-rounds N] [--only-cells A,B | --around X,Y,Z [--depth K]] [--boundary coarse|dark] [--jobs N]
// [--plan PLAN] [atlas options] [solver options] [decomposition options for --cells auto] [--no-ambient]
// [--allow-dark] [--view-size WxH] [loading options]`: the flags parsed into the library's BakeSettings
// (radiosity/bake/bake_settings.h, whose defaults these are), the bake run by radiosity/bake/bake.h
// (or, with --plan, its cell jobs' plan by radiosity/bake/bake_jobs.h), and its summary printed. The
// flags' names, checks and help are apps/options.h's.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <unistd.h>

#include "apps/commands.h"
#include "apps/options.h"
#include "core/error.h"
#include "core/progress.h"
#include "radiosity/bake/bake.h"
#include "radiosity/bake/bake_jobs.h"

namespace cpgi::cli {
namespace {

// A line on stderr that stays, clear of a live progress line on a terminal.
void printNote(const std::string& text) {
  std::fprintf(stderr, "%s%s\n", ::isatty(STDERR_FILENO) ? "\r\033[K" : "", text.c_str());
  std::fflush(stderr);
}

struct BakeCommand {
  BakeSettings settings;
  std::string method = bakeMethodName(BakeSettings{}.cells.method);
  std::string indirect = indirectSolverName(BakeSettings{}.solver.indirect);
  std::string backend = backendName(BakeSettings{}.solver.backend);
  bool noAmbient = false;
  std::string uv = "auto";  ///< --uv: where the engine lightmap lies (EngineOutputParams::uv)
  /// --plan DIR: the cell jobs' plan (radiosity/bake/bake_jobs.h, docs/cell-jobs.md) instead of the bake.
  std::string plan;
  bool quiet = false;
};

void printWarnings(const Context& ctx) {
  for (const std::string& w : ctx.warnings()) printWarning(w);
}

int runPlan(const BakeCommand& c) {
  Context ctx;
  ctx.setProgress(stderrProgress(c.quiet));
  const CellJobPlan plan = planBakeJobs(c.plan, c.settings, ctx);
  if (!c.quiet) {
    std::cout << c.plan << ": plan of " << plan.cells.size() << " cells and " << plan.firstShotGroups.size()
              << " emitter groups; next: cpgi cell-job " << c.plan << " --first-shot\n";
    printWarnings(ctx);
  }
  return 0;
}

int runBake(const BakeCommand& c) {
  if (!c.plan.empty()) return runPlan(c);
  BakeRun run;  // the time limit counts from here
  auto size = std::make_shared<std::string>();
  run.sized = [size](const std::string& line) { *size = line; };
  Context ctx;
  ctx.setProgress(bakeNotes(stderrProgress(c.quiet), c.settings, run.start, size, printNote));
  const BakeResult r = bake(c.settings, ctx, run);
  if (!c.quiet) {
    std::cout << c.settings.output.folder << ": " << r.atlas.validTexels() << " texels, " << r.shots
              << " shots, unshot " << r.unshotFraction * 100.0 << " %, " << r.seconds << " s"
              << (r.partial ? " (partial: stopped at the time limit)" : "") << "\n";
    printWarnings(ctx);
  }
  return 0;
}

void addOnDemandOptions(CLI::App& sub, BakeSettings::Cells& c) {
  const OptionGroup group(sub, "Cells");
  auto* only =
      sub.add_option("--only-cells", c.onlyCells,
                     "With --method cells: bake only these cells (comma-separated names); the others "
                     "act through their portals (see --boundary)");
  auto* around =
      sub.add_option("--around", c.around,
                     "With --method cells: bake the cell holding the point X,Y,Z (metres) and those "
                     "within --depth portals of it");
  only->excludes(around);
  sub.add_option("--depth", c.depth, "With --around: portals away from the point's cell")
      ->check(CLI::Range(0, 1000000))
      ->needs(around)
      ->capture_default_str();
  addBoundaryOption(sub, c.boundary);
}

void addMethodOptions(CLI::App& sub, BakeCommand& c) {
  sub.add_option("--method", c.method,
                 "global: one progressive radiosity solve over the whole scene; cells: cell by cell, light "
                 "handed on through portals (needs --cells)")
      ->check(CLI::IsMember({"global", "cells"}))
      ->capture_default_str()
      ->group("Solver");
  const OptionGroup group(sub, "Cells");
  sub.add_option("--cells", c.settings.cells.source,
                 "With --method cells: a glTF with cell:/portal: nodes or with rooms given as cellvolume: "
                 "meshes alone (the scene itself when it has them), a decompose output folder, or auto (the "
                 "automatic decomposition, with the decomposition options below); without it, the scene's "
                 "own cells when it has them, else auto")
      ->capture_default_str();
  addCellOptions(sub, c.settings.cells.params);
  addOnDemandOptions(sub, c.settings.cells);
  sub.add_option(
      "--plan", c.plan,
      "With --method cells: do not solve; write the cell jobs' plan (cells, portals and the lamps' "
      "emitter groups) into this folder, for `cpgi cell-job` or cpgi-dask (docs/cell-jobs.md)");
}

void addSolveOptions(CLI::App& sub, BakeCommand& c) {
  BakeSettings& s = c.settings;
  addAtlasOptions(sub, s.atlas.params, {}, &s.atlas.densityAuto, &s.limits.maxMemory);
  addSolverOptions(sub, s.solver.params);
  addDecomposeOptions(sub, s.cells.decompose);
  addAmbientOption(sub, c.noAmbient, s.solver.ambientShare);
  addTimeLimitOption(sub, s.limits.timeLimit);
  addSolveDensityOption(sub, s.solver.solveDensity);
  addLampCoarseningOption(sub, s.solver.lampCoarsening);
  const OptionGroup group(sub, "Solver");
  sub.add_option("--indirect-solver", c.indirect,
                 "With two levels (--solve-density): shoot the interreflection on the coarse atlas by item "
                 "buffers on the GL device (gpu), by Embree rays on the CPU (rays), or by rays where the GL "
                 "device is a software rasterizer such as llvmpipe (auto)")
      ->check(CLI::IsMember({"auto", "gpu", "rays"}))
      ->default_str(c.indirect);
  sub.add_option(
         "--backend", c.backend,
         "How every shot sees: item buffers on the GL device (gl), Embree rays on the CPU with no GL at "
         "all (rays: lamps by shadow rays; every --portals model), or gl where an OpenGL 4.5 context "
         "can be made and rays where not (auto)")
      ->check(CLI::IsMember({"auto", "gl", "rays"}))
      ->default_str(c.backend);
  addDensityToleranceOption(sub, s.atlas.autoDensity.light.tolerance);
  addMaxTexelsOption(sub, s.atlas.autoDensity.maxTexels);
}

// --help's last lines.
constexpr const char* kBakeExamples =
    "Examples:\n"
    "  cpgi bake scene.glb -o out/scene                     # the defaults\n"
    "  cpgi bake scene.glb -o out/scene --time-limit 120    # a result within two minutes\n"
    "  cpgi bake scene.glb -o out/scene --method cells --cells auto\n"
    "  cpgi bake house.glb -o out/house --sky cie-overcast --sun 0.3,0.8,0.2,500\n"
    "  cpgi bake scene.glb -o out/scene --density 10 --view-size 1280x720\n"
    "Every option: docs/commands/bake.md";

// The files for engines (issue 48; docs/engines.md): baked.glb's helpers and the lightmap's layout.
void addEngineOptions(CLI::App& sub, BakeCommand& c) {
  sub.add_flag("--keep-helpers", c.settings.output.engine.keepHelpers,
               "Keep in baked.glb the portal: quads, cellvolume: meshes and KHR_lights_punctual lamps "
               "(left out by default: an engine would draw them, or light the baked scene twice; preview.glb "
               "keeps them always)")
      ->group("Output");
  sub.add_option(
         "--uv", c.uv,
         "Where the engine lightmap (baked.glb's TEXCOORD_1, lightmap_irradiance.*) lies: cpgi's own "
         "atlas (own), the scene's TEXCOORD_1 (scene: refused, naming the mesh, when it leaves [0,1], "
         "overlaps or is missing), or the scene's when it passes those checks, else own with a warning "
         "(auto)")
      ->check(CLI::IsMember({"auto", "own", "scene"}))
      ->default_str(c.uv)
      ->group("Output");
  sub.add_flag(
         "--per-object", c.settings.output.engine.perObject,
         "Also a lightmap per object (glTF node's mesh, OBJ object): lightmap-OBJECT.exr and .png (RGBM), "
         "each object's charts (or, with the scene's UVs, its own TEXCOORD_1 square) in an image of its "
         "own, and baked.glb's materials and TEXCOORD_1 on them; one solve as without it")
      ->group("Output");
  // Directional light for normal maps (issue 48; docs/engines.md, "Directional lightmaps").
  sub.add_flag("--directional", c.settings.output.engine.directional,
               "Also write the directional lightmap: the L1 spherical harmonics of the light arriving per "
               "texel (lightmap_sh_l0/l1y/l1z/l1x.exr), for normal maps, gathered by rays from the bake")
      ->group("Output");
  sub.add_option("--directional-rays", c.settings.output.engine.directionalRays,
                 "Directions per texel of the directional lightmap's gather")
      ->check(CLI::Range(4, 65536))
      ->default_val(c.settings.output.engine.directionalRays)
      ->group("Output");
  sub.add_flag("--probes", c.settings.output.engine.probes,
               "Also write light probes through the rooms' empty space (probes.json, baked.glb's extras): L2 "
               "spherical harmonics of the light arriving, for objects that move")
      ->group("Output");
  sub.add_option("--probe-spacing", c.settings.output.engine.probeSpacing, "Metres between light probes")
      ->check(CLI::Range(0.05, 100.0))
      ->default_val(c.settings.output.engine.probeSpacing)
      ->group("Output");
}

// What the flags leave to be set after parsing: the names they take as the settings' enums.
void finishSettings(BakeCommand& c, const CLI::App& sub) {
  BakeSettings& s = c.settings;
  s.cells.method = c.method == "cells" ? BakeMethod::Cells : BakeMethod::Global;
  s.solver.indirect = c.indirect == "rays"  ? IndirectSolver::Rays
                      : c.indirect == "gpu" ? IndirectSolver::Gpu
                                            : IndirectSolver::Auto;
  s.solver.backend = c.backend == "rays" ? Backend::Rays : c.backend == "gl" ? Backend::Gl : Backend::Auto;
  s.solver.ambient = !c.noAmbient;
  s.output.engine.uv = c.uv == "own" ? UvSource::Own : c.uv == "scene" ? UvSource::Scene : UvSource::Auto;
  // --max-shots bounds the solve: no refusal of a scene that would need more.
  s.limits.refuseEndless = sub.count("--max-shots") == 0;
  // The options' tables fill the machine's memory in as the default; the library's default (0) is the
  // same limit found where the bake runs (a cell job on another machine finds its own).
  if (sub.count("--max-memory") == 0) s.limits.maxMemory = BakeSettings{}.limits.maxMemory;
  s.cells.decompose.memoryLimit = BakeSettings{}.cells.decompose.memoryLimit;  // the bake sets it from Limits
}

}  // namespace

void addBakeCommand(CLI::App& app, CommandFn& selected) {
  auto c = std::make_shared<BakeCommand>();
  CLI::App* sub =
      app.add_subcommand("bake", "Bake diffuse global illumination into a lightmap (GPU radiosity)");
  sub->footer(kBakeExamples);
  sub->add_option("scene", c->settings.input.scene, "Scene (.glb, .gltf, .obj)")->required();
  sub->add_option("-o,--output", c->settings.output.folder,
                  "Output folder: lightmap.exr/.png, baked.glb, report.html/.json, view-*.png")
      ->required()
      ->group("Output");
  addMethodOptions(*sub, *c);
  addSolveOptions(*sub, *c);
  addViewOptions(*sub, c->settings.output.views);
  addEngineOptions(*sub, *c);
  addLoadOptions(*sub, c->settings.input.load);
  addDarkOption(*sub, c->settings.input.allowDark);
  addSkyOptions(*sub, c->settings.sky, true);
  sub->add_flag("-q,--quiet", c->quiet, "No progress or summary")->group("Output");
  sub->callback([&selected, c, sub] {
    finishSettings(*c, *sub);
    selected = [c] { return runBake(*c); };
  });
}

}  // namespace cpgi::cli
