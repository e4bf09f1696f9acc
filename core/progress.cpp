#include "core/progress.h"

#include <time.h>
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

double processCpuSeconds() {
  timespec t{};
  if (::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) != 0) return 0.0;
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
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
  if (settings_.tickSeconds > 0.0)
    ticker_ = std::thread([this] {
      std::unique_lock lock(mutex_);
      const auto every = std::chrono::duration<double>(settings_.tickSeconds);
      while (!wake_.wait_for(lock, every, [this] { return stopping_; })) {
        lock.unlock();
        tick();
        lock.lock();
      }
    });
}

ProgressPrinter::~ProgressPrinter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

std::string ProgressPrinter::line(const Progress& p, double stageSeconds, double sinceReport) {
  const double fraction = std::clamp(p.fraction, 0.0, 1.0);
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3.0f%%", 100.0 * fraction);
  std::string text = p.stage + " " + percent;
  if (!p.status.empty()) text += " " + p.status;
  if (fraction >= 1.0) return text;
  if (p.secondsLeft >= 0.0)
    text += ", " + formatDuration(std::max(p.secondsLeft - sinceReport, 0.0)) + " left";
  else if (!p.ownsTimeLeft && fraction >= 0.01 && stageSeconds >= 1.0)
    text += ", " + formatDuration(stageSeconds * (1.0 - fraction) / fraction) + " left";
  else if (stageSeconds >= 1.0)
    text += ", " + formatDuration(stageSeconds) + " so far";
  return text;
}

void ProgressPrinter::emit(double now) {
  const std::string text = line(last_, now - stageStart_, now - lastReportAt_);
  shown_ = text;
  if (settings_.live) {
    sink_("\r" + text + "\033[K");  // erase what a longer earlier line left
    openLine_ = last_.fraction < 1.0;
    if (!openLine_) sink_("\n");
  } else {
    sink_("progress: " + text + "\n");
    lastLine_ = now;
    stageShown_ = true;
  }
}

void ProgressPrinter::report(const Progress& p) {
  std::lock_guard lock(mutex_);
  const double now = clock_();
  // A new stage, or the same one started over (each cell's solve in a cells bake): time it afresh.
  if (!any_ || p.stage != last_.stage || p.fraction < last_.fraction - 0.25) {
    if (settings_.live && openLine_) sink_("\n");
    openLine_ = false;
    if (!any_ || p.stage != last_.stage) stageShown_ = false;
    stageStart_ = now;
  }
  last_ = p;
  any_ = true;
  lastReportAt_ = now;
  if (settings_.live) return emit(now);
  const bool firstDue =
      !stageShown_ && now - stageStart_ >= std::min(settings_.firstLineAfter, settings_.periodSeconds);
  if (firstDue || now - lastLine_ >= settings_.periodSeconds) emit(now);
}

void ProgressPrinter::tick() {
  std::lock_guard lock(mutex_);
  if (!any_ || last_.fraction >= 1.0) return;
  const double now = clock_();
  if (settings_.live) {  // redrawn only when its text changed (the time so far, the time left)
    if (openLine_ && line(last_, now - stageStart_, now - lastReportAt_) != shown_) emit(now);
    return;
  }
  const bool firstDue = !stageShown_ && now - stageStart_ >= settings_.firstLineAfter;
  if (firstDue || (stageShown_ && now - lastLine_ >= settings_.periodSeconds)) emit(now);
}

ProgressStage::ProgressStage(Context& ctx, std::string stage, const std::string& status)
    : ctx_(ctx), outer_(ctx.progressFn()) {
  if (!outer_) return;
  ctx.setProgress([outer = outer_, stage](const Progress& p) {
    Progress q;
    q.stage = stage;
    q.fraction = p.fraction;
    q.status = p.stage == stage ? p.status : p.status.empty() ? p.stage : p.stage + ": " + p.status;
    outer(q);
  });
  ctx.progress(stage, 0.0, status);
}

ProgressStage::~ProgressStage() {
  if (outer_) ctx_.setProgress(outer_);
}

Context::ProgressFn stderrProgress(bool quiet) {
  if (quiet) return {};
  ProgressPrinter::Settings settings;
  settings.live = ::isatty(STDERR_FILENO) != 0;
  settings.tickSeconds = 0.25;
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
