#pragma once
#include <weft/physics/ExternalForce.h>

namespace weft {

// m_i g on every node.
class GravityForce final : public ExternalForce {
 public:
  GravityForce(const Vec3& g, const Eigen::VectorXd& mass) : g_(g), mass_(mass) {}
  const char* name() const override { return "gravity"; }
  void accumulate(double, NodeMatrix& f) const override {
    // Row by row: the outer-product expression allocated an m x 3 temporary every step.
    for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) += mass_[i] * g_.transpose();
  }

 private:
  Vec3 g_;
  Eigen::VectorXd mass_;
};

}  // namespace weft
