// Time stamps for LCM messages: utime, microseconds since the Unix epoch.
#pragma once

#include <chrono>
#include <cstdint>

namespace flagsim {

inline int64_t UnixMicros() {
  using namespace std::chrono;
  return duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
}

/// Seconds on a monotonic clock, for measuring intervals.
inline double MonotonicSeconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace flagsim
