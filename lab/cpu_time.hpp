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

/// CPU seconds of this thread per call of `call`, which is called until at least `seconds` of
/// CPU have gone; the number of calls in `*calls` if given.
template <typename Call>
double CpuSecondsPerCall(double seconds, Call&& call, int* calls = nullptr) {
  int count = 0;
  const double start = ThreadCpuSeconds();
  double spent = 0;
  while (spent < seconds) {
    call();
    ++count;
    spent = ThreadCpuSeconds() - start;
  }
  if (calls != nullptr) *calls = count;
  return spent / count;
}

}  // namespace flagsim::lab
