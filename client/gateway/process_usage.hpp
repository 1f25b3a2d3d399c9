// This process's CPU time and resident memory, from /proc (Linux), for the gateway's status.
#pragma once

#include <cstdint>

namespace flagsim::gateway {

struct ProcessUsage {
  double cpu_seconds = 0;      ///< user + system time since the process started
  int64_t resident_bytes = 0;  ///< resident set size
};

/// Zeros where /proc cannot be read.
ProcessUsage ReadProcessUsage();

}  // namespace flagsim::gateway
