#include "core/crash_report.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <initializer_list>

namespace cpgi {
namespace {

const char* gProgram = "cpgi";

// Only async-signal-safe calls below: write(2), no stdio, no allocation (backtrace() was primed at install
// so that its first call's loading of libgcc happens outside the handler).
void writeText(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= size_t(n);
  }
}

const char* signalName(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "a segmentation fault (SIGSEGV)";
    case SIGBUS:
      return "a bus error (SIGBUS)";
    case SIGFPE:
      return "an arithmetic fault (SIGFPE)";
    case SIGILL:
      return "an illegal instruction (SIGILL)";
    case SIGABRT:
      return "an abort (SIGABRT)";
    default:
      return "a fatal signal";
  }
}

void onFatalSignal(int sig) {
  writeText("\n");
  writeText(gProgram);
  writeText(": crashed with ");
  writeText(signalName(sig));
  writeText(": a bug in cpgi, not in the input; please report it with the command line and this stack:\n");
  void* frames[64];
  const int count = ::backtrace(frames, 64);
  ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
  // Die of the same signal (exit status 128 + sig, a core dump where enabled): SA_RESETHAND restored the
  // default action.
  ::raise(sig);
}

}  // namespace

void installCrashReport(const char* program) {
#if defined(__SANITIZE_ADDRESS__)
  (void)program;  // AddressSanitizer's own report of a crash says more
  return;
#endif
  gProgram = program;
  void* prime[1];
  ::backtrace(prime, 1);
  // The handler's own stack: a stack overflow has none left to run it on.
  static char altStack[64 * 1024];
  stack_t ss{};
  ss.ss_sp = altStack;
  ss.ss_size = sizeof altStack;
  ::sigaltstack(&ss, nullptr);
  struct sigaction action {};
  action.sa_handler = onFatalSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_ONSTACK | SA_RESETHAND | SA_NODEFER;
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(sig, &action, nullptr);
}

}  // namespace cpgi
