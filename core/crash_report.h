#pragma once
// A crash (a segmentation fault, an abort) prints one line naming the signal, then the call stack, on
// stderr before the process dies of the signal as it would have: a user's report, or a CI log of a crash
// that does not repeat, then says where it happened. Call once, early in main.

namespace cpgi {

/// Installs the handlers for SIGSEGV, SIGBUS, SIGFPE, SIGILL and SIGABRT, on a stack of their own (a
/// stack overflow is reported too). `program` names the process in the line ("cpgi").
void installCrashReport(const char* program);

}  // namespace cpgi
