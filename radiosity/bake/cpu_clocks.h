// The clocks a bake's CPU share is measured on (bake_limits.h, CpuShare): what BakeRun records at a bake's
// start, before its loading, so that the loading's own rate is the first share seen.
#pragma once

#include <chrono>
#include <functional>

namespace cpgi {

/// One reading of the clocks a CPU share is measured with.
struct CpuReading {
  std::chrono::steady_clock::time_point wall;
  double process = 0.0;  ///< CPU seconds of every thread of the process (user + system)
  double thread = -1.0;  ///< CPU seconds of the thread the clocks were made on (< 0: not known)
};

/// Reads the clocks; cpuClocks() reads the real ones, tests give fake ones.
using CpuClocks = std::function<CpuReading()>;

/// The process's CPU clock (CLOCK_PROCESS_CPUTIME_ID), the calling thread's (pthread_getcpuclockid: read
/// from any thread later) and steady_clock.
CpuClocks cpuClocks();

}  // namespace cpgi
