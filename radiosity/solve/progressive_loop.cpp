#include "radiosity/solve/progressive_loop.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "core/progress.h"

#include "radiosity/solve/solve_estimate.h"

namespace cpgi {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A report of the loop: how far towards the stop, the shots, the unshot share and the time left in wall
// and CPU seconds (negative: no estimate yet; the loop owns its estimate, so a printer never extrapolates
// one from the fraction, which is not linear in time).
Progress solveProgress(double fraction, int shots, double unshot, double secondsLeft, double cpuSecondsLeft) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "shots %d, unshot %.2f%%", shots, 100.0 * unshot);
  Progress p{"solve", fraction, buf};
  p.shots = shots;
  p.unshot = unshot;
  p.secondsLeft = secondsLeft;
  p.cpuSecondsLeft = cpuSecondsLeft;
  p.ownsTimeLeft = true;
  return p;
}

// The books of the solve as the loop keeps them, and the stop's measure of the unshot light.
struct Books {
  EnergyTotals e;
  void read(const TexelSums& s) { e.unshot = s.unshot, e.received = s.received, e.absorbed = s.absorbed; }
  // The stop weighs the unshot power against the light the surfaces reflect when that is less than what
  // the lamps emit: a lamp in a black housing sends 1 % of its power out and the rest is absorbed at
  // once, so 1 % of the emitted power was the whole of the rooms' light, and the solve stopped after the
  // lamp's shot (spot-door: the lit room +5 % at the default stop, +1.6 % converged). In a scene whose
  // surfaces reflect as much as is emitted, this is the emitted power.
  double unshotShare() const {
    const double scale = std::min(e.emitted, e.received - e.absorbed);
    return scale > 0.0 ? e.unshot / scale : 1.0;
  }
};

// What of the light still unshot will leave the scene rather than arrive on a surface: the share of the
// reflectors' recent shots (kWindow of them, weighed by their power) that their eyes saw open
// (ShotGathered::open). The unshot stop weighs the light that can still arrive, so a daylit map stops where
// a closed scene with as much light left to arrive would: oa_dm2's shots sent about a third of their power
// out through the sky, and 10 000 shots to 1 % unshot counted it as if it would all land. A closed scene's
// shots see nothing open: 0, the stop as before. At most kMost: the recent shooters are a sample of the
// patches still holding light, and the indoor ones among them may see less sky.
class LeavingShare {
 public:
  void add(double power, double open) {
    shots_.push_back({power, power * std::clamp(open, 0.0, 1.0)});
    power_ += shots_.back().power, open_ += shots_.back().open;
    if (shots_.size() > kWindow) {
      power_ -= shots_.front().power, open_ -= shots_.front().open;
      shots_.pop_front();
    }
  }
  double share() const { return power_ > 0.0 ? std::clamp(open_ / power_, 0.0, kMost) : 0.0; }

 private:
  static constexpr size_t kWindow = 256;
  static constexpr double kMost = 0.5;
  struct Shot {
    double power, open;
  };
  std::deque<Shot> shots_;
  double power_ = 0.0, open_ = 0.0;
};

// The factor a shot is scaled by. A shot whose eyes see nothing open delivers what they see covered; no
// shot delivers more than its power (design.md §5: received ≤ shot) nor more than its eyes see covered or
// open. The receivers' form factors, each gated by one eye's visibility, share the shot out but do not sum
// to it: an eye drawn beside an occluder hides what most of its region sees, and the occluder gets only the
// region-wide form factor (seed3's room C floor shots delivered 78 %, and 6 % of the light vanished); an
// eye that sees more than its region made light up (1.07× on seed1). Where open space is in view, one
// eye's share of it is not its region's, so the gathered figure stands. Over the target by anything beyond
// float rounding, the shot is scaled back: shots a little over their power added up (0.23 % of the light
// made in two closed rooms, EnergyConservation.ZeroThicknessPartitionLosesNoLight); not with emission
// lobes, whose normalisation the tolerance covers (+1.1e-3 measured).
constexpr double kTolerance = 2e-3;
float shotScale(const ShotGathered& seen, double shotPower, bool lobedEmission) {
  constexpr double kClosedBelow = 1e-3;  // open share under which the view counts as closed
  const double target = seen.open < kClosedBelow
                            ? shotPower * std::min(seen.covered, 1.0)
                            : std::min(seen.gathered, shotPower * std::min(seen.covered + seen.open, 1.0));
  const double over = lobedEmission ? kTolerance : 1e-5;
  if (seen.gathered > 0.0 &&
      (seen.gathered - target > over * shotPower || target - seen.gathered > kTolerance * shotPower))
    return float(target / seen.gathered);
  return 1.0f;
}

// The progress line and the time estimate (solve_estimate.h) from the reflectors' shots and the patches'
// light. The estimate is made in the process's CPU seconds, which a machine loaded by others does not
// stretch, and said in wall seconds at the CPU rate of the last kRateWindow seconds: a load that changes
// after that skews the wall figure by as much (bench/RESULTS.md, "Progress from the first second").
class LoopProgress {
 public:
  LoopProgress(double strongAt, const LoopControls& controls, ShotBackend& backend, Context& ctx)
      : estimate_(strongAt, roomStop(controls)),
        cellLight_(controls.roomStop.cellLight),
        backend_(backend),
        ctx_(ctx) {}
  /// One shot as the progress sees it.
  struct Shot {
    int shots;            ///< shots so far, this one included
    int patch;            ///< its shooter
    bool strong;          ///< it carried the strong power
    double power;         ///< W it shot
    double unshot;        ///< the stop's share after it
    double emittedShare;  ///< the unshot against the emitted power, shown while the emitters still shoot
                          ///< (the stop's share weighs it against the light reflected so far, and with
                          ///< lamps yet to shoot that is over 100 %)
    double reflected;     ///< W reflected so far (received − absorbed)
    double emitted;       ///< W emitted
    double stopAt;        ///< the stop's share now
    int bound;  ///< past a refused stop, the shot the loop stops at whatever acceptStop says (0: none)
    bool nextIsEmitter;  ///< the next shot is an emitter's own
  };
  void shot(const Shot& s) {
    const double elapsed = secondsSince(start_), cpu = processCpuSeconds() - cpuStart_;
    if (reflecting_)
      estimate_.addShot(s.patch, s.strong, backend_.shotEyes(s.patch, s.strong), s.power, cpu - lastShotCpu_);
    if (!reflecting_ && !s.nextIsEmitter) reflecting_ = true;
    if (reflecting_ && estimate_.wantsPatches(s.shots, s.stopAt, cpu)) {
      std::function<CellLight()> cells;
      if (cellLight_) cells = [this] { return cellLight_(backend_.radiosity(), backend_.residual()); };
      estimate_.observe(
          {s.shots, backend_.patchUnshot(), s.reflected, s.emitted, s.stopAt, s.bound, cpu},
          [this](int patch, bool strong) { return backend_.shotEyes(patch, strong); }, cells);
    }
    lastShotCpu_ = processCpuSeconds() - cpuStart_;  // the model's own run is not a shot's cost
    if (s.bound > 0 && refusedAt_ == 0) refusedAt_ = s.shots, refusedCpu_ = cpu;
    if (elapsed - lastReport_ <= kReportSeconds) return;
    rates_.push_back({elapsed, cpu});
    while (rates_.size() > 2 && rates_[1].wall < elapsed - kRateWindow) rates_.pop_front();
    // Towards the current stop: past a refused one (acceptStop), the next ask or the bound, whichever
    // comes first: the shots since the refusal, at their own pace, towards the bound.
    double fraction = std::clamp(std::log(std::max(s.unshot, 1e-12)) / std::log(s.stopAt), 0.0, 1.0);
    double left = estimate_.secondsLeft(s.shots), shotsLeft = estimate_.shotsLeft(s.shots);
    if (s.bound > 0 && s.shots > refusedAt_) {
      const double perShot = (cpu - refusedCpu_) / double(s.shots - refusedAt_);
      const double toBound = double(std::max(s.bound - s.shots, 0));
      fraction = std::max(fraction, double(s.shots) / double(s.bound));
      left = left >= 0.0 ? std::min(left, perShot * toBound) : perShot * toBound;
      shotsLeft = shotsLeft >= 0.0 ? std::min(shotsLeft, toBound) : toBound;
    }
    const double shown = reflecting_ ? std::min(s.unshot, 1.0) : s.emittedShare;
    Progress p = solveProgress(fraction, s.shots, shown, left >= 0.0 ? left / cpuRate() : -1.0, left);
    p.shotsLeft = shotsLeft;
    ctx_.progress(p);
    lastReport_ = elapsed;
  }

 private:
  static constexpr double kReportSeconds = 0.25, kRateWindow = 20.0;
  struct Stamp {
    double wall, cpu;
  };
  // CPU seconds per wall second over the window (1 before a quarter of a second of it).
  double cpuRate() const {
    const double wall = rates_.back().wall - rates_.front().wall;
    const double cpu = rates_.back().cpu - rates_.front().cpu;
    return wall >= kReportSeconds && cpu > 0.0 ? cpu / wall : 1.0;
  }

  // The stop per room as the estimate asks it, with the texels the loop's stop asks it of (the caller's
  // acceptStop): empty without one.
  static EstimateRoomStop roomStop(const LoopControls& c) {
    if (!c.acceptStop || !c.roomStop.accepts || !c.roomStop.cellLight) return {};
    return {c.patchCell, c.roomStop.accepts, c.roomStop.texelCell.size(), c.refusedStopTexelShots};
  }

  SolveEstimate estimate_;
  std::function<CellLight(const std::vector<glm::vec3>&, const std::vector<glm::vec3>&)> cellLight_;
  ShotBackend& backend_;
  Context& ctx_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double cpuStart_ = processCpuSeconds();
  std::deque<Stamp> rates_{{0.0, 0.0}};
  bool reflecting_ = false;  // the emitters' own shots are over
  double lastShotCpu_ = 0.0, lastReport_ = -1.0;
  int refusedAt_ = 0;  // the shot of the first refused stop, and its CPU time
  double refusedCpu_ = 0.0;
};

}  // namespace

// The most work, in shots × receiver texels, "as many shots again" (kStopRefusedShots) may add past the
// first refused stop; the floor (kStopRefusedTexelShots) still holds above it. About two CPU minutes of
// shots on the rays engine (2.3e-7 CPU s a shot and receiver texel): a daylit game map reaches the unshot
// stop after 10 000 shots over 200 000 coarse texels, and as many again was another 8 CPU minutes, doubling
// its bake, where a house's or a plan's few hundred shots stay under it.
constexpr double kMostRefusedTexelShots = 5.0e8;

int refusedStopBound(int shots, size_t receivers, double texelShots) {
  const double texels = double(std::max<size_t>(receivers, 1));
  const double again = std::min(kStopRefusedShots * double(shots), kMostRefusedTexelShots / texels);
  const double extra = std::max(again, texelShots / texels);
  return shots + std::max(1, int(std::min(std::ceil(extra), 1e9)));
}

SolveResult runProgressiveLoop(ShotBackend& backend, const ShotSettings& settings,
                               const LoopControls& controls, Context& ctx) {
  const auto start = std::chrono::steady_clock::now();
  SolveResult result;
  Books books{backend.start()};
  EnergyTotals& e = books.e;
  result.history.push_back(e);
  // Before the first shot, once the settings are checked and the backend is built: the CLI prints the
  // bake's size here (apps/bake_command.cpp).
  ctx.progress(solveProgress(0.0, 0, std::min(books.unshotShare(), 1.0), -1.0, -1.0));
  const double strongAt =
      controls.strongShotPower > 0.0 ? controls.strongShotPower : settings.strongShotFraction * e.emitted;
  LoopProgress progress(strongAt, controls, backend, ctx);
  // The stop is on the light that can still arrive: the unshot share less what of it leaves the scene.
  LeavingShare leaving;
  const auto arrivingShare = [&] { return books.unshotShare() * (1.0 - leaving.share()); };
  double stopAt = settings.unshotFraction;
  int bound = 0;  // past the first refused stop, the shot the loop stops at (kStopRefusedShots)
  ShooterChoice next = backend.next();
  while (e.emitted > 0.0 && result.shots < settings.maxShots && next.valid) {
    if (bound > 0 && result.shots >= bound) {
      result.stopBounded = true;
      break;
    }
    if (arrivingShare() <= stopAt) {
      if (!controls.acceptStop) break;
      ++result.stopChecks;
      const std::vector<glm::vec3> radiosity = backend.radiosity();
      if (controls.acceptStop(radiosity, backend.residual())) break;
      stopAt = arrivingShare() * kStopRecheck;
      if (bound == 0) {
        result.stopRefusedAt = result.shots;
        bound = refusedStopBound(result.shots, radiosity.size(), controls.refusedStopTexelShots);
      }
    }
    if (next.power < controls.minShotPower) break;
    if (std::chrono::steady_clock::now() >= controls.deadline) {
      result.timedOut = true;
      break;
    }
    const ShooterChoice shooter = next;
    const bool strong = shooter.power >= strongAt;
    const ShotGathered seen = backend.shoot(shooter, strong, shooter.emitting && controls.emittersAreLamps);
    if (shooter.power > 0.0) e.worstShotGain = std::max(e.worstShotGain, seen.gathered / shooter.power);
    const bool given = !controls.patchShotScale.empty();
    const float scale = given ? controls.patchShotScale[size_t(shooter.patch)]
                              : shotScale(seen, shooter.power, controls.lobedEmission);
    const double delivered = backend.deliver(scale);
    if (!shooter.emitting) leaving.add(shooter.power, seen.open);
    e.shot += shooter.power;
    books.read(backend.sums());
    // A shot scaled by a coarser shot's factor checks nothing here (its receivers are only some).
    if (!given && delivered > shooter.power * (1.0 + kTolerance)) e.created += delivered - shooter.power;
    ++result.shots;
    result.shooters.push_back(shooter.patch);
    result.shotScales.push_back(scale);
    result.history.push_back(e);
    next = backend.next();
    if (!given)
      // The progress and the estimate read the unshot share, so the stop is said as the share it is now.
      progress.shot({result.shots, shooter.patch, strong, shooter.power, books.unshotShare(),
                     e.unshot / e.emitted, e.received - e.absorbed, e.emitted,
                     stopAt / (1.0 - leaving.share()), bound, next.emitting});
  }
  result.energy = e;
  if (result.stopBounded) {
    char note[200];
    std::snprintf(note, sizeof note,
                  "the stop per room was still refused after %d shots (first refused at shot %d, unshot "
                  "%.3f%% now): stopped at its bound",
                  result.shots, result.stopRefusedAt, 100.0 * books.unshotShare());
    ctx.warn(note);
  }
  if (e.created > 1e-4 * e.emitted) {
    char note[160];
    std::snprintf(
        note, sizeof note,
        "the solve created %.3g W of light (%.2f%% of the emitted; worst shot received %.3fx its power)",
        e.created, 100.0 * e.created / e.emitted, e.worstShotGain);
    ctx.warn(note);
  }
  result.unshotFraction = e.emitted > 0.0 ? e.unshot / e.emitted : 0.0;
  ctx.addTiming("solve: shots", secondsSince(start));
  Progress last = solveProgress(1.0, result.shots, std::min(books.unshotShare(), 1.0), -1.0, -1.0);
  if (leaving.share() > 0.0) {
    char leaves[64];
    std::snprintf(leaves, sizeof leaves, ", %.0f%% of it leaving the scene", 100.0 * leaving.share());
    last.status += leaves;
  }
  ctx.progress(last);
  return result;
}

}  // namespace cpgi
