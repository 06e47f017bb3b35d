#pragma once
// The ranks of MPI_COMM_WORLD (a duplicate of it) as a WorkDistributor: rank 0 hands out items
// from a thread of its own while its main thread runs items too; the other ranks ask for an
// item, run it, and send its result with the next request. Waits poll with short sleeps rather
// than MPI's busy-waiting, so that a rank waiting for others leaves its core to them.

#include <weft/distributed/WorkDistributor.h>

#include <mpi.h>

namespace weft {

class MpiDistributor : public WorkDistributor {
 public:
  // MPI must be initialised with at least MPI_THREAD_SERIALIZED.
  MpiDistributor();
  ~MpiDistributor() override;
  MpiDistributor(const MpiDistributor&) = delete;
  MpiDistributor& operator=(const MpiDistributor&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::string description() const override;
  std::vector<WorkItemResult> map(std::size_t count, const Work& work) override;
  void rootFirst(const std::function<void()>& step) override;

 private:
  std::vector<WorkItemResult> mapOnRoot(std::size_t count, const Work& work);
  void mapOnWorker(const Work& work);
  // Every rank leaves with rank 0's `results`.
  void shareResults(std::vector<WorkItemResult>& results, std::size_t count);

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
};

}  // namespace weft
