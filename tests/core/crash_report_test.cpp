// A crash names itself and its stack on stderr, and the process still dies of its signal (the exit status
// a caller sees, 128 + signal, is unchanged).
#include <csignal>

#include <gtest/gtest.h>

#include "core/crash_report.h"

namespace cpgi {
namespace {

#if !defined(__SANITIZE_ADDRESS__)
void crashWith(int sig) {
  installCrashReport("cpgi-test");
  std::raise(sig);
}

TEST(CrashReport, ASegmentationFaultIsNamedWithItsStackAndStillKills) {
  EXPECT_EXIT(
      crashWith(SIGSEGV), testing::KilledBySignal(SIGSEGV),
      "cpgi-test: crashed with a segmentation fault \\(SIGSEGV\\): a bug in cpgi.*\n.*\\[0x[0-9a-f]+\\]");
}

TEST(CrashReport, AnAbortIsNamedAndStillAborts) {
  EXPECT_EXIT(crashWith(SIGABRT), testing::KilledBySignal(SIGABRT), "crashed with an abort \\(SIGABRT\\)");
}

// Deeper than any stack: 2³⁰ frames of 4 KiB. The use of `frame` after the call keeps it from being a loop.
int overflow(int depth) {
  volatile char frame[4096];
  frame[0] = char(depth);
  if (depth > (1 << 30)) return 0;
  return overflow(depth + 1) + frame[0];
}

TEST(CrashReport, AStackOverflowIsReportedOnTheHandlersOwnStack) {
  EXPECT_EXIT((installCrashReport("cpgi-test"), overflow(0)), testing::KilledBySignal(SIGSEGV),
              "crashed with a segmentation fault");
}
#endif

}  // namespace
}  // namespace cpgi
