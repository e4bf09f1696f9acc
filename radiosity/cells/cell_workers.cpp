#include "radiosity/cells/cell_workers.h"

#include "core/error.h"

namespace cpgi {

CellWorkers::CellWorkers(int jobs, ShotEngine& engine) : engine_(engine) {
  if (jobs < 1) throw InputError("jobs", "must be at least 1");
  for (int w = 1; w < jobs; ++w) threads_.emplace_back(&CellWorkers::workerLoop, this, size_t(w));
  std::exception_ptr failure;
  {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return ready_ == int(threads_.size()); });
    failure = startFailure_;
  }
  if (failure) {
    stopAll();
    std::rethrow_exception(failure);
  }
}

CellWorkers::~CellWorkers() {
  stopAll();
}

void CellWorkers::stopAll() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_)
    if (t.joinable()) t.join();
}

void CellWorkers::workerLoop(size_t) {
  std::unique_ptr<ShotEngine> engine;
  try {
    engine = engine_.forThisThread();
  } catch (...) {
    std::lock_guard lock(mutex_);
    if (!startFailure_) startFailure_ = std::current_exception();
    ++ready_;
    done_.notify_all();
    return;
  }
  unsigned seen = 0;
  {
    std::lock_guard lock(mutex_);
    ++ready_;
    seen = generation_;
    done_.notify_all();
  }
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) break;
      seen = generation_;
    }
    work(*engine);
  }
  // The engine's device objects go while its context is still current on this thread.
  engine.reset();
}

void CellWorkers::work(ShotEngine& engine) {
  for (;;) {
    size_t i = 0;
    const Task* task = nullptr;
    {
      std::lock_guard lock(mutex_);
      if (!task_ || next_ >= count_) return;
      i = next_++;
      task = task_;
    }
    try {
      (*task)(i, engine, contexts_[i]);
    } catch (...) {
      failures_[i] = std::current_exception();
    }
    std::lock_guard lock(mutex_);
    if (++finished_ == count_) done_.notify_all();
  }
}

void CellWorkers::run(size_t n, Context& ctx, const Task& task) {
  if (n == 0) return;
  if (threads_.empty()) {
    for (size_t i = 0; i < n; ++i) task(i, engine_, ctx);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    contexts_.assign(n, Context());
    failures_.assign(n, nullptr);
    task_ = &task;
    count_ = n, next_ = 0, finished_ = 0;
    ++generation_;
  }
  wake_.notify_all();
  work(engine_);
  {
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return finished_ == count_; });
    task_ = nullptr;
  }
  for (const Context& c : contexts_) {
    for (const Context::Timing& t : c.timings()) ctx.addTiming(t.stage, t.seconds);
    for (const std::string& w : c.warnings()) ctx.warn(w);
  }
  for (const std::exception_ptr& f : failures_)
    if (f) std::rethrow_exception(f);
}

}  // namespace cpgi
