#include "ProcessMemory.h"

#include <fstream>
#include <sstream>
#include <string>

namespace weft::bench {
namespace {

// The value of a "Key:   1234 kB" line of /proc/self/status, in MB.
double statusMb(const char* key) {
  std::ifstream status("/proc/self/status");
  const std::string prefix = std::string(key) + ":";
  for (std::string line; std::getline(status, line);)
    if (line.rfind(prefix, 0) == 0) {
      std::istringstream s(line.substr(prefix.size()));
      double kb = 0.0;
      s >> kb;
      return kb / 1024.0;
    }
  return 0.0;
}

}  // namespace

bool resetPeakMemory() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return static_cast<bool>(f);
}

double peakMemoryMb() {
  return statusMb("VmHWM");
}

double residentMemoryMb() {
  return statusMb("VmRSS");
}

}  // namespace weft::bench
