// Seconds of CPU time of the calling thread: what the lab times single-threaded work in, since
// other processes on a shared machine change wall time far more than they change it.
#pragma once

#include <time.h>

namespace flagsim::lab {

inline double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

}  // namespace flagsim::lab
