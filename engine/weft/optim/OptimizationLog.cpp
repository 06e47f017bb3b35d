#include <weft/optim/OptimizationLog.h>

namespace weft {

void OptimizationLog::add(LogEntry entry) {
  entries_.push_back(std::move(entry));
  if (entries_.back().loss < entries_[best_].loss) best_ = entries_.size() - 1;
  if (observer_) observer_(entries_.back());
}

}  // namespace weft
