#include "radiosity/solve/solve_estimate.h"

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

// A geometric decay is extrapolated exactly, one whose rate falls as n^-0.5 nearly; a power law in the
// shot count (rate ∝ 1/n) is taken as slowing at most as n^-0.75, so its figure lies between the
// geometric one and the truth.
TEST(SolveEstimate, ExtrapolatesHowTheDecaySlows) {
  const double stop = 0.01;
  {  // 0.5 × 0.999^n: 1 % after 3 912 shots.
    const SolveEstimate e = sampled([](int n) { return 0.5 * std::pow(0.999, n); }, 1000);
    const double left = e.shotsLeft(stop), truth = std::log(0.5 / stop) / -std::log(0.999) - 1000;
    EXPECT_NEAR(left, truth, 0.01 * truth);
    EXPECT_NEAR(e.secondsLeft(stop), left, 1e-6 * left);  // one second a shot
  }
  {  // rate ∝ n^-0.5.
    const SolveEstimate e = sampled([](int n) { return 0.5 * std::exp(-0.05 * std::sqrt(n + 1.0)); }, 1000);
    const double truth = std::pow(std::log(0.5 / stop) / 0.05, 2.0) - 1.0 - 1000.0;
    EXPECT_NEAR(e.shotsLeft(stop), truth, 0.05 * truth);
  }
  {  // 0.5 × 100 / (n + 100): 1 % at n = 4 900; the last half's geometric rate says 1 090 more.
    const SolveEstimate e = sampled([](int n) { return 0.5 * 100.0 / (n + 100.0); }, 1000);
    const double left = e.shotsLeft(stop);
    EXPECT_GT(left, 1500.0);
    EXPECT_LT(left, 3900.0);
  }
}

// The first shots are strong (a fifth of a second each, seen from 16 eyes) while the largest patch carries
// at least the strong power, the rest weak (0.05 s): the time left is the strong shots left at their cost
// and the others at the weak ones', not all of them at the last shots' rate (1 200 s here, against 316).
TEST(SolveEstimate, CountsTheStrongShotsLeftAtTheirCostAndTheRestAtTheWeakOnes) {
  const double stop = 0.01, strongCost = 0.2, weakCost = 0.05;
  auto unshot = [](double n) { return 0.5 * std::exp(-0.05 * std::sqrt(n + 1.0)); };
  const double strongPower = 2.0 * unshot(200.0);  // the largest patch holds twice the share, in W
  const double total = std::pow(std::log(0.5 / stop) / 0.05, 2.0) - 1.0;  // 6 118 shots
  auto truth = [&](int n) {
    const double strongLeft = std::max(200.0 - n, 0.0);
    return strongLeft * strongCost + (total - n - strongLeft) * weakCost;
  };
  SolveEstimate e(strongPower);
  double seconds = 0.0;
  for (int n = 1; n <= 400; ++n) {
    const double power = 2.0 * unshot(n - 1.0);
    const bool strong = power >= strongPower;
    seconds += strong ? strongCost : weakCost;
    e.addShot(strong, strong ? strongCost : weakCost, power, unshot(n));
    e.add({n, unshot(n), seconds});
    if (n == 100) {  // no weak shot yet: their cost guessed from the strong ones' (0.3x)
      EXPECT_NEAR(e.secondsLeft(stop), truth(n), 0.25 * truth(n)) << "after " << n << " shots";
    } else if (n == 400) {
      EXPECT_NEAR(e.secondsLeft(stop), truth(n), 0.05 * truth(n)) << "after " << n << " shots";
    }
  }
}

TEST(SolveEstimate, SaysNothingBeforeTwentyShotsOrWhileTheShareDoesNotFall) {
  SolveEstimate e;
  EXPECT_LT(e.shotsLeft(0.01), 0.0);
  e.add({5, 0.5, 1.0});
  e.add({20, 0.4, 2.0});
  EXPECT_LT(e.shotsLeft(0.01), 0.0);  // 15 shots
  e.add({30, 0.4, 3.0});
  e.add({40, 0.4, 4.0});
  EXPECT_LT(e.shotsLeft(0.01), 0.0);  // flat over the window
  e.add({50, 0.005, 5.0});
  EXPECT_EQ(e.shotsLeft(0.01), 0.0);  // past the stop
}

}  // namespace
}  // namespace cpgi
