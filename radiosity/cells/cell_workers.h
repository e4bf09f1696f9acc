// Runs the solves of one round of cells side by side (issue 5 item 4). Every worker thread beyond the
// caller's has a shot engine of its own (ShotEngine::forThisThread: for GL, a sibling context on the same
// EGL display with its own compiled programs, since a GL context is current on one thread at a time); the
// caller works too, on its own engine. Tasks share nothing on the GPU, and the caller combines their results
// in a fixed order afterwards, so any number of workers gives the serial run's numbers.
//
// On llvmpipe every context already rasterizes and dispatches on all cores, so on a 2-core machine the
// gain is only what one solve leaves idle (CPU-side setup, read-backs, small dispatches).
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/context.h"
#include "radiosity/solve/shot_engine.h"

namespace cpgi {

class CellWorkers {
 public:
  /// One task: index, the engine of this thread, a Context for its timings and warnings.
  using Task = std::function<void(size_t, ShotEngine&, Context&)>;

  /// `jobs` >= 1 tasks at once; jobs − 1 threads are started (each makes its engine at once). `engine` is
  /// the caller's, usable on the calling thread.
  CellWorkers(int jobs, ShotEngine& engine);
  ~CellWorkers();
  CellWorkers(const CellWorkers&) = delete;
  CellWorkers& operator=(const CellWorkers&) = delete;

  /// Runs task(i) for i in [0, n) and returns when all are done. With one job each runs on the calling
  /// thread with `ctx` itself; with more, each task gets a fresh Context whose timings and warnings are
  /// added to `ctx` in task order. Rethrows the first task's exception (by index).
  void run(size_t n, Context& ctx, const Task& task);

  int jobs() const { return int(threads_.size()) + 1; }

 private:
  void workerLoop(size_t worker);
  void stopAll();
  void work(ShotEngine& engine);

  ShotEngine& engine_;  // the caller's
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  // The current batch (guarded by mutex_).
  const Task* task_ = nullptr;
  size_t count_ = 0, next_ = 0, finished_ = 0;
  unsigned generation_ = 0;
  bool stop_ = false;
  int ready_ = 0;  // workers whose engine is made (or failed)
  std::exception_ptr startFailure_;
  std::vector<Context> contexts_;
  std::vector<std::exception_ptr> failures_;
};

}  // namespace cpgi
