#pragma once
// A fixed set of threads that run one loop at a time over an index range,
// split into equal contiguous parts. The split depends only on the range and
// the worker count, so work whose result depends only on its own index gives
// the same bits however many workers run it.
#include <cstddef>
#include <functional>
#include <memory>

namespace mrcloth {

class WorkerPool {
 public:
  /// `workers`: how many parts a loop is split into, 1 .. kMostWorkers (the
  /// calling thread runs part 0; workers - 1 threads are started here).
  /// Throws ArgumentError outside that range, or when the system refuses a
  /// thread (those already started are stopped first).
  explicit WorkerPool(int workers);
  static constexpr int kMostWorkers = 1024;
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int workers() const { return workers_; }

  /// Runs body(part, begin, end) for part 0 .. workers() - 1, part k over
  /// [count * k / workers(), count * (k + 1) / workers()), and returns when
  /// all have finished. An exception thrown by a part is rethrown here (the
  /// lowest part's, when several throw). Not re-entrant: one loop at a time.
  void run(std::size_t count, const std::function<void(int part, std::size_t begin, std::size_t end)>& body);

 /// The threads' shared state (worker_pool.cpp).
  struct Shared;

 private:
  int workers_;
  std::unique_ptr<Shared> shared_;
};

/// Threads to use for `requested` (0: one per hardware thread, 1 to
/// WorkerPool::kMostWorkers).
int resolve_thread_count(int requested);

}  // namespace mrcloth
