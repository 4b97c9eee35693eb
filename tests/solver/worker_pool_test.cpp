// The worker pool: parts cover the range exactly once, split as stated,
// whatever the worker count; errors come back to the caller; and it can be
// used loop after loop.
#include "mesh_ops/errors.h"
#include "solver/worker_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/resource.h>

namespace mrcloth {
namespace {

TEST(WorkerPool, PartsCoverTheRangeOnceInEqualContiguousPieces) {
  for (int workers = 1; workers <= 4; ++workers) {
    WorkerPool pool(workers);
    for (std::size_t count : {0u, 1u, 2u, 3u, 7u, 64u, 1001u}) {
      std::vector<int> hits(count, 0);
      std::vector<std::pair<std::size_t, std::size_t>> ranges(static_cast<std::size_t>(workers), {9999, 9999});
      pool.run(count, [&](int part, std::size_t begin, std::size_t end) {
        ranges[static_cast<std::size_t>(part)] = {begin, end};
        for (std::size_t i = begin; i < end; ++i) ++hits[i];  // parts are disjoint: no two write one element
      });
      for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(hits[i], 1) << workers << " workers, count " << count;
      for (int part = 0; part < workers; ++part) {
        const auto k = static_cast<std::size_t>(part), n = static_cast<std::size_t>(workers);
        EXPECT_EQ(ranges[k].first, count * k / n);
        EXPECT_EQ(ranges[k].second, count * (k + 1) / n);
      }
    }
  }
}

TEST(WorkerPool, PartsRunOnOtherThreadsAndTheCallerRunsPartZero) {
  WorkerPool pool(3);
  std::vector<std::thread::id> who(3);
  pool.run(30, [&](int part, std::size_t, std::size_t) { who[static_cast<std::size_t>(part)] = std::this_thread::get_id(); });
  EXPECT_EQ(who[0], std::this_thread::get_id());
  EXPECT_NE(who[1], std::this_thread::get_id());
  EXPECT_NE(who[2], std::this_thread::get_id());
  EXPECT_NE(who[1], who[2]);
}

TEST(WorkerPool, RunsManyLoopsAndSums) {
  WorkerPool pool(2);
  std::atomic<long> total{0};
  for (int loop = 0; loop < 2000; ++loop)
    pool.run(100, [&](int, std::size_t begin, std::size_t end) {
      long sum = 0;
      for (std::size_t i = begin; i < end; ++i) sum += static_cast<long>(i);
      total += sum;
    });
  EXPECT_EQ(total.load(), 2000L * 4950L);
}

TEST(WorkerPool, AnErrorInAPartReachesTheCaller) {
  WorkerPool pool(3);
  EXPECT_THROW(pool.run(9, [](int part, std::size_t, std::size_t) {
                 if (part == 2) throw std::runtime_error("part 2 failed");
               }),
               std::runtime_error);
  // The lowest failing part's error, and the pool still works afterwards.
  try {
    pool.run(9, [](int part, std::size_t, std::size_t) {
      if (part >= 1) throw std::runtime_error("part " + std::to_string(part));
    });
    FAIL() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "part 1");
  }
  int ran = 0;
  pool.run(3, [&](int part, std::size_t, std::size_t) {
    if (part == 0) ran = 1;
  });
  EXPECT_EQ(ran, 1);
}

// And more than kMostWorkers: a script asking for a billion threads made
// the system refuse one partway, and the threads already started, destroyed
// joinable, took the host down.
TEST(WorkerPool, RefusesFewerThanOneWorkerOrMoreThanItsMost) {
  EXPECT_THROW(WorkerPool(0), ArgumentError);
  EXPECT_THROW(WorkerPool(WorkerPool::kMostWorkers + 1), ArgumentError);
  EXPECT_THROW(WorkerPool(1000000000), ArgumentError);
  EXPECT_EQ(resolve_thread_count(3), 3);
  EXPECT_GE(resolve_thread_count(0), 1);
}

// With the address space capped, the system refuses a thread partway
// through 1024 (each reserves its stack): the pool stops and joins the ones
// it started and throws, and the threads' resources are back (a pool can be
// made again). Not under AddressSanitizer, which reserves terabytes.
TEST(WorkerPool, AThreadTheSystemRefusesStopsTheStartedOnesAndThrows) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the address-space cap does not work under AddressSanitizer";
#else
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &before), 0);
  const rlimit cap{rlim_t{2} << 30, before.rlim_max};
  ASSERT_EQ(setrlimit(RLIMIT_AS, &cap), 0);
  // The cap ends with the test (the tests after it in a whole-binary run).
  struct Restore {
    rlimit limit;
    ~Restore() { setrlimit(RLIMIT_AS, &limit); }
  } restore{before};
  try {
    WorkerPool pool(WorkerPool::kMostWorkers);
    GTEST_SKIP() << "the system started " << WorkerPool::kMostWorkers << " threads within 2 GiB";
  } catch (const ArgumentError& error) {
    EXPECT_NE(std::string(error.what()).find("the system refused worker thread"), std::string::npos) << error.what();
  }
  WorkerPool again(4);
  std::atomic<int> sum{0};
  again.run(100, [&](int, std::size_t begin, std::size_t end) { sum += static_cast<int>(end - begin); });
  EXPECT_EQ(sum.load(), 100);
#endif
}

}  // namespace
}  // namespace mrcloth
