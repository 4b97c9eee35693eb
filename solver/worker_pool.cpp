#include "worker_pool.h"

#include "mesh_ops/errors.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <string>
#include <thread>
#include <vector>

namespace mrcloth {

struct WorkerPool::Shared {
  std::mutex mutex;
  std::condition_variable start, done;
  std::vector<std::thread> threads;
  // The loop being run: each thread waits for a new generation, runs its
  // part and counts itself finished.
  const std::function<void(int, std::size_t, std::size_t)>* body = nullptr;
  std::size_t count = 0;
  unsigned long long generation = 0;
  int unfinished = 0;
  bool stopping = false;
  std::vector<std::exception_ptr> errors;  // per part
};

namespace {

std::pair<std::size_t, std::size_t> part_range(std::size_t count, int part, int parts) {
  const auto k = static_cast<std::size_t>(part), n = static_cast<std::size_t>(parts);
  return {count * k / n, count * (k + 1) / n};
}

}  // namespace

namespace {

/// Stops the pool's threads and joins them.
void stop_threads(WorkerPool::Shared& s) {
  {
    std::lock_guard<std::mutex> lock(s.mutex);
    s.stopping = true;
  }
  s.start.notify_all();
  for (std::thread& t : s.threads) t.join();
}

/// What the thread of `part` runs: each generation's part, until stopped.
void serve_part(WorkerPool::Shared& s, int part, int workers) {
  unsigned long long seen = 0;
  for (;;) {
    std::unique_lock<std::mutex> lock(s.mutex);
    s.start.wait(lock, [&] { return s.stopping || s.generation != seen; });
    if (s.stopping) return;
    seen = s.generation;
    const auto [begin, end] = part_range(s.count, part, workers);
    const auto* body = s.body;
    lock.unlock();
    try {
      (*body)(part, begin, end);
    } catch (...) {
      s.errors[static_cast<std::size_t>(part)] = std::current_exception();
    }
    lock.lock();
    if (--s.unfinished == 0) s.done.notify_one();
  }
}

}  // namespace

WorkerPool::WorkerPool(int workers) : workers_(workers), shared_(std::make_unique<Shared>()) {
  if (workers < 1 || workers > kMostWorkers)
    throw ArgumentError("WorkerPool: " + std::to_string(workers) + " workers; expected 1 to " +
                        std::to_string(kMostWorkers));
  Shared& s = *shared_;
  s.errors.resize(static_cast<std::size_t>(workers));
  s.threads.reserve(static_cast<std::size_t>(workers - 1));
  for (int part = 1; part < workers; ++part) {
    try {
      s.threads.emplace_back(serve_part, std::ref(s), part, workers);
    } catch (const std::system_error& error) {
      // The threads started stop first: a joinable thread destroyed with
      // the pool took the process down (a script asking for 1e9 threads).
      stop_threads(s);
      throw ArgumentError("WorkerPool: the system refused worker thread " + std::to_string(part) + " of " +
                          std::to_string(workers - 1) + " (" + error.what() + "); ask for fewer threads");
    }
  }
}

WorkerPool::~WorkerPool() { stop_threads(*shared_); }

void WorkerPool::run(std::size_t count, const std::function<void(int, std::size_t, std::size_t)>& body) {
  Shared& s = *shared_;
  std::fill(s.errors.begin(), s.errors.end(), nullptr);
  if (workers_ > 1) {
    {
      std::lock_guard<std::mutex> lock(s.mutex);
      s.body = &body;
      s.count = count;
      s.unfinished = workers_ - 1;
      ++s.generation;
    }
    s.start.notify_all();
  }
  const auto [begin, end] = part_range(count, 0, workers_);
  try {
    body(0, begin, end);
  } catch (...) {
    s.errors[0] = std::current_exception();
  }
  if (workers_ > 1) {
    std::unique_lock<std::mutex> lock(s.mutex);
    s.done.wait(lock, [&] { return s.unfinished == 0; });
  }
  for (const std::exception_ptr& error : s.errors)
    if (error) std::rethrow_exception(error);
}

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, WorkerPool::kMostWorkers);
}

}  // namespace mrcloth
