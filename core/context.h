// What every stage receives besides its data (Recast's rcContext, OpenVDB's interrupter): warnings,
// named timers and progress. Stages never print; the CLI decides what the user sees.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"

namespace cpgi {

/// One report of a long stage, as data: a printer formats it, a caller reads the numbers (no parsing of
/// text). The fields after `status` are set by the stages that know them and negative otherwise.
struct Progress {
  std::string stage;           ///< "solve", "atlas", "reference", ...
  double fraction = 0;         ///< of the stage, in [0, 1]
  std::string status;          ///< short text such as "shots 120, unshot 3.2%"
  int shots = -1;              ///< a solve: shots so far
  double unshot = -1;          ///< a solve: the unshot share the stop weighs (0.032 = 3.2 %)
  double secondsLeft = -1;     ///< the stage's own estimate of its time left (s), from a model of its work
  double cpuSecondsLeft = -1;  ///< the same estimate in the process's CPU seconds (what load does not skew)
  double shotsLeft = -1;       ///< a solve: the shots its estimate foresees before the stop
  /// The stage estimates its own time left (a solve: its fraction is not linear in time), so a printer
  /// must not extrapolate one from the fraction while secondsLeft is still unknown.
  bool ownsTimeLeft = false;
};

class Context {
 public:
  using ProgressFn = std::function<void(const Progress&)>;

  /// Kept to one line of sane length whatever names a file smuggled into it (core/error.h).
  void warn(const std::string& message) { warnings_.push_back(printable(message, 2000)); }
  const std::vector<std::string>& warnings() const { return warnings_; }

  void setProgress(ProgressFn fn) { progress_ = std::move(fn); }
  const ProgressFn& progressFn() const { return progress_; }
  void progress(const Progress& p) const {
    if (progress_) progress_(p);
  }
  void progress(const std::string& stage, double fraction, const std::string& status = {}) const {
    if (progress_) progress_(Progress{stage, fraction, status});
  }

  struct Timing {
    std::string stage;
    double seconds;
  };
  /// Stages in the order they finished; a stage timed twice appears twice.
  const std::vector<Timing>& timings() const { return timings_; }
  void addTiming(std::string stage, double seconds) { timings_.push_back({std::move(stage), seconds}); }
  double totalSeconds(const std::string& stage) const;

  /// Times a scope and records it in the context it was made from.
  class ScopedTimer {
   public:
    ScopedTimer(Context& ctx, std::string stage)
        : ctx_(ctx), stage_(std::move(stage)), start_(std::chrono::steady_clock::now()) {}
    ~ScopedTimer() { ctx_.addTiming(stage_, elapsed()); }
    double elapsed() const {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    ScopedTimer(const ScopedTimer&) = delete;
    ScopedTimer& operator=(const ScopedTimer&) = delete;

   private:
    Context& ctx_;
    std::string stage_;
    std::chrono::steady_clock::time_point start_;
  };
  ScopedTimer time(std::string stage) { return ScopedTimer(*this, std::move(stage)); }

 private:
  std::vector<std::string> warnings_;
  std::vector<Timing> timings_;
  ProgressFn progress_;
};

inline double Context::totalSeconds(const std::string& stage) const {
  double s = 0.0;
  for (const Timing& t : timings_)
    if (t.stage == stage) s += t.seconds;
  return s;
}

}  // namespace cpgi
