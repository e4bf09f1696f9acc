// Progressive radiosity's shots by Embree rays on the CPU (issue 13 item 3): where there is no GPU, the many
// shots of the interreflection on a two-level solve's coarse atlas (radiosity/solve/two_level_solve.h) cost
// less as rays from each eye than as item buffers drawn by llvmpipe. Every shot is the GL engine's
// reflector shot (ray_shot.h): the same regions, eyes drawn by power, pieces and form factors; the loop
// around them (radiosity/solve/progressive_loop.h) scales each to what its eyes saw covered, and shooters
// emit with the cells' portal lobes and bins as the GL programs do (shaders/directional.glsl). The lamps'
// own shots (edges resampled, replicated eyes) stay on the GL engine.
#pragma once

#include <memory>
#include <string>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/shot_engine.h"

namespace cpgi {

/// The rays engine: a backend per solve, its shots traced through every scene triangle. It has no lamp
/// shot of its own (an emitter shoots as a reflector does; the lamps' first shot by rays is the solve's,
/// SolverParams::lampRays).
class RayShotEngine final : public ShotEngine {
 public:
  std::string name() const override { return "rays"; }
  EngineFeatures features() const override { return {.directionalEmission = true}; }
  std::unique_ptr<ShotBackend> backend(const Scene& scene, const LightmapAtlas& atlas,
                                       const SolverParams& settings, const ShotShape& shape,
                                       const FirstShot& first, Context& ctx,
                                       std::chrono::steady_clock::time_point deadline) override;
  std::unique_ptr<ShotEngine> forThisThread() const override { return std::make_unique<RayShotEngine>(); }
};

}  // namespace cpgi
