#include "radiosity/solve/solve_estimate.h"

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
// k while the last half of the shots holds strong ones. Fitted freely there, k swung from 0 to 0.75
// between windows a few shots apart (house-spiral: 10x the shots left after 140, 0.2x after 22); held
// fixed at 0.5 the seven bakes measured stayed within 0.4-2.3x, and [0.45, 0.6] lets it follow a little.
constexpr double kLeastSlowingStrong = 0.45, kMostSlowingStrong = 0.6;
// Before any weak shot: its cost against a strong one's. Measured 0.22-0.39 (house-furnished 0.22,
// house-spiral 0.26, seed1 and seed3 0.34, openings 0.35, office-small 0.36, seed3 at 64² per quad 0.39).
constexpr double kWeakCostPrior = 0.3;
// How many recent shots the costs and the power per unshot share are taken over.
constexpr size_t kStrongWindow = 64, kWeakWindow = 256, kPowerWindow = 16;
constexpr int kMinWeakShots = 8;

void push(std::deque<double>& window, double& sum, double value, size_t most) {
  window.push_back(value);
  sum += value;
  if (window.size() > most) sum -= window.front(), window.pop_front();
}
}  // namespace

void SolveEstimate::add(const SolveSample& s) {
  if (!(s.unshot > 0.0) || (!samples_.empty() && s.shots <= samples_.back().at.shots)) return;
  samples_.push_back({s, strongShots_});
}

void SolveEstimate::addShot(bool strong, double seconds, double power, double unshot) {
  seconds = std::max(seconds, 0.0);
  if (strong) {
    ++strongShots_;
    push(strongSeconds_, strongSum_, seconds, kStrongWindow);
  } else {
    push(weakSeconds_, weakSum_, seconds, kWeakWindow);
  }
  double unused = 0.0;
  if (unshot > 0.0 && power > 0.0) push(powerPerShare_, unused, power / unshot, kPowerWindow);
}

double SolveEstimate::logUnshotAt(double shots) const {
  auto next = std::lower_bound(samples_.begin(), samples_.end(), shots,
                               [](const Sample& s, double n) { return double(s.at.shots) < n; });
  if (next == samples_.begin()) return std::log(next->at.unshot);
  if (next == samples_.end()) return std::log(samples_.back().at.unshot);
  const SolveSample& a = (next - 1)->at;
  const double t = (shots - a.shots) / double(next->at.shots - a.shots);
  return std::log(a.unshot) * (1.0 - t) + std::log(next->at.unshot) * t;
}

double SolveEstimate::shotsLeft(double stop) const {
  if (samples_.empty()) return -1.0;
  // Strong shots in the last half of the samples: the last sample's count against the one at the half.
  const double half =
      samples_.front().at.shots + (samples_.back().at.shots - samples_.front().at.shots) / 2.0;
  auto mid = std::lower_bound(samples_.begin(), samples_.end(), half,
                              [](const Sample& s, double n) { return double(s.at.shots) < n; });
  const bool strongRecently = mid != samples_.end() && samples_.back().strongShots > mid->strongShots;
  return strongRecently ? shotsLeft(stop, kLeastSlowingStrong, kMostSlowingStrong)
                        : shotsLeft(stop, 0.0, kMostSlowing);
}

double SolveEstimate::shotsLeft(double stop, double leastK, double mostK) const {
  if (samples_.empty() || !(stop > 0.0)) return -1.0;
  const SolveSample& last = samples_.back().at;
  const double first = samples_.front().at.shots, span = last.shots - first;
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
  double lo = leastK, hi = mostK;  // ratio grows with k: 0.5 at k = 0, about 1 at k = 1
  for (int i = 0; i < 40; ++i) (ratio((lo + hi) / 2.0) < measured ? lo : hi) = (lo + hi) / 2.0;
  const double k = (lo + hi) / 2.0;
  const double c = dropRecent / (g(nm, k) - g(nh, k));
  const double target = g(nm, k) + std::log(last.unshot / stop) / c;
  const double total = std::pow(target * (1.0 - k), 1.0 / (1.0 - k));
  return std::max(total - nm, 0.0);
}

// The largest patch holds a share of the unshot power that falls as the light spreads; at the recent
// shots' share (their median power per unshot share), shots stay strong until the unshot share is
// strongPower_ / that. Later shots hold less of it, so this counts strong shots generously.
double SolveEstimate::strongShotsLeft(double stop, double total) const {
  if (!(strongPower_ > 0.0) || powerPerShare_.empty()) return 0.0;
  std::vector<double> recent(powerPerShare_.begin(), powerPerShare_.end());
  std::nth_element(recent.begin(), recent.begin() + recent.size() / 2, recent.end());
  const double strongUntil = strongPower_ / recent[recent.size() / 2];
  if (strongUntil >= samples_.back().at.unshot) return 0.0;
  if (strongUntil <= stop) return total;
  return std::clamp(shotsLeft(strongUntil), 0.0, total);
}

double SolveEstimate::secondsLeft(double stop) const {
  const double shots = shotsLeft(stop);
  if (shots <= 0.0) return shots;
  if (strongSeconds_.empty() && weakSeconds_.empty()) {  // no shots' costs: the samples' rate
    const SolveSample& last = samples_.back().at;
    const double half = samples_.front().at.shots + (last.shots - samples_.front().at.shots) / 2.0;
    auto from = std::lower_bound(samples_.begin(), samples_.end(), half,
                                 [](const Sample& s, double n) { return double(s.at.shots) < n; });
    if (from == samples_.end() || from->at.shots >= last.shots) from = samples_.end() - 2;
    const double perShot = (last.seconds - from->at.seconds) / double(last.shots - from->at.shots);
    return shots * std::max(perShot, 0.0);
  }
  const double weakCost =
      weakSeconds_.size() >= size_t(kMinWeakShots) || strongSeconds_.empty()
          ? weakSum_ / double(weakSeconds_.size())
          : kWeakCostPrior * strongSum_ / double(std::max<size_t>(strongSeconds_.size(), 1));
  const double strongCost = strongSeconds_.empty() ? weakCost : strongSum_ / double(strongSeconds_.size());
  const double strong = strongShotsLeft(stop, shots);
  return strong * strongCost + (shots - strong) * weakCost;
}

}  // namespace cpgi
