#include "server/parallel/core_budget.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "server/parallel/worker_pool.hpp"

namespace flagsim {
namespace {

// /proc/stat's first line, in ticks: busy is user + nice + system + irq + softirq + steal.
TEST(CoreBudget, ReadsTheMachinesBusyTimeFromProcStat) {
  EXPECT_DOUBLE_EQ(*MachineBusySeconds("cpu  100 20 30 5000 40 5 6 7 0 0", 100),
                   (100 + 20 + 30 + 5 + 6 + 7) / 100.0);
  EXPECT_DOUBLE_EQ(*MachineBusySeconds("cpu 100 20 30 5000 40 5 6", 100), 1.61);  // no steal column
  EXPECT_FALSE(MachineBusySeconds("cpu0 1 2 3 4 5 6 7 8", 100).has_value());
  EXPECT_FALSE(MachineBusySeconds("intr 12 0 0", 100).has_value());
  EXPECT_FALSE(MachineBusySeconds("cpu 1 2", 100).has_value());
}

// What the other processes ran over the window, in cores, takes that many from the budget once
// it reaches 1 - kSlack of a core; one core is always left.
TEST(CoreBudget, LeavesTheCoresThatOthersTake) {
  const auto free_cores = [](int cores, double machine, double process) {
    return FreeCores(cores, CpuTimes{10, 3}, CpuTimes{10 + machine, 3 + process}, 1.0);
  };
  EXPECT_EQ(free_cores(2, 2.0, 2.0), 2);  // this process alone on both cores
  EXPECT_EQ(free_cores(2, 2.0, 1.0), 1);  // a neighbour spins on one core
  EXPECT_EQ(free_cores(2, 1.3, 1.0), 2);  // a light neighbour: 0.3 of a core
  EXPECT_EQ(free_cores(2, 1.0 + (1 - CoreBudget::kSlack) + 0.05, 1.0), 1);  // just over the slack
  EXPECT_EQ(free_cores(2, 2.0, 0.0), 1);  // others take everything: still one
  EXPECT_EQ(free_cores(8, 5.0, 2.0), 5);
  EXPECT_EQ(free_cores(2, 0.5, 0.6), 2);                        // the two clocks' ticks disagree: nobody else
  EXPECT_EQ(FreeCores(4, CpuTimes{}, CpuTimes{9, 0}, 0.0), 4);  // no time passed: no evidence
}

// A pool hands out the threads asked for unless told to share the free cores only; then between
// one and the number asked for.
TEST(CoreBudget, APoolAllowsAtMostTheThreadsAskedFor) {
  WorkerPool pool;
  EXPECT_EQ(pool.Threads(2), 2);
  EXPECT_EQ(pool.Threads(1), 1);
  pool.ShareFreeCoresOnly(true);
  const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  for (int call = 0; call < 3; ++call) {
    const int threads = pool.Threads(cores);
    EXPECT_GE(threads, 1);
    EXPECT_LE(threads, cores);
  }
  EXPECT_EQ(pool.Threads(1), 1);
}

}  // namespace
}  // namespace flagsim
