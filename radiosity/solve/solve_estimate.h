// How long a progressive solve has left, from where its light is: the loop is run forward on a model of
// the patches, and the shots it takes are priced at what the solve's shots have cost per eye.
//
// The unshot share falls fast over the first shots and then at a steady rate per shot that the first tenth
// of a solve does not show (seed3 after 20 shots: 6x the later rate; the furnished house keeps slowing for
// 3 000 shots), and that rate is set by how many patches the light is spread over: each shot takes the
// patch holding the most, so in the steady state every lit patch is shot when it fills up to a common
// level. So the estimate keeps each patch's unshot power (ShotBackend::patchUnshot) and where the light
// shot so far came back unshot: patch i got a share w_i of it, and each W shot gave back f W. The model
// shoots the patch with the most, gives f of its power back spread as w, and counts the shots until the
// unshot share reaches the stop (as the loop weighs it). The strong shots among them (those carrying at
// least the strong power) and the weak ones are priced at the seconds per eye the solve's own strong and
// weak shots took, times the eyes of each shooter (ShotBackend::shotEyes): a wall's shot looks from
// 16 times the eyes of a book's. bench/RESULTS.md, "The time estimate from the patches' light".
//
// Where the bake stops per room (RoomStop, radiosity/solve/ambient.h), the loop's stop at the unshot share
// is only its first ask: the office shot on past six refusals, 41 % of its solve, to 0.12 % unshot. So the
// model keeps each cell's unshot power and light as its shots move them, and at each of its own stops asks
// the bake's rule of them, refused shooting on to the loop's next ask (kStopRecheck) or its bound
// (refusedStopBound), as the loop does.
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "radiosity/solve/ambient.h"

namespace cpgi {

/// The patches as the model shoots them.
struct PatchLight {
  std::vector<double> unshot;   ///< per patch, its unshot power (W, R + G + B)
  std::vector<double> landing;  ///< per patch, its share of the light a shot gives back unshot (sum 1)
  double returned = 0.0;        ///< W given back unshot per W shot (in [0, 1))
  double reflected = 0.0;       ///< W reflected so far (received − absorbed)
  double emitted = 0.0;         ///< W emitted: the stop weighs the unshot against min(emitted, reflected)
};

/// The stop per room as the model asks it: the loop's acceptStop, cell by cell.
struct ModelRoomStop {
  std::vector<int> patchCell;                     ///< per patch, its entry in CellLight
  CellLight now;                                  ///< the cells' light and unshot power as the model starts
  std::function<bool(const CellLight&)> accepts;  ///< the rule (RoomStop::accepts)
  int shots = 0;                                  ///< the loop's shots so far
  int bound = 0;          ///< the shot the loop stops at past a refused stop (0: none refused yet)
  size_t receivers = 0;   ///< refusedStopBound's receivers (the loop's atlas texels)
  double texelShots = 0;  ///< and its least work past the first refusal
};

/// The shots the model takes until the stop.
struct ModelShots {
  std::vector<int> patches;  ///< the shooters, in order
  std::vector<char> strong;  ///< per shot, 1 if it carried at least the strong power
  double beyond = 0.0;       ///< shots after these, extrapolated where the model ran out of work
  bool reached = false;      ///< the stop was reached (else the light ran out: a share that cannot fall)
  int refusals = 0;          ///< stops the rule per room refused
  bool bounded = false;      ///< stopped at the loop's bound past a refused stop
  double count() const { return double(patches.size()) + beyond; }
};

/// Runs the loop forward on `light` until the unshot share reaches `stop`: each shot takes the
/// patch with the most unshot power P (strong if P >= `strongPower`), zeroes it and adds
/// returned × P × landing to every patch. After `work` patch updates (shots × patches) it stops shooting
/// and extrapolates the rest at the rate per shot of the last half of its shots. With `rooms`, each stop
/// is asked of the rule per room (each cell's unshot power scaled as its patches' has been, its light
/// grown by what landed on them); refused, the stop moves to kStopRecheck of the share, up to the bound.
ModelShots simulateShots(const PatchLight& light, double stop, double strongPower, double work,
                         const ModelRoomStop* rooms = nullptr);

/// The stop per room as the loop hands it to the estimate (ModelRoomStop without the loop's state).
struct EstimateRoomStop {
  std::vector<int> patchCell;
  std::function<bool(const CellLight&)> accepts;
  size_t receivers = 0;
  double texelShots = 0.0;
};

/// Where the loop stands when the estimate looks.
struct LoopState {
  int shots = 0;               ///< shots so far
  std::vector<double> unshot;  ///< per patch, its unshot power (W, R + G + B)
  double reflected = 0.0;      ///< W reflected so far (received − absorbed)
  double emitted = 0.0;        ///< W emitted
  double stop = 0.0;           ///< the unshot stop now (lowered past a refused stop)
  int bound = 0;               ///< past a refused stop, the shot the loop stops at (0: none)
  double seconds = 0.0;        ///< CPU seconds since the solve started
};

/// The solve's estimate, fed by the loop after each shot (addShot) and, when it asks (wantsPatches),
/// with the patches' state (observe).
class SolveEstimate {
 public:
  /// `strongPower`: the least power (W) of a strong shot; `rooms`: the loop's stop per room, if any.
  explicit SolveEstimate(double strongPower, EstimateRoomStop rooms = {})
      : strongPower_(strongPower), rooms_(std::move(rooms)) {}

  /// Every reflector shot, in order: the shooter, whether strong, the eyes it looked from, its power (W)
  /// and the seconds it took.
  void addShot(int patch, bool strong, int eyes, double power, double seconds);
  /// Whether observe() would run the model now: `seconds` since the solve started, after `shots` shots,
  /// towards `stop`. The model runs after kMinShots reflector shots and then again once the solve has
  /// spent kModelShare's inverse times the model's last run, or has passed the shots it foresaw.
  bool wantsPatches(int shots, double stop, double seconds) const;
  /// The loop's state (the first call sets where the light is counted from), the eyes a shot of a patch
  /// looks from and, with the stop per room, the cells' light now (called only when the model runs).
  /// Runs the model when wantsPatches says so.
  void observe(LoopState state, const std::function<int(int patch, bool strong)>& eyes,
               const std::function<CellLight()>& cells = {});
  /// Shots left after `shots` shots, from the model's last run; < 0 before it ran or when it found the
  /// stop out of reach.
  double shotsLeft(int shots) const;
  /// Those shots priced at what the solve's recent shots of as many eyes and the same strength cost
  /// (seconds; < 0 as shotsLeft).
  double secondsLeft(int shots) const;

 private:
  double secondsPerEye(bool strong) const;
  double shotSeconds(bool strong, int eyes) const;
  ModelShots runModel(const LoopState& state, std::vector<double> unshot,
                      const std::function<CellLight()>& cells) const;

  double strongPower_;
  EstimateRoomStop rooms_;
  // Where the light is counted from: the patches' unshot power at the first observe, and the power
  // each patch has shot since.
  std::vector<double> firstUnshot_, shotSince_;
  double shotPowerSince_ = 0.0;
  int reflectorShots_ = 0;
  // The recent shots' seconds and eyes, strong and weak, with their running sums.
  struct Window {
    std::deque<double> seconds, eyes;
    double secondsSum = 0.0, eyesSum = 0.0;
    void push(double s, double e, size_t most);
  };
  Window strongCost_, weakCost_;
  // The same by strength and eyes: a shot's cost is set by its eyes, but not in proportion to them (the
  // house's weak shots of 2, 4 and 8 eyes: 0.0095, 0.033 and 0.064 CPU s).
  std::map<std::pair<bool, int>, Window> costByEyes_;
  // The model's last run: the shot it ran after, its stop, its shots' strength and eyes in order, and the
  // extrapolated shots' count and the model's last weak shots they repeat.
  using ShotKind = std::pair<bool, int>;
  bool ran_ = false;
  int modelShot_ = 0;
  double modelStop_ = 0.0, modelSeconds_ = 0.0, modelCost_ = 0.0;
  bool modelReached_ = false;
  std::vector<ShotKind> modelShots_, beyondShots_;
  double beyond_ = 0.0;
};

}  // namespace cpgi
