#include <weft/optim/SearchBox.h>

#include <cmath>

namespace weft {

SearchBox::SearchBox(const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                     const Eigen::VectorXd& upper)
    : start_(start), lower_(lower), upper_(upper), width_(start.size()) {
  for (int i = 0; i < size(); ++i) {
    const double w = upper[i] - lower[i];  // +inf for an open side
    // A variable fixed by its bounds (w = 0) keeps unit scale: the repair pins it anyway.
    width_[i] = w > 0.0 ? std::min(w, kMaxWidth) : 1.0;
  }
}

Eigen::VectorXd SearchBox::repairedCoordinates(const Eigen::VectorXd& u) const {
  return (start_ + width_.cwiseProduct(u)).cwiseMax(lower_).cwiseMin(upper_);
}

Eigen::VectorXd SearchBox::toSearch(const Eigen::VectorXd& z) const {
  return (z - start_).cwiseQuotient(width_);
}

}  // namespace weft
