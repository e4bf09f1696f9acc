// Cells solved side by side: the worker pool runs every task once, on several threads each with its own
// GL context, passes task exceptions on, and a cells solve with several jobs gives exactly the serial
// numbers (the syncs combine the solves in cell order).
#include "radiosity/cells/cell_workers.h"
#include "radiosity/gpu/gl_shot_engine.h"

#include <atomic>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "radiosity/cells/cell_solver.h"
#include "radiosity/gpu/gl.h"
#include "scenes/seed_scenes.h"

namespace cpgi {
namespace {

TEST(CellWorkers, EveryTaskOnceOnSeveralContexts) {
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellWorkers workers(3, gl);
  EXPECT_EQ(workers.jobs(), 3);
  for (int batch = 0; batch < 3; ++batch) {
    std::vector<int> runs(20, 0);
    std::mutex m;
    std::set<const EglContext*> contexts;
    workers.run(runs.size(), ctx, [&](size_t i, ShotEngine& engine, Context& taskCtx) {
      const EglContext& context = dynamic_cast<GlShotEngine&>(engine).context();
      // Real GL work on this thread's context: a buffer written and read back.
      const uint32_t value = uint32_t(i) * 7u + 1u;
      gl::Buffer b = gl::makeBuffer(sizeof value, &value);
      uint32_t back = 0;
      glGetNamedBufferSubData(b.get(), 0, sizeof back, &back);
      if (back != value) throw std::runtime_error("read back another context's data");
      taskCtx.warn("task " + std::to_string(i));
      std::lock_guard lock(m);
      ++runs[i];
      contexts.insert(&context);
    });
    for (int r : runs) EXPECT_EQ(r, 1);
    EXPECT_GE(contexts.size(), 1u);
  }
  // Warnings arrive in task order, whichever thread ran the task.
  ASSERT_EQ(ctx.warnings().size(), 60u);
  EXPECT_EQ(ctx.warnings()[0], "task 0");
  EXPECT_EQ(ctx.warnings()[19], "task 19");
}

TEST(CellWorkers, TaskExceptionsReachTheCaller) {
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellWorkers workers(2, gl);
  std::atomic<int> ran{0};
  EXPECT_THROW(workers.run(6, ctx,
                           [&](size_t i, ShotEngine&, Context&) {
                             ++ran;
                             if (i == 4) throw std::runtime_error("task 4 failed");
                           }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 6);  // the other tasks still ran
  // The pool still works afterwards.
  ran = 0;
  workers.run(5, ctx, [&](size_t, ShotEngine&, Context&) { ++ran; });
  EXPECT_EQ(ran.load(), 5);
}

TEST(CellWorkers, ParallelCellsSolveEqualsSerial) {
  const SeedScene s = makeSeedScene(1);
  Context ctx;
  EglContext context(ctx);
  GlShotEngine gl(context);
  CellSolveParams params;
  params.atlas.texelsPerQuad = 4;
  params.solver.unshotFraction = 0.02;
  params.solver.itemBuffer = 256;
  const LightmapAtlas atlas = buildAtlas(s.scene, findQuads(s.scene), params.atlas, ctx);
  const SolveResult serial = solveCells(s.scene, s.cells, atlas, params, gl, ctx);
  params.jobs = 3;
  const SolveResult parallel = solveCells(s.scene, s.cells, atlas, params, gl, ctx);
  ASSERT_EQ(parallel.radiosity.size(), serial.radiosity.size());
  size_t differing = 0;
  for (size_t i = 0; i < serial.radiosity.size(); ++i)
    differing += parallel.radiosity[i] != serial.radiosity[i];
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(parallel.shots, serial.shots);
  EXPECT_EQ(parallel.perCell->rounds, serial.perCell->rounds);
  ASSERT_EQ(parallel.perCell->cells.size(), serial.perCell->cells.size());
  for (size_t c = 0; c < serial.perCell->cells.size(); ++c) {
    EXPECT_EQ(parallel.perCell->cells[c].sent, serial.perCell->cells[c].sent);
    EXPECT_EQ(parallel.perCell->cells[c].absorbed, serial.perCell->cells[c].absorbed);
    EXPECT_EQ(parallel.perCell->cells[c].shots, serial.perCell->cells[c].shots);
  }
  EXPECT_GE(serial.perCell->rounds, 2);
}

}  // namespace
}  // namespace cpgi
