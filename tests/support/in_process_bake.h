// bake() in the test process (radiosity/bake/bake.h), for the end-to-end suites that run a bake only to read
// its results back: no process to start, no scene file to parse, no EGL display to open per bake. The
// suites that test the command line itself (exit codes, messages, files) keep running the binary
// (run_cpgi.h).
#pragma once

#include <string>

#include "core/context.h"
#include "radiosity/bake/bake.h"
#include "radiosity/gpu/egl_context.h"

namespace cpgi::test {

/// One EGL context for the whole test binary, as a cell-job server keeps one from job to job (never
/// destroyed: the driver may be gone by the time static objects are). Every in-process bake of the binary
/// takes it; the bakes that open their own (run.gl null) leave it current again when they close theirs.
inline const EglContext& sharedGl() {
  static Context ctx;
  static const EglContext* gl = new EglContext(ctx);
  return *gl;
}

/// seed1 at a coarse fixed resolution and an early stop: a bake of seconds, not minutes, for the suites
/// that test what a bake does rather than how well it lights.
inline BakeSettings quickSeed1() {
  BakeSettings s;
  s.input.scene = "seed1";
  s.atlas.densityAuto = false;
  s.atlas.params.texelsPerQuad = 4;
  s.solver.params.unshotFraction = 0.05;
  s.solver.params.itemBuffer = 128;
  s.output.views.width = 32;
  return s;
}

/// bake() of `scene` with its `cells` (the scene's own for a global bake) on the shared context.
inline BakeResult bakeHere(const Scene& scene, const CellGraph& cells, const BakeSettings& settings) {
  Context ctx;
  BakeRun run;
  run.gl = &sharedGl();
  return bake(scene, cells, settings, ctx, run);
}

/// bake() of settings.input.scene (loadBakeScene) on the shared context; its warnings in `ctx`.
inline BakeResult bakeHere(const BakeSettings& settings, Context& ctx) {
  BakeRun run;
  run.gl = &sharedGl();
  return bake(settings, ctx, run);
}
inline BakeResult bakeHere(const BakeSettings& settings) {
  Context ctx;
  return bakeHere(settings, ctx);
}

/// `bake SCENE --method cells --cells CELLS` as settings.
inline BakeSettings cellsBake(const std::string& scene, const std::string& cells) {
  BakeSettings s;
  s.input.scene = scene;
  s.cells.method = BakeMethod::Cells;
  s.cells.source = cells;
  return s;
}

}  // namespace cpgi::test
