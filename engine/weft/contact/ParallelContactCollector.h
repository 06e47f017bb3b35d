#pragma once
// Contact detection in parallel without locks: each OpenMP thread appends the contacts it finds
// to its own buffer (kept between steps, so no allocation once they have grown), and the buffers
// are concatenated in thread order afterwards. The caller sorts the result, so the contact order
// never depends on the thread count.

#include <weft/record/ContactPoint.h>

#include <omp.h>

#include <vector>

namespace weft {

class ParallelContactCollector {
 public:
  // Calls visit(k, buffer) for k in [0, count), spread over the threads with a static schedule,
  // and appends everything the calls pushed to `out`.
  template <class Visit>
  void collect(int count, std::vector<ContactPoint>& out, Visit visit) {
    const int threads = omp_get_max_threads();
    if (static_cast<int>(perThread_.size()) < threads) perThread_.resize(threads);
    int used = 1;
#pragma omp parallel
    {
      std::vector<ContactPoint>& local = perThread_[omp_get_thread_num()];
      local.clear();
#pragma omp single
      used = omp_get_num_threads();
#pragma omp for schedule(static)
      for (int k = 0; k < count; ++k) visit(k, local);
    }
    for (int t = 0; t < used; ++t)
      out.insert(out.end(), perThread_[t].begin(), perThread_[t].end());
  }

 private:
  std::vector<std::vector<ContactPoint>> perThread_;
};

}  // namespace weft
