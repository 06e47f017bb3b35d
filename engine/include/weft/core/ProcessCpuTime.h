#pragma once
// CPU seconds used so far by this process, all threads together. Benchmarks report it beside
// wall time: on a machine shared with other jobs the wall time includes waiting for a core, the
// CPU time is the work done.

#include <ctime>

namespace weft {

inline double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace weft
