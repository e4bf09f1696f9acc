#include "radiosity/solve/solve_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/progress.h"

namespace cpgi {

namespace {
// Reflector shots before the model first runs: the light's landing shares are those of these shots'
// receivers (seed1's first estimate at 10 % of its solve comes after its 8th shot).
constexpr int kMinShots = 8;
// The share of the solve's time the model may take: it runs again once the solve has spent this many
// times its last run since.
constexpr double kModelEvery = 40.0;
// Patch updates per run of the model (shots × patches): about a tenth of a second.
constexpr double kModelWork = 1e8;
// Before any weak shot, their seconds per eye against the strong ones': measured 1.43-1.59 on seed1-3 by
// rays (a weak shot looks from half the eyes of each region, while its coverage rays and the loop over
// every receiver are the same).
constexpr double kWeakEyeCostPrior = 1.5;
// How many recent shots the costs per eye are taken over.
constexpr size_t kStrongWindow = 64, kWeakWindow = 256;
constexpr size_t kMinWeakShots = 8;
}  // namespace

ModelShots simulateShots(const PatchLight& light, double stop, double strongPower, double work) {
  ModelShots out;
  // Only the patches that hold light or get some take part.
  std::vector<int> index;
  std::vector<double> u, w;
  for (size_t p = 0; p < light.unshot.size(); ++p)
    if (light.unshot[p] > 0.0 || (p < light.landing.size() && light.landing[p] > 0.0)) {
      index.push_back(int(p));
      u.push_back(std::max(light.unshot[p], 0.0));
      w.push_back(p < light.landing.size() ? std::max(light.landing[p], 0.0) : 0.0);
    }
  double unshot = 0.0, reflected = light.reflected;
  for (double x : u) unshot += x;
  auto share = [&] {
    const double scale = std::min(light.emitted, reflected);
    return scale > 0.0 ? unshot / scale : 1.0;
  };
  if (u.empty() || !(stop > 0.0)) return out;
  size_t best = size_t(std::max_element(u.begin(), u.end()) - u.begin());
  std::vector<double> shares;  // after each shot, for the extrapolation
  const size_t most = size_t(std::max(work / double(u.size()), 2.0));
  while (share() > stop) {
    if (out.patches.size() >= most) break;
    const double power = u[best];
    if (!(power > 0.0)) return out;
    out.patches.push_back(index[best]);
    out.strong.push_back(power >= strongPower ? 1 : 0);
    const double back = light.returned * power;
    u[best] = 0.0;
    unshot += back - power;
    reflected += back;
    double top = -1.0;
    size_t next = 0;
    for (size_t i = 0; i < u.size(); ++i) {
      u[i] += back * w[i];
      if (u[i] > top) top = u[i], next = i;
    }
    best = next;
    shares.push_back(share());
  }
  out.reached = true;
  if (share() <= stop) return out;
  // Out of work: the rest at the rate of the last half of the model's shots.
  const size_t half = shares.size() / 2;
  const double rate = std::log(shares[half] / shares.back()) / double(shares.size() - 1 - half);
  if (!(rate > 0.0)) {
    out.reached = false;
    return out;
  }
  out.beyond = std::log(shares.back() / stop) / rate;
  return out;
}

void SolveEstimate::Window::push(double s, double e, size_t most) {
  seconds.push_back(s), eyes.push_back(e);
  secondsSum += s, eyesSum += e;
  if (seconds.size() > most) {
    secondsSum -= seconds.front(), eyesSum -= eyes.front();
    seconds.pop_front(), eyes.pop_front();
  }
}

void SolveEstimate::addShot(int patch, bool strong, int eyes, double power, double seconds) {
  ++reflectorShots_;
  (strong ? strongCost_ : weakCost_)
      .push(std::max(seconds, 0.0), double(std::max(eyes, 1)), strong ? kStrongWindow : kWeakWindow);
  if (firstUnshot_.empty() || patch < 0 || size_t(patch) >= shotSince_.size()) return;
  shotSince_[size_t(patch)] += power;
  shotPowerSince_ += power;
}

bool SolveEstimate::wantsPatches(int shots, double stop, double seconds) const {
  if (firstUnshot_.empty()) return true;  // where the light is counted from
  if (reflectorShots_ < kMinShots) return false;
  if (!ran_ || stop != modelStop_) return true;
  const bool overrun =
      modelReached_ && double(shots - modelShot_) >= double(strongEyesAfter_.size() - 1) + beyond_;
  return overrun || seconds - modelSeconds_ >= kModelEvery * modelCost_;
}

void SolveEstimate::observe(int shots, std::vector<double> unshot, double reflected, double emitted,
                            double stop, double seconds, const std::function<int(int, bool)>& eyes) {
  if (firstUnshot_.empty()) {
    shotSince_.assign(unshot.size(), 0.0);
    firstUnshot_ = std::move(unshot);
    return;
  }
  if (!wantsPatches(shots, stop, seconds) || unshot.size() != firstUnshot_.size() || !(shotPowerSince_ > 0.0))
    return;
  const double cpu = processCpuSeconds();
  // Where the light shot since the first observe came back: each patch's unshot now, less what it had,
  // plus what it shot.
  PatchLight light;
  light.landing.resize(unshot.size());
  double back = 0.0;
  for (size_t p = 0; p < unshot.size(); ++p) {
    light.landing[p] = std::max(unshot[p] - firstUnshot_[p] + shotSince_[p], 0.0);
    back += light.landing[p];
  }
  if (!(back > 0.0)) return;
  for (double& w : light.landing) w /= back;
  light.returned = std::min(back / shotPowerSince_, 0.999);
  light.unshot = std::move(unshot);
  light.reflected = reflected;
  light.emitted = emitted;
  const ModelShots model = simulateShots(light, stop, strongPower_, kModelWork);

  const size_t n = model.patches.size();
  strongEyesAfter_.assign(n + 1, 0.0);
  weakEyesAfter_.assign(n + 1, 0.0);
  for (size_t k = n; k-- > 0;) {
    const bool strong = model.strong[k] != 0;
    const double e = double(std::max(eyes(model.patches[k], strong), 1));
    strongEyesAfter_[k] = strongEyesAfter_[k + 1] + (strong ? e : 0.0);
    weakEyesAfter_[k] = weakEyesAfter_[k + 1] + (strong ? 0.0 : e);
  }
  // The extrapolated shots are weak, with the eyes of the model's last weak shots.
  beyond_ = model.beyond;
  double lastEyes = 0.0, lastCount = 0.0;
  for (size_t k = n; k-- > 0 && lastCount < 64.0;)
    if (!model.strong[k]) lastEyes += double(std::max(eyes(model.patches[k], false), 1)), lastCount += 1.0;
  beyondEyes_ = lastCount > 0.0 ? lastEyes / lastCount : 1.0;
  ran_ = true;
  modelReached_ = model.reached;
  modelShot_ = shots;
  modelStop_ = stop;
  modelSeconds_ = seconds;
  modelCost_ = processCpuSeconds() - cpu;
}

double SolveEstimate::shotsLeft(int shots) const {
  if (!ran_ || !modelReached_) return -1.0;
  const double foreseen = double(strongEyesAfter_.size() - 1) + beyond_;
  return std::max(foreseen - double(shots - modelShot_), 0.0);
}

double SolveEstimate::secondsPerEye(bool strong) const {
  const Window& own = strong ? strongCost_ : weakCost_;
  const Window& other = strong ? weakCost_ : strongCost_;
  const size_t enough = strong ? 1 : kMinWeakShots;
  if (own.seconds.size() >= enough && own.eyesSum > 0.0) return own.secondsSum / own.eyesSum;
  if (other.eyesSum > 0.0) {
    const double perEye = other.secondsSum / other.eyesSum;
    return strong ? perEye / kWeakEyeCostPrior : perEye * kWeakEyeCostPrior;
  }
  return own.eyesSum > 0.0 ? own.secondsSum / own.eyesSum : 0.0;
}

double SolveEstimate::secondsLeft(int shots) const {
  const double left = shotsLeft(shots);
  if (left <= 0.0) return left;
  const size_t n = strongEyesAfter_.size() - 1;
  const size_t done = size_t(std::max(shots - modelShot_, 0));
  double strongEyes = 0.0, weakEyes = 0.0, beyond = beyond_;
  if (done <= n) {
    strongEyes = strongEyesAfter_[done], weakEyes = weakEyesAfter_[done];
  } else {
    beyond = std::max(beyond_ - double(done - n), 0.0);
  }
  weakEyes += beyond * beyondEyes_;
  return strongEyes * secondsPerEye(true) + weakEyes * secondsPerEye(false);
}

}  // namespace cpgi
