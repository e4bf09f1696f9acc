#include "radiosity/gpu/solve_estimate.h"

#include <algorithm>
#include <cmath>

namespace cpgi {

namespace {
// Fewer shots than this since the first reflector shot say nothing about the decay (the house's first
// hundred shots: k from 0 to 1 and back).
constexpr int kMinShots = 20;
// The most the rate may be taken to slow: at k = 1 an early window's estimate runs away (the house after
// 143 shots: 1.7e6 s), and from 0.75 up the house's estimates were no better.
constexpr double kMostSlowing = 0.75;
}  // namespace

void SolveEstimate::add(const SolveSample& s) {
  if (!(s.unshot > 0.0) || (!samples_.empty() && s.shots <= samples_.back().shots)) return;
  samples_.push_back(s);
}

double SolveEstimate::logUnshotAt(double shots) const {
  auto next = std::lower_bound(samples_.begin(), samples_.end(), shots,
                               [](const SolveSample& s, double n) { return double(s.shots) < n; });
  if (next == samples_.begin()) return std::log(next->unshot);
  if (next == samples_.end()) return std::log(samples_.back().unshot);
  const SolveSample& a = *(next - 1);
  const double t = (shots - a.shots) / double(next->shots - a.shots);
  return std::log(a.unshot) * (1.0 - t) + std::log(next->unshot) * t;
}

double SolveEstimate::shotsLeft(double stop) const {
  if (samples_.empty() || !(stop > 0.0)) return -1.0;
  const SolveSample& last = samples_.back();
  const double first = samples_.front().shots, span = last.shots - first;
  if (span < kMinShots) return -1.0;
  if (last.unshot <= stop) return 0.0;
  // log(unshot) = L0 - c g(n) with g' = n^-k, n counted from one shot before the first reflector shot;
  // k from how the drop over the last half compares with the quarter before it.
  const double nq = span / 4.0 + 1.0, nh = span / 2.0 + 1.0, nm = span + 1.0;
  const double dropRecent = logUnshotAt(first + nh - 1.0) - std::log(last.unshot);
  const double dropBefore = logUnshotAt(first + nq - 1.0) - logUnshotAt(first + nh - 1.0);
  if (!(dropRecent > 0.0)) return -1.0;
  auto g = [](double n, double k) { return std::pow(n, 1.0 - k) / (1.0 - k); };
  auto ratio = [&](double k) { return (g(nh, k) - g(nq, k)) / (g(nm, k) - g(nh, k)); };
  const double measured = std::max(dropBefore, 0.0) / dropRecent;
  double lo = 0.0, hi = kMostSlowing;  // ratio grows with k: 0.5 at k = 0, about 1 at k = 1
  for (int i = 0; i < 40; ++i) (ratio((lo + hi) / 2.0) < measured ? lo : hi) = (lo + hi) / 2.0;
  const double k = (lo + hi) / 2.0;
  const double c = dropRecent / (g(nm, k) - g(nh, k));
  const double target = g(nm, k) + std::log(last.unshot / stop) / c;
  const double total = std::pow(target * (1.0 - k), 1.0 / (1.0 - k));
  return std::max(total - nm, 0.0);
}

double SolveEstimate::secondsLeft(double stop) const {
  const double shots = shotsLeft(stop);
  if (shots <= 0.0) return shots;
  const SolveSample& last = samples_.back();
  const double half = samples_.front().shots + (last.shots - samples_.front().shots) / 2.0;
  auto from = std::lower_bound(samples_.begin(), samples_.end(), half,
                               [](const SolveSample& s, double n) { return double(s.shots) < n; });
  if (from == samples_.end() || from->shots >= last.shots) from = samples_.end() - 2;
  const double perShot = (last.seconds - from->seconds) / double(last.shots - from->shots);
  return shots * std::max(perShot, 0.0);
}

}  // namespace cpgi
