// Progressive radiosity's shots by item buffers on an EGL device (thesis ch. 6, after Coombe, Harris &
// Lastra 2004): every atlas texel is a sub-patch with radiosity and residual (unshot) buffers on the GPU.
// One shot: select the patch with the largest unshot power (emitters first), build a residual pyramid over
// it (sub-shooters), render an item buffer of patch IDs from each of its regions' eyes, and let every
// visible receiver texel gather ρ ΔB F(dA → A_s) with the disk approximation. The loop around the shots is
// radiosity/solve/progressive_loop.h; this is the GL engine under it (radiosity/solve/shot_engine.h), the
// only code that calls GL.
//
// Requires a current OpenGL 4.5 context (EglContext) on the calling thread.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/gpu/egl_context.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/solve_result.h"
#include "radiosity/solve/shot_engine.h"
#include "radiosity/solve/solve.h"
#include "radiosity/solve/solve_controls.h"
#include "radiosity/solve/solver_params.h"

namespace cpgi {

/// The solver's GLSL programs, compiled once and reused by every solve given the same object (a cell
/// solve runs once per cell and round). llvmpipe translates a program to machine code at its first draw
/// or dispatch, so a fresh set per solve costs setup time and slower first shots. Belongs to the
/// context (and thread) current when the first solve used it.
class SolverPrograms {
 public:
  SolverPrograms();
  ~SolverPrograms();
  SolverPrograms(const SolverPrograms&) = delete;
  SolverPrograms& operator=(const SolverPrograms&) = delete;
  struct Set;  // gl_shot_backend.h
  /// The programs for `settings` with or without directional emission (their #defines: visibility mode,
  /// ...), compiled at first use; null when `deadline` came between two of their compilations (none kept).
  const Set* get(const SolverParams& settings, bool directionalEmission, bool binnedEmission,
                 std::chrono::steady_clock::time_point deadline);

 private:
  std::map<std::string, std::unique_ptr<Set>> sets_;  // by the programs' #defines
};

/// The GL engine: a backend per solve on `gl`'s device, with programs compiled once for every solve it
/// makes (a cell solve runs once per cell and round).
class GlShotEngine final : public ShotEngine {
 public:
  /// On `gl`, which must outlive the engine and be current on the calling thread.
  explicit GlShotEngine(const EglContext& gl);
  ~GlShotEngine() override;
  std::string name() const override { return "gl"; }
  EngineFeatures features() const override { return {.lampShots = true, .directionalEmission = true}; }
  std::unique_ptr<ShotBackend> backend(const Scene& scene, const LightmapAtlas& atlas,
                                       const SolverParams& settings, const ShotShape& shape,
                                       const FirstShot& first, Context& ctx,
                                       std::chrono::steady_clock::time_point deadline) override;
  /// A sibling context on the same display, current on the calling thread, with programs of its own.
  std::unique_ptr<ShotEngine> forThisThread() const override;
  const EglContext& context() const { return gl_; }

 private:
  explicit GlShotEngine(std::unique_ptr<EglContext> own);
  std::unique_ptr<EglContext> own_;  // a sibling's context; null when the caller's
  const EglContext& gl_;
  SolverPrograms programs_;
};

/// A solve on `gl` (radiosity/solve/solve.h on a GlShotEngine of its own, programs compiled for this solve).
SolveResult solveProgressive(const Scene& scene, const LightmapAtlas& atlas, const SolverParams& settings,
                             const EglContext& gl, Context& ctx, const SolveControls& controls = {},
                             const ShotShape& shape = {});

}  // namespace cpgi
