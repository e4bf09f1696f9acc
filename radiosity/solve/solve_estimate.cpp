#include "radiosity/solve/solve_estimate.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/progress.h"
#include "radiosity/solve/progressive_loop.h"

namespace cpgi {

namespace {
// Reflector shots before the model first runs: the light's landing shares are those of these shots'
// receivers (seed1's first estimate at 10 % of its solve comes after its 8th shot).
constexpr int kMinShots = 8;
// The share of the solve's time the model may take: it runs again once the solve has spent this many
// times its last run since.
constexpr double kModelEvery = 40.0;
// A stop that moved by less than this share of the one the model ran to does not run it again: the unshot
// stop moves a little every shot with the share of the light leaving the scene (progressive_loop.cpp), and
// running the model each time was as dear as the shots; a refused stop moves it by 30 % (kStopRecheck).
constexpr double kStopDrift = 0.05;
// Patch updates per run of the model (shots × patches): about a tenth of a second.
constexpr double kModelWork = 1e8;
// Before any weak shot, their seconds per eye against the strong ones': measured 1.43-1.59 on seed1-3 by
// rays (a weak shot looks from half the eyes of each region, while its coverage rays and the loop over
// every receiver are the same).
constexpr double kWeakEyeCostPrior = 1.5;
// How many recent shots the costs per eye are taken over.
constexpr size_t kStrongWindow = 64, kWeakWindow = 256;
constexpr size_t kMinWeakShots = 8;
// Shots of a strength and eye count before their own mean cost prices the model's shots of that kind
// (before: the strength's cost per eye times the eyes).
constexpr size_t kMinKindShots = 4;
// The cells' books as the model shoots: each cell's unshot power (its patches' sum, against the sum and the
// RGB power it had at the start) and its light, grown by what lands on its patches (a reflector's light
// grows by what it reflects, as its unshot power does).
class ModelCells {
 public:
  ModelCells(const ModelRoomStop& rooms, const std::vector<int>& index, const std::vector<double>& unshot,
             const std::vector<double>& landing)
      : rooms_(rooms), light_(rooms.now.light) {
    const size_t k = light_.size();
    start_.assign(k, 0.0), landing_.assign(k, 0.0);
    cellOf_.resize(index.size());
    for (size_t i = 0; i < index.size(); ++i) {
      const size_t p = size_t(index[i]);
      const int c = p < rooms.patchCell.size() ? rooms.patchCell[p] : -1;
      cellOf_[i] = c >= 0 && size_t(c) < k ? size_t(c) : k - 1;  // no cell: the last entry
      start_[cellOf_[i]] += unshot[i];
      landing_[cellOf_[i]] += landing[i];
    }
    sum_ = start_;
  }
  void shot(size_t shooter, double power, double back) {
    sum_[cellOf_[shooter]] -= power;
    for (size_t c = 0; c < sum_.size(); ++c) sum_[c] += back * landing_[c], light_[c] += back * landing_[c];
  }
  bool accepted() const {
    // Each cell's unshot power as the model foresees it, leaving from where it is now.
    CellLight now{rooms_.now.unshot, light_, rooms_.now.texelUnshot};
    for (size_t c = 0; c < sum_.size(); ++c) {
      const double u = std::max(sum_[c], 0.0);
      now.unshot[c] = start_[c] > 0.0 ? rooms_.now.unshot[c] * (u / start_[c]) : glm::dvec3(u / 3.0);
    }
    return rooms_.accepts(now);
  }

 private:
  const ModelRoomStop& rooms_;
  std::vector<size_t> cellOf_;                 // per patch taking part
  std::vector<double> start_, sum_, landing_;  // per cell
  std::vector<double> light_;
};

}  // namespace

ModelShots simulateShots(const PatchLight& light, double stop, double strongPower, double work,
                         const ModelRoomStop* rooms) {
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
  std::optional<ModelCells> cells;
  if (rooms && rooms->accepts && !rooms->now.light.empty() &&
      rooms->now.unshot.size() == rooms->now.light.size())
    cells.emplace(*rooms, index, u, w);
  const int shotsBefore = rooms ? rooms->shots : 0;
  int bound = rooms ? rooms->bound : 0;
  double stopAt = stop;
  size_t best = size_t(std::max_element(u.begin(), u.end()) - u.begin());
  std::vector<double> shares;  // after each shot, for the extrapolation
  const size_t most = size_t(std::max(work / double(u.size()), 2.0));
  for (;;) {
    // The loop's stop, as the loop asks it (progressive_loop.cpp).
    const int shots = shotsBefore + int(out.patches.size());
    if (bound > 0 && shots >= bound) {
      out.bounded = true;
      break;
    }
    if (share() <= stopAt) {
      if (!cells || cells->accepted()) break;
      ++out.refusals;
      stopAt = share() * kStopRecheck;
      if (bound == 0) bound = refusedStopBound(shots, rooms->receivers, rooms->texelShots);
    }
    if (out.patches.size() >= most) break;
    const double power = u[best];
    if (!(power > 0.0)) return out;
    out.patches.push_back(index[best]);
    out.strong.push_back(power >= strongPower ? 1 : 0);
    const double back = light.returned * power;
    u[best] = 0.0;
    unshot += back - power;
    reflected += back;
    if (cells) cells->shot(best, power, back);
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
  if (out.bounded || share() <= stopAt) return out;
  // Out of work: the rest at the rate of the last half of the model's shots, towards the stop it stands
  // at (a refusal past it is not foreseen), up to the bound.
  const size_t half = shares.size() / 2;
  const double rate = std::log(shares[half] / shares.back()) / double(shares.size() - 1 - half);
  if (!(rate > 0.0)) {
    out.reached = false;
    return out;
  }
  out.beyond = std::log(shares.back() / stopAt) / rate;
  if (bound > 0) out.beyond = std::min(out.beyond, double(bound - shotsBefore) - double(out.patches.size()));
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
  const size_t most = strong ? kStrongWindow : kWeakWindow;
  const double s = std::max(seconds, 0.0), e = double(std::max(eyes, 1));
  (strong ? strongCost_ : weakCost_).push(s, e, most);
  costByEyes_[{strong, std::max(eyes, 1)}].push(s, e, most);
  if (firstUnshot_.empty() || patch < 0 || size_t(patch) >= shotSince_.size()) return;
  shotSince_[size_t(patch)] += power;
  shotPowerSince_ += power;
}

bool SolveEstimate::wantsPatches(int shots, double stop, double seconds) const {
  if (firstUnshot_.empty()) return true;  // where the light is counted from
  if (reflectorShots_ < kMinShots) return false;
  if (!ran_ || std::abs(stop - modelStop_) > kStopDrift * modelStop_) return true;
  const bool overrun = modelReached_ && double(shots - modelShot_) >= double(modelShots_.size()) + beyond_;
  return overrun || seconds - modelSeconds_ >= kModelEvery * modelCost_;
}

ModelShots SolveEstimate::runModel(const LoopState& state, std::vector<double> unshot,
                                   const std::function<CellLight()>& cells) const {
  // Where the light shot since the first observe came back: each patch's unshot now, less what it had,
  // plus what it shot.
  PatchLight light;
  light.landing.resize(unshot.size());
  double back = 0.0;
  for (size_t p = 0; p < unshot.size(); ++p) {
    light.landing[p] = std::max(unshot[p] - firstUnshot_[p] + shotSince_[p], 0.0);
    back += light.landing[p];
  }
  if (!(back > 0.0)) return {};
  for (double& w : light.landing) w /= back;
  light.returned = std::min(back / shotPowerSince_, 0.999);
  light.unshot = std::move(unshot);
  light.reflected = state.reflected;
  light.emitted = state.emitted;
  if (!rooms_.accepts || !cells) return simulateShots(light, state.stop, strongPower_, kModelWork);
  const ModelRoomStop rooms{rooms_.patchCell, cells(),          rooms_.accepts,   state.shots,
                            state.bound,      rooms_.receivers, rooms_.texelShots};
  return simulateShots(light, state.stop, strongPower_, kModelWork, &rooms);
}

void SolveEstimate::observe(LoopState state, const std::function<int(int, bool)>& eyes,
                            const std::function<CellLight()>& cells) {
  if (firstUnshot_.empty()) {
    shotSince_.assign(state.unshot.size(), 0.0);
    firstUnshot_ = std::move(state.unshot);
    return;
  }
  if (!wantsPatches(state.shots, state.stop, state.seconds) || state.unshot.size() != firstUnshot_.size() ||
      !(shotPowerSince_ > 0.0))
    return;
  const double cpu = processCpuSeconds();
  std::vector<double> unshot = std::move(state.unshot);
  const ModelShots model = runModel(state, std::move(unshot), cells);
  if (model.patches.empty() && !model.reached) return;
  modelShots_.resize(model.patches.size());
  for (size_t k = 0; k < model.patches.size(); ++k) {
    const bool strong = model.strong[k] != 0;
    modelShots_[k] = {strong, std::max(eyes(model.patches[k], strong), 1)};
  }
  // The extrapolated shots are weak, as the model's last weak shots.
  beyond_ = model.beyond;
  beyondShots_.clear();
  for (size_t k = modelShots_.size(); k-- > 0 && beyondShots_.size() < 64;)
    if (!modelShots_[k].first) beyondShots_.push_back(modelShots_[k]);
  ran_ = true;
  modelReached_ = model.reached;
  modelShot_ = state.shots;
  modelStop_ = state.stop;
  modelSeconds_ = state.seconds;
  modelCost_ = processCpuSeconds() - cpu;
}

double SolveEstimate::shotsLeft(int shots) const {
  if (!ran_ || !modelReached_) return -1.0;
  const double foreseen = double(modelShots_.size()) + beyond_;
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

double SolveEstimate::shotSeconds(bool strong, int eyes) const {
  const auto kind = costByEyes_.find({strong, eyes});
  if (kind != costByEyes_.end() && kind->second.seconds.size() >= kMinKindShots)
    return kind->second.secondsSum / double(kind->second.seconds.size());
  return secondsPerEye(strong) * double(eyes);
}

double SolveEstimate::secondsLeft(int shots) const {
  const double left = shotsLeft(shots);
  if (left <= 0.0) return left;
  const size_t done = size_t(std::max(shots - modelShot_, 0));
  double seconds = 0.0;
  // Each kind's price once: the shots to come are many, their kinds few.
  std::map<ShotKind, double> price;
  auto priced = [&](const ShotKind& k) {
    const auto [at, added] = price.try_emplace(k, 0.0);
    if (added) at->second = shotSeconds(k.first, k.second);
    return at->second;
  };
  for (size_t k = done; k < modelShots_.size(); ++k) seconds += priced(modelShots_[k]);
  const double beyond =
      std::max(beyond_ - double(done > modelShots_.size() ? done - modelShots_.size() : 0), 0.0);
  if (beyond > 0.0) {
    double each = 0.0;
    for (const ShotKind& k : beyondShots_) each += priced(k);
    seconds += beyond * (beyondShots_.empty() ? secondsPerEye(false) : each / double(beyondShots_.size()));
  }
  return seconds;
}

}  // namespace cpgi
