#pragma once
// One process runs every item, in order.

#include <weft/distributed/WorkDistributor.h>

namespace weft {

class SerialDistributor : public WorkDistributor {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::string description() const override { return "serial"; }
  std::vector<WorkItemResult> map(std::size_t count, const Work& work) override;
  void rootFirst(const std::function<void()>& step) override { step(); }
};

}  // namespace weft
