#pragma once
#include <weft/physics/ExternalForce.h>

namespace weft {

// m_i g on every node.
class GravityForce final : public ExternalForce {
 public:
  GravityForce(const Vec3& g, const Eigen::VectorXd& mass) : g_(g), mass_(mass) {}
  const char* name() const override { return "gravity"; }
  void accumulate(double, NodeMatrix& f) const override { f += mass_ * g_.transpose(); }

 private:
  Vec3 g_;
  Eigen::VectorXd mass_;
};

}  // namespace weft
