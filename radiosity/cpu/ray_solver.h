// Progressive radiosity on the CPU, by Embree rays (issue 13 item 3): where there is no GPU, the many
// shots of the interreflection on a two-level solve's coarse atlas (radiosity/gpu/two_level_solve.h) cost
// less as rays from each eye than as item buffers drawn by llvmpipe. Every shot is the GPU solver's
// reflector shot (ray_shot.h): the same regions, eyes drawn by power, pieces, form factors, and the same
// scaling of what a shot delivered to what its eyes saw covered. The lamps' own shots (edges resampled,
// replicated eyes) and directional emission stay on the GPU solver.
#pragma once

#include <chrono>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/lightmap/shot_settings.h"
#include "radiosity/lightmap/solve_result.h"

namespace cpgi {

/// The shared settings (shot_settings.h) and the rays' own.
struct RaySolveParams : ShotSettings {
  /// Cosine-distributed rays per region eye measuring what it sees covered (the item buffer's coverage).
  int coverageRays = 1024;
  /// Eyes per region for the receivers far from it (RayShotParams::eyesPerRegion). On seed3 at --density
  /// auto, per cell A / B / C over three draws: 1 eye 1.16 / 3.77 / 3.22 % in 2.4 s, 2 eyes 0.99 / 3.47 /
  /// 3.16 % in 3.6 s, 4 eyes 0.94 / 3.36 / 3.03 % in 5.2 s (item buffers: 1.94 / 4.02 / 3.59 % in 14.7 s).
  int eyesPerRegion = 2;
  /// Eyes per region in the strong shots (strongShotFraction), which carry most of the light through
  /// openings. 2 → 4, mean of 2–3 eye draws, worst room and CPU: seed3 C 3.16 → 3.01 % (+11 % CPU),
  /// openings C 5.47 → 5.01 % (+13 %), seed1 B 2.26 → 1.89 % (+24 %).
  int strongEyesPerRegion = 4;
};

struct RaySolveControls {
  /// A first shot made elsewhere (PriorShot in gpu_solver.h): per atlas texel the irradiance it delivered,
  /// and the power its sources emitted. Empty: none.
  std::span<const glm::vec3> priorIrradiance = {};
  double priorEmitted = 0.0;
  /// Also return every texel's irradiance and residual (SolveResult::incident, ::residual).
  bool readTransfer = false;
  /// As SolveControls::acceptStop: asked at the stop with the radiosity and residual; false shoots on until
  /// the unshot share has fallen to `stopRecheck` of what it was.
  std::function<bool(const std::vector<glm::vec3>& radiosity, const std::vector<glm::vec3>& residual)>
      acceptStop = {};
  double stopRecheck = 0.7;
  /// The number the shots count from in the eyes' draw.
  uint32_t firstShotNumber = 0;
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
};

/// Solves `atlas` by shots whose visibility is traced by rays through every scene triangle. The atlas's
/// emission shoots as reflectors' light does; the scene's punctual lights are not shot (a prior shot stands
/// for them). Energy, history, shooters and shot scales are those the GPU solver reports.
SolveResult solveByRays(const Scene& scene, const LightmapAtlas& atlas, const RaySolveParams& params,
                        Context& ctx, const RaySolveControls& controls = {});

}  // namespace cpgi
