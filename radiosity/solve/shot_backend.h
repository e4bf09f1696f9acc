// What the progressive loop (progressive_loop.h) asks of a way of seeing: the state of every atlas texel
// (radiosity, unshot residual, irradiance received), the choice of the next shooter, and one shot's
// visibility and gather. Two implementations, each made by its engine (shot_engine.h): GL item buffers on
// the EGL device (radiosity/gpu/gl_shot_engine.h, the only code that calls GL) and Embree rays on the CPU
// (radiosity/cpu/ray_shot_engine.h). The loop owns everything else: the stop and its recheck, the deadline,
// the scaling of a shot to what its eyes saw, the energy books, the time estimate and the progress reports
// (Cycles' PathTraceWork under one RenderScheduler).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/context.h"
#include "radiosity/lightmap/solve_result.h"

namespace cpgi {

/// The patch the next shot takes: the one with the largest unshot power, emitters first where a backend
/// keeps them apart.
struct ShooterChoice {
  int patch = -1;         ///< -1: none left
  double power = 0.0;     ///< its unshot power, W summed over R, G, B
  bool emitting = false;  ///< an emitter's own light still unshot (a lamp's shot: edges resampled)
  bool valid = false;     ///< a patch to shoot (a backend may test more than power > 0)
};

/// What one shot's eyes saw and its receivers gathered, before the loop scales it.
struct ShotGathered {
  double gathered = 0.0;  ///< W (R + G + B) the receivers gathered
  double covered = 1.0;   ///< share of the eyes' views covered by receivers facing them, by unshot power
  double open = 0.0;      ///< share that sees nothing (open scenes)
};

/// The sums over the atlas the loop's books read after every shot (W, R + G + B).
struct TexelSums {
  double unshot = 0.0, received = 0.0, absorbed = 0.0;
};

/// Which per-texel results a solve hands back besides the radiosity (SolveResult's fields).
struct ReadBack {
  bool transfer = false;   ///< SolveResult::incident and ::residual
  bool arrivals = false;   ///< SolveResult::arrivals (directional emission)
  bool lampFlags = false;  ///< SolveResult::lampFlags
};

class ShotBackend {
 public:
  virtual ~ShotBackend() = default;
  /// The books before the first shot: emitted (the atlas's emission and a prior shot's sources), shot (a
  /// prior shot's power), received, absorbed and unshot. Called once, first.
  virtual EnergyTotals start() = 0;
  /// The next shooter, from the state after start() or the last delivered shot.
  virtual ShooterChoice next() = 0;
  /// Shoots `choice`: the eyes' views and every receiver's gather, held until deliver(). `strong`: the
  /// shot carries at least the strong share of the light (more visibility regions, more eyes). `lamp`:
  /// an emitter's own shot (edges resampled where the backend can).
  virtual ShotGathered shoot(const ShooterChoice& choice, bool strong, bool lamp) = 0;
  /// Adds the held shot, scaled by `scale`, to its receivers' radiosity, residual and irradiance, zeroes
  /// the shooter's residual and returns the power (W, R + G + B) the receivers got.
  virtual double deliver(float scale) = 0;
  /// The sums after start() or the last deliver().
  virtual TexelSums sums() const = 0;
  /// Per atlas texel: radiosity and unshot residual now (the caller's stop per room reads them).
  virtual std::vector<glm::vec3> radiosity() = 0;
  virtual std::vector<glm::vec3> residual() = 0;
  /// Per patch, its unshot power now (W, R + G + B): what the time estimate reads to see over how many
  /// patches the light is spread (solve_estimate.h). Called now and then, not after every shot.
  virtual std::vector<double> patchUnshot() = 0;
  /// The eyes a shot of `patch` looks from (its visibility regions, times the eyes of each): what a shot's
  /// cost grows with, so the time estimate can price shots of patches that have not shot yet.
  virtual int shotEyes(int patch, bool strong) const = 0;
  /// The final per-texel results into `result` (radiosity, and what `what` asks), texels outside every
  /// patch zero. After the last shot.
  virtual void readBack(const ReadBack& what, SolveResult& result, Context& ctx) = 0;
};

}  // namespace cpgi
