#include "client/gateway/process_usage.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace flagsim::gateway {

// /proc/self/stat: the 14th and 15th fields are utime and stime in clock ticks; the command
// name (field 2) is in parentheses and may hold spaces, so fields are counted after its ')'.
// /proc/self/statm: the second field is resident pages.
ProcessUsage ReadProcessUsage() {
  ProcessUsage usage;
  std::ifstream stat("/proc/self/stat");
  std::string line;
  if (std::getline(stat, line) && line.rfind(')') != std::string::npos) {
    std::istringstream fields(line.substr(line.rfind(')') + 2));
    std::string field;
    double ticks = 0;
    for (int index = 3; fields >> field && index <= 15; ++index) {
      if (index == 14 || index == 15) ticks += std::stod(field);
    }
    usage.cpu_seconds = ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
  }
  std::ifstream statm("/proc/self/statm");
  int64_t size_pages = 0, resident_pages = 0;
  if (statm >> size_pages >> resident_pages) usage.resident_bytes = resident_pages * sysconf(_SC_PAGESIZE);
  return usage;
}

}  // namespace flagsim::gateway
