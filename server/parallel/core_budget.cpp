#include "server/parallel/core_budget.hpp"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace flagsim {
namespace {

/// Now, or nothing where /proc/stat or the process clock cannot be read.
std::optional<CpuTimes> ReadCpuTimes() {
  std::ifstream file("/proc/stat");
  std::string first_line;
  if (!std::getline(file, first_line)) return std::nullopt;
  const std::optional<double> machine = MachineBusySeconds(first_line, double(sysconf(_SC_CLK_TCK)));
  timespec process{};
  if (!machine || clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &process) != 0) return std::nullopt;
  return CpuTimes{*machine, double(process.tv_sec) + 1e-9 * double(process.tv_nsec)};
}

}  // namespace

// "cpu  user nice system idle iowait irq softirq steal ...", in ticks: busy is all but idle and
// iowait (guest time is inside user already).
std::optional<double> MachineBusySeconds(const std::string& proc_stat, double ticks_per_second) {
  std::istringstream line(proc_stat);
  std::string label;
  double user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  line >> label >> user >> nice >> system >> idle >> iowait >> irq >> softirq;
  if (!line || label != "cpu" || ticks_per_second <= 0) return std::nullopt;
  line >> steal;  // absent on old kernels
  return (user + nice + system + irq + softirq + (line ? steal : 0)) / ticks_per_second;
}

int FreeCores(int cores, const CpuTimes& before, const CpuTimes& after, double seconds) {
  if (seconds <= 0) return cores;
  const double others =
      std::max(0.0, (after.machine - before.machine) - (after.process - before.process)) / seconds;
  return std::clamp(cores - int(std::floor(others + CoreBudget::kSlack)), 1, cores);
}

int CoreBudget::Cores(double now) {
  if (now < next_reading_.load(std::memory_order_relaxed)) return budget_.load(std::memory_order_relaxed);
  const std::unique_lock<std::mutex> lock(reading_, std::try_to_lock);
  if (!lock.owns_lock()) return budget_.load(std::memory_order_relaxed);
  next_reading_.store(now + kWindowSeconds, std::memory_order_relaxed);
  const std::optional<CpuTimes> times = ReadCpuTimes();
  if (!times) return budget_.load(std::memory_order_relaxed);
  if (last_time_ >= 0) budget_.store(FreeCores(cores_, last_, *times, now - last_time_));
  last_time_ = now;
  last_ = *times;
  return budget_.load(std::memory_order_relaxed);
}

}  // namespace flagsim
