// How long a progressive solve has left, from how its unshot power has fallen so far and what its shots
// cost. Once the lamps have shot, the unshot share falls neither geometrically (the same share per shot)
// nor steadily slower in one known way: each shot takes the largest unshot patch, and as the light
// spreads over more patches each shot carries less of it. The estimate fits log(unshot) = L0 - c g(n)
// with g'(n) = n^-k (k = 0 geometric, k = 1 a power law in the shot count n) to the drops over the last
// half of the shots and the quarter before, and extrapolates to the stop.
//
// While the shots are strong (SolverParams::strongShotFraction: the lit surfaces next to the lamps, seen
// from up to 16 eyes) the decay is at its least regular and the shots cost 3-4x the later ones; taking
// the last shots' rate and cost for all that was left said 54 min of a 7-min bake of house-furnished
// (and 30x the time left on house-spiral). So k is held to [0.45, 0.6] while the last half holds strong
// shots (free in [0, 0.75] after), and the time is the strong shots left at their cost plus the rest at
// the weak shots' cost, the strong ones lasting until the largest patch's share of the unshot, as of the
// last shots, would carry less than a strong shot. bench/RESULTS.md, "The solve's time estimate": the
// time left within 0.26-3.7x the truth from the 20th shot on over seven bakes, against 0.13-32x before.
#pragma once

#include <deque>
#include <vector>

namespace cpgi {

/// One point of a solve's history: shots so far, unshot share (of what the stop weighs it against), and
/// seconds since the first shot.
struct SolveSample {
  int shots = 0;
  double unshot = 1.0;
  double seconds = 0.0;
};

/// Keeps the samples since the first reflector shot and extrapolates to a stop.
class SolveEstimate {
 public:
  /// `strongPower`: the least power (W) of a strong shot, 0 if no shot is strong.
  explicit SolveEstimate(double strongPower = 0.0) : strongPower_(strongPower) {}
  /// Samples must come in order of shots (one with no more shots than the last is ignored).
  void add(const SolveSample& s);
  /// Every reflector shot, in order: whether it was strong, the seconds it took, the power it shot (W)
  /// and the unshot share after it.
  void addShot(bool strong, double seconds, double power, double unshot);
  /// Shots until the unshot share reaches `stop`; 0 when it has; < 0 while fewer than 20 shots were
  /// sampled or the share has not fallen over the last half of them.
  double shotsLeft(double stop) const;
  /// Those shots at what strong and weak shots cost (without addShot: at the seconds a shot took over
  /// the last half of the samples).
  double secondsLeft(double stop) const;

 private:
  struct Sample {
    SolveSample at;
    int strongShots;  // strong shots (addShot) by then
  };
  double logUnshotAt(double shots) const;
  double shotsLeft(double stop, double leastK, double mostK) const;
  double strongShotsLeft(double stop, double total) const;

  double strongPower_;
  std::vector<Sample> samples_;
  int strongShots_ = 0;
  // The recent shots' seconds (strong, weak) and shot power per unshot share, with their running sums.
  std::deque<double> strongSeconds_, weakSeconds_, powerPerShare_;
  double strongSum_ = 0.0, weakSum_ = 0.0;
};

}  // namespace cpgi
