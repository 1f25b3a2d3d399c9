// How many cores this process can use without taking turns with its neighbours.
//
// A loop shared among more threads than the cores left free runs slower than on one thread: a
// helper is taken off its core for a time slice (milliseconds) while the others wait for the index
// it holds, and the thread that hands out the loops loses turns too. On two cores, beside
// one process spinning on a core, a 128 x 96 step took 10-15 % longer on two threads than on one.
// So a live server shares its loops among no more threads than the cores its neighbours leave:
//   others = (CPU time of the whole machine - CPU time of this process) / wall time
//   budget = cores - floor(others + kSlack)
// over the last kWindowSeconds, from /proc/stat and the process's CPU clock (libgomp's dynamic
// thread count, OMP_DYNAMIC, likewise asks the load average). A neighbour that uses under
// 1 - kSlack of a core is not counted. Where an index runs never changes what it computes, so
// results are the same bit for bit whatever the budget.
#pragma once

#include <atomic>
#include <mutex>
#include <optional>
#include <string>

namespace flagsim {

/// What the machine and this process have run so far, s of CPU time.
struct CpuTimes {
  double machine = 0;  ///< every core's busy time (user, nice, system, interrupts, steal)
  double process = 0;  ///< this process's
};

/// The busy time in a /proc/stat text, s at `ticks_per_second`; nothing if it has no cpu line.
std::optional<double> MachineBusySeconds(const std::string& proc_stat, double ticks_per_second);

/// The cores free for this process between two readings `seconds` apart, at least 1.
int FreeCores(int cores, const CpuTimes& before, const CpuTimes& after, double seconds);

class CoreBudget {
 public:
  static constexpr double kWindowSeconds = 0.25;
  static constexpr double kSlack = 0.4;

  explicit CoreBudget(int cores) : cores_(cores), budget_(cores) {}

  /// The budget at `now` (s, steady clock), read again once a window has passed since the last
  /// reading. Any thread may ask; one reads while the others take the last budget.
  int Cores(double now);

 private:
  int cores_;
  std::atomic<int> budget_;
  std::atomic<double> next_reading_{0};
  std::mutex reading_;  ///< held by the thread that reads
  double last_time_ = -1;
  CpuTimes last_;
};

}  // namespace flagsim
