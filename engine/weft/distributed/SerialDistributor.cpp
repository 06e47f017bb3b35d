#include "SerialDistributor.h"

namespace weft {

std::vector<WorkItemResult> SerialDistributor::map(std::size_t count, const Work& work) {
  std::vector<WorkItemResult> results;
  results.reserve(count);
  for (std::size_t i = 0; i < count; ++i) results.push_back(runWorkItem(work, i, 0));
  return results;
}

std::unique_ptr<WorkDistributor> makeSerialDistributor() {
  return std::make_unique<SerialDistributor>();
}

}  // namespace weft
