// How long a progressive solve has left, from how its unshot power has fallen so far. Once the lamps
// have shot, the unshot share falls neither geometrically (the same share per shot) nor steadily slower
// in one known way: each shot takes the largest unshot patch, and as the light spreads over more patches
// each shot carries less of it. The estimate fits log(unshot) = L0 - c g(n) with g'(n) = n^-k (k = 0
// geometric, k = 1 a power law in the shot count n; k at most 0.75) to the drops over the last half of
// the shots and the quarter before, and extrapolates to the stop. On house-furnished (16 759 patches,
// 8 060 shots to 1 %) it said 7 300 shots in all after 200, 5 300 after 720, 6 300 to 9 800 from 1 300 to
// 5 000 and within 10 % after 5 600; the old rate over all shots since the first reflector shot, taken
// as constant, said 54 s of what took 650 s.
#pragma once

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
  /// Samples must come in order of shots (one with no more shots than the last is ignored).
  void add(const SolveSample& s);
  /// Shots until the unshot share reaches `stop`; 0 when it has; < 0 while fewer than 20 shots were
  /// sampled or the share has not fallen over the last half of them.
  double shotsLeft(double stop) const;
  /// shotsLeft at the seconds a shot took over the last half of the shots (the early, strong shots cost
  /// more than the many after them).
  double secondsLeft(double stop) const;

 private:
  /// log(unshot) at `shots`, interpolated between the samples.
  double logUnshotAt(double shots) const;
  std::vector<SolveSample> samples_;
};

}  // namespace cpgi
