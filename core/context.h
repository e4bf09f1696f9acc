// What every stage receives besides its data (Recast's rcContext, OpenVDB's interrupter): warnings,
// named timers and progress. Stages never print; the CLI decides what the user sees.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"

namespace cpgi {

class Context {
 public:
  /// Called with (stage, fraction in [0,1], short status such as "shots 120, unshot 3.2%").
  using ProgressFn = std::function<void(const std::string&, double, const std::string&)>;

  /// Kept to one line of sane length whatever names a file smuggled into it (core/error.h).
  void warn(const std::string& message) { warnings_.push_back(printable(message, 2000)); }
  const std::vector<std::string>& warnings() const { return warnings_; }

  void setProgress(ProgressFn fn) { progress_ = std::move(fn); }
  void progress(const std::string& stage, double fraction, const std::string& status = {}) const {
    if (progress_) progress_(stage, fraction, status);
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
