#include "server/parallel/worker_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace flagsim {
namespace {

// Every index runs once, whatever the count and the thread count.
TEST(WorkerPool, RunsEveryIndexOnce) {
  WorkerPool pool;
  for (const int threads : {1, 2, 3, 8}) {
    for (const int count : {0, 1, 2, 7, 100, 1000}) {
      std::vector<std::atomic<int>> runs(count);
      pool.Run(count, threads, [&](int i, int) { runs[i].fetch_add(1); });
      for (int i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << "index " << i << " of " << count;
    }
  }
}

// Participants number the threads of one loop: below `threads`, and never two at once.
TEST(WorkerPool, ParticipantsAreDistinctAndBelowThreads) {
  WorkerPool pool;
  constexpr int kThreads = 3;
  std::vector<std::atomic<int>> inside(kThreads);
  std::atomic<int> shared{0}, out_of_range{0};
  pool.Run(3000, kThreads, [&](int, int participant) {
    if (participant < 0 || participant >= kThreads) {
      out_of_range.fetch_add(1);
      return;
    }
    if (inside[participant].fetch_add(1) != 0) shared.fetch_add(1);
    volatile double spin = 0;
    for (int k = 0; k < 200; ++k) spin = spin + k;
    inside[participant].fetch_sub(1);
  });
  EXPECT_EQ(out_of_range.load(), 0);
  EXPECT_EQ(shared.load(), 0);
}

// With one thread the caller runs every index itself, in order.
TEST(WorkerPool, OneThreadRunsInOrderOnTheCaller) {
  WorkerPool pool;
  std::vector<int> order;
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  pool.Run(5, 1, [&](int i, int) {
    order.push_back(i);
    elsewhere |= std::this_thread::get_id() != caller;
  });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_FALSE(elsewhere);
}

// Loops from two threads at once, and a loop inside a loop's body, all finish: the caller always
// works through its own loop, so no loop waits on a worker that is busy elsewhere.
TEST(WorkerPool, ConcurrentAndNestedLoopsFinish) {
  WorkerPool pool;
  std::atomic<long> sum{0};
  const auto nested = [&] {
    for (int repeat = 0; repeat < 200; ++repeat) {
      pool.Run(8, 2, [&](int i, int) { pool.Run(4, 2, [&](int j, int) { sum.fetch_add(i * 4 + j); }); });
    }
  };
  std::thread other(nested);
  nested();
  other.join();
  EXPECT_EQ(sum.load(), 2L * 200 * (31 * 32 / 2));
}

// A helper that stops inside its share (the kernel took its core: here, a body that waits until
// the rest of its share has run elsewhere) holds back that index only: the caller takes the rest
// of its share once it has made no progress for kStallSeconds.
TEST(WorkerPool, AStalledShareIsTakenFromItsParticipant) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core: a loop has no helper";
  WorkerPool pool;
  constexpr int kHalf = 8;
  std::vector<std::atomic<int>> ran_on(2 * kHalf);
  for (auto& participant : ran_on) participant.store(-1);
  // Waits until index `i` has run somewhere, for at most 10 s.
  const auto wait_for = [&](int i) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (ran_on[i].load() < 0 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
  };
  pool.Run(2 * kHalf, 2, [&](int i, int participant) {
    ran_on[i].store(participant);
    if (i == 0) wait_for(kHalf);  // the caller lets the helper reach its first index
    if (i == kHalf && participant == 1) wait_for(2 * kHalf - 1);  // the helper stalls there
  });
  ASSERT_EQ(ran_on[kHalf].load(), 1) << "no helper joined";
  int taken = 0;
  for (int i = kHalf + 1; i < 2 * kHalf; ++i) taken += ran_on[i].load() == 0;
  EXPECT_EQ(taken, kHalf - 1) << "the caller should have run the rest of the stalled share";
}

// The free functions: the same results as a plain loop.
TEST(ParallelFor, MatchesAPlainLoop) {
  std::vector<int> squares(257);
  ParallelFor(257, 2, [&](int i) { squares[i] = i * i; });
  for (int i = 0; i < 257; ++i) ASSERT_EQ(squares[i], i * i);
}

}  // namespace
}  // namespace flagsim
