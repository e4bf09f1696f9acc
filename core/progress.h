// What a person sees of a long run: Context::progress calls (stage, fraction, status) turned into text
// with the time left. On a terminal, one live line rewritten in place; in a pipe or a log, a plain line
// every `periodSeconds` (none at all for a run shorter than that), so a log of a long bake shows that it
// moves and when it will end.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <string>

#include "core/context.h"

namespace cpgi {

/// "42 s", "3 min 20 s", "1 h 05 min"; negative → "".
std::string formatDuration(double seconds);

class ProgressPrinter {
 public:
  struct Settings {
    bool live = false;            ///< a terminal: "\r" + the line, a newline when a stage ends
    double periodSeconds = 10.0;  ///< plain lines: at least this long apart (0: one per call)
  };
  using Clock = std::function<double()>;                 ///< seconds, monotonic
  using Sink = std::function<void(const std::string&)>;  ///< receives text as is ("\r", "\n" included)

  /// `clock` defaults to std::chrono::steady_clock.
  ProgressPrinter(Settings settings, Sink sink, Clock clock = {});

  /// Thread-safe, so a stage may report from worker threads.
  void report(const Progress& p);

  /// The text of one report without its "\r" or newline: "solve  42% shots 120, unshot 3.2%, 1 min left".
  /// The time left is the stage's own estimate (Progress::secondsLeft) when it gives one, else
  /// extrapolated from the stage's elapsed time and fraction; none before 1 % or 1 s.
  static std::string line(const Progress& p, double stageSeconds);

 private:
  Settings settings_;
  Sink sink_;
  Clock clock_;
  std::mutex mutex_;
  std::string stage_;        ///< the stage being reported
  double stageStart_ = 0.0;  ///< when it started (or restarted: its fraction fell back)
  double lastFraction_ = 0.0;
  double lastLine_ = 0.0;  ///< plain mode: when the last line went out (the run's start at first)
  bool openLine_ = false;  ///< live mode: a line is shown without its newline
};

/// The CLI's printer on stderr: live on a terminal, else plain lines every CPGI_PROGRESS_SECONDS seconds
/// (10 when unset or not a number ≥ 0). Nothing when `quiet`.
Context::ProgressFn stderrProgress(bool quiet);

}  // namespace cpgi
