#include "WorkerThreads.h"

#include <omp.h>

#include <algorithm>
#include <cstdlib>

namespace weft::editor {

void useWorkerThreads() {
  int threads = std::max(1, omp_get_num_procs() - 1);
  if (const char* text = std::getenv("WEFT_EDITOR_THREADS")) {
    const int asked = std::atoi(text);
    if (asked > 0) threads = asked;
  }
  omp_set_num_threads(threads);
}

}  // namespace weft::editor
