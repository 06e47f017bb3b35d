#include "PassiveOpenMpWait.h"

#include <cstdlib>

#include <unistd.h>

namespace weft::process {

void preferPassiveOpenMpWait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 0) != 0) return;
  execv("/proc/self/exe", argv);
  // execv returned: it failed (no /proc). The variable stays set for child processes; this
  // process keeps libgomp's default.
}

}  // namespace weft::process
