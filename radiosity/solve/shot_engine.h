// A way of shooting (Cycles' device): it makes the shot backend of each solve (shot_backend.h) and says
// which of the shot's features it has. Two engines: GL item buffers on an EGL device
// (radiosity/gpu/gl_shot_engine.h) and Embree rays on the CPU (radiosity/cpu/ray_shot_engine.h); which one
// runs is chosen once, from what the machine offers (radiosity/bake/, chooseShotEngines).
#pragma once

#include <chrono>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "core/scene.h"
#include "radiosity/lightmap/atlas.h"
#include "radiosity/solve/shot_backend.h"
#include "radiosity/solve/shot_shape.h"
#include "radiosity/solve/solver_params.h"

namespace cpgi {

/// Where a solve starts, besides the atlas's own emission: the first shot made before it (the scene's
/// punctual lights and sky, the lamps by rays, or a caller's prior shot: solve.h).
struct FirstShot {
  std::span<const glm::vec3> irradiance;  ///< per atlas texel (W/m²) it delivered; empty: none
  double emitted = 0.0;                   ///< W (R + G + B) its sources emitted, all counted as shot
  /// Per patch, 1 for an emitter whose own light that shot carried (lamps shot by rays): its emission
  /// shows in the radiosity but is not unshot. Empty: none.
  std::span<const char> spentEmitters;
};

/// What only some engines can do.
struct EngineFeatures {
  /// An emitter's own shot resampled at its edges, with the lamp flags and a receiver mask
  /// (ShotShape::receivers, ::readLampFlags: radiosity/solve/refined_lamp_shot.h).
  bool lampShots = false;
  /// Emission with per-texel lobes or bins and arrival moments (ShotShape::directionalEmission).
  bool directionalEmission = false;
};

class ShotEngine {
 public:
  virtual ~ShotEngine() = default;
  /// "gl" or "rays" (report.json's `backend`).
  virtual std::string name() const = 0;
  virtual EngineFeatures features() const = 0;
  /// The backend of one solve of `atlas` with its shots shaped as `shape` asks, built and ready for start();
  /// null for an atlas without patches (once the settings are checked), and null too for a set-up that
  /// `deadline` stopped: it checks the clock between its steps and within its long ones (the shooters'
  /// layout, the programs, the uploads), reporting each step to ctx as "set-up". Throws InputError for
  /// settings out of range or an atlas the engine cannot hold, SystemError for a device failure.
  virtual std::unique_ptr<ShotBackend> backend(const Scene& scene, const LightmapAtlas& atlas,
                                               const SolverParams& settings, const ShotShape& shape,
                                               const FirstShot& first, Context& ctx,
                                               std::chrono::steady_clock::time_point deadline) = 0;
  /// An engine of the same kind for the calling thread (a worker of radiosity/cells/cell_workers.h): the
  /// GL engine's needs a context of its own, current on that thread.
  virtual std::unique_ptr<ShotEngine> forThisThread() const = 0;
};

/// The engines of one bake, chosen once from what the machine offers (radiosity/bake/): `lamps` shoots
/// the emitters' own light at the output's texels, with its edges resampled where it can, and every solve
/// of a global or cells bake; `reflections` the many shots of a two-level solve's interreflection on its
/// coarse atlas (two_level_solve.h), where a software rasterizer draws item buffers slower than the CPU
/// traces rays. Both may be the same engine.
struct ShotEngines {
  ShotEngine& lamps;
  ShotEngine& reflections;
};

}  // namespace cpgi
