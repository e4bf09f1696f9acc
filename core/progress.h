// What a person sees of a long run: Context::progress calls (stage, fraction, status) turned into text
// with the time left. On a terminal, one live line rewritten in place; in a pipe or a log, plain lines:
// a stage's first once it has lasted a second (a shorter one prints nothing), then one every
// `periodSeconds` while it runs, so a log of a long bake shows every stage, that it moves, and when it
// will end. A stage that reports nothing for a while (the loader, a set-up) is shown again by the ticker
// with the time it has taken so far.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "core/context.h"

namespace cpgi {

/// "42 s", "3 min 20 s", "1 h 05 min"; negative → "".
std::string formatDuration(double seconds);

/// CPU seconds the process has used, over all its threads (what a loaded machine does not stretch).
double processCpuSeconds();

class ProgressPrinter {
 public:
  struct Settings {
    bool live = false;            ///< a terminal: "\r" + the line, a newline when a stage ends
    double periodSeconds = 5.0;   ///< plain lines: at least this often while a stage runs (0: every call)
    double firstLineAfter = 1.0;  ///< plain lines: a new stage's first once it has lasted this long
    double tickSeconds = 0.0;     ///< > 0: a thread calls tick() this often (the CLI's printer)
  };
  using Clock = std::function<double()>;                 ///< seconds, monotonic
  using Sink = std::function<void(const std::string&)>;  ///< receives text as is ("\r", "\n" included)

  /// `clock` defaults to std::chrono::steady_clock.
  ProgressPrinter(Settings settings, Sink sink, Clock clock = {});
  ~ProgressPrinter();
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  /// Thread-safe, so a stage may report from worker threads.
  void report(const Progress& p);
  /// Between reports: a plain line when one is due (a stage's first second, the period), the live line
  /// redrawn with its time. A finished stage (fraction 1) is not repeated.
  void tick();

  /// The text of one report without its "\r" or newline: "solve  42% shots 120, unshot 3.2%, 1 min left".
  /// The time left is the stage's own estimate (Progress::secondsLeft, less the `sinceReport` seconds
  /// since it was made) when it gives one, else extrapolated from the stage's elapsed time and fraction
  /// (none before 1 % or 1 s, nor for a stage that estimates its own: Progress::ownsTimeLeft); without
  /// one, the time the stage has taken so far once that is a second.
  static std::string line(const Progress& p, double stageSeconds, double sinceReport = 0.0);

 private:
  void emit(double now);  // the last report as a line (mutex_ held)

  Settings settings_;
  Sink sink_;
  Clock clock_;
  std::mutex mutex_;
  Progress last_;              ///< the last report
  bool any_ = false;           ///< a report came
  double lastReportAt_ = 0.0;  ///< when it came
  double stageStart_ = 0.0;    ///< when its stage started (or restarted: its fraction fell back)
  bool stageShown_ = false;    ///< plain mode: the stage has had a line
  double lastLine_ = 0.0;      ///< plain mode: when the last line went out
  bool openLine_ = false;      ///< live mode: a line is shown without its newline
  std::string shown_;          ///< the text of the last line
  // The ticker thread (Settings::tickSeconds > 0).
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread ticker_;
};

/// Within its life, every report to `ctx` goes out as stage `stage` with the inner stage's name leading
/// its status ("auto density  40% solve: shots 2, unshot 60%"), and without a solve's shots, unshot and
/// time left, which are the inner pass's and not the stage's: a pre-pass's solve shown as what it is,
/// never as "solve 0% → 100%" before the bake's own solve. Reports `stage` at 0 when made.
class ProgressStage {
 public:
  ProgressStage(Context& ctx, std::string stage, const std::string& status = {});
  ~ProgressStage();
  ProgressStage(const ProgressStage&) = delete;
  ProgressStage& operator=(const ProgressStage&) = delete;

 private:
  Context& ctx_;
  Context::ProgressFn outer_;
};

/// The CLI's printer on stderr: live on a terminal, else plain lines (a stage's first after a second, then
/// every CPGI_PROGRESS_SECONDS seconds: 5 when unset or not a number ≥ 0; 0 prints every report).
/// Nothing when `quiet`.
Context::ProgressFn stderrProgress(bool quiet);

}  // namespace cpgi
