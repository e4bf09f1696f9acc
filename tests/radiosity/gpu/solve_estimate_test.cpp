#include "radiosity/gpu/solve_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cpgi {
namespace {

// A solve whose unshot share falls as `unshot(n)` over n shots, one second a shot, sampled every 10 shots
// (every shot up to 100).
template <class F>
SolveEstimate sampled(F unshot, int upTo) {
  SolveEstimate e;
  for (int n = 0; n <= upTo; n += upTo >= 100 ? 10 : 1) e.add({n, unshot(n), double(n)});
  return e;
}

// Both pure decays are extrapolated exactly: the same share per shot, and a power of the shot count.
TEST(SolveEstimate, ExtrapolatesAGeometricAndAPowerLawDecay) {
  const double stop = 0.01;
  {  // 0.5 × 0.999^n: 1 % after 3 912 shots.
    const SolveEstimate e = sampled([](int n) { return 0.5 * std::pow(0.999, n); }, 1000);
    const double left = e.shotsLeft(stop), truth = std::log(0.5 / stop) / -std::log(0.999) - 1000;
    EXPECT_NEAR(left, truth, 0.01 * truth);
    EXPECT_NEAR(e.secondsLeft(stop), left, 1e-6 * left);  // one second a shot
  }
  {  // 0.5 / (n + 1): 1 % after 49 shots... at n + 1 = 50; sampled to 20.
    const SolveEstimate e = sampled([](int n) { return 0.5 / (n + 1.0); }, 20);
    EXPECT_NEAR(e.shotsLeft(stop), 49.0 - 20.0, 0.5);
  }
  {  // A decay slowing between the two (rate ∝ n^-0.5) lands between their figures.
    const SolveEstimate e = sampled([](int n) { return 0.5 * std::exp(-0.05 * std::sqrt(n + 1.0)); }, 1000);
    const double truth = std::pow(std::log(0.5 / stop) / 0.05, 2.0) - 1.0 - 1000.0;
    EXPECT_NEAR(e.shotsLeft(stop), truth, 0.05 * truth);
  }
}

TEST(SolveEstimate, SaysNothingBeforeThreeShotsOrWhileTheShareDoesNotFall) {
  SolveEstimate e;
  EXPECT_LT(e.shotsLeft(0.01), 0.0);
  e.add({5, 0.5, 1.0});
  e.add({7, 0.4, 2.0});
  EXPECT_LT(e.shotsLeft(0.01), 0.0);  // 2 shots
  e.add({20, 0.4, 3.0});
  e.add({30, 0.4, 4.0});
  EXPECT_LT(e.shotsLeft(0.01), 0.0);  // flat over the window
  e.add({40, 0.005, 5.0});
  EXPECT_EQ(e.shotsLeft(0.01), 0.0);  // past the stop
}

}  // namespace
}  // namespace cpgi
