#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace cpgi {

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return {};
  const long s = std::lround(seconds);
  char buf[48];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%ld s", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  return buf;
}

ProgressPrinter::ProgressPrinter(Settings settings, Sink sink, Clock clock)
    : settings_(settings), sink_(std::move(sink)), clock_(std::move(clock)) {
  if (!clock_) {
    const auto start = std::chrono::steady_clock::now();
    clock_ = [start] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
  }
  lastLine_ = clock_();
}

std::string ProgressPrinter::line(const Progress& p, double stageSeconds) {
  const double fraction = std::clamp(p.fraction, 0.0, 1.0);
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3.0f%%", 100.0 * fraction);
  std::string text = p.stage + " " + percent;
  if (!p.status.empty()) text += " " + p.status;
  if (fraction < 1.0 && p.secondsLeft >= 0.0)
    text += ", " + formatDuration(p.secondsLeft) + " left";
  else if (fraction >= 0.01 && fraction < 1.0 && stageSeconds >= 1.0)
    text += ", " + formatDuration(stageSeconds * (1.0 - fraction) / fraction) + " left";
  return text;
}

void ProgressPrinter::report(const Progress& p) {
  const std::string& stage = p.stage;
  const double fraction = p.fraction;
  std::lock_guard lock(mutex_);
  const double now = clock_();
  // A new stage, or the same one started over (each cell's solve in a cells bake): time it afresh.
  if (stage != stage_ || fraction < lastFraction_ - 0.25) {
    if (settings_.live && openLine_) sink_("\n");
    openLine_ = false;
    stage_ = stage;
    stageStart_ = now;
  }
  lastFraction_ = fraction;
  const std::string text = line(p, now - stageStart_);
  if (settings_.live) {
    sink_("\r" + text + "\033[K");  // erase what a longer earlier line left
    openLine_ = fraction < 1.0;
    if (!openLine_) sink_("\n");
  } else if (now - lastLine_ >= settings_.periodSeconds) {
    sink_("progress: " + text + "\n");
    lastLine_ = now;
  }
}

Context::ProgressFn stderrProgress(bool quiet) {
  if (quiet) return {};
  ProgressPrinter::Settings settings;
  settings.live = ::isatty(STDERR_FILENO) != 0;
  if (const char* period = std::getenv("CPGI_PROGRESS_SECONDS")) {
    char* end = nullptr;
    const double value = std::strtod(period, &end);
    if (end != period && *end == '\0' && value >= 0.0 && std::isfinite(value)) settings.periodSeconds = value;
  }
  auto printer = std::make_shared<ProgressPrinter>(settings, [](const std::string& text) {
    std::fputs(text.c_str(), stderr);
    std::fflush(stderr);
  });
  return [printer](const Progress& p) { printer->report(p); };
}

}  // namespace cpgi
