#pragma once
#include <weft/physics/ExternalForce.h>
#include <weft/scene/Scene.h>

namespace weft {

// DiffCloth's sinusoidal wind (Appendix B.1, Eq. 35 with k = lumped area): each node receives
// strength * area_i * 0.5 (sin(2 pi frequency t + phase) + 1) * direction; "constant" drops the
// time factor.
class WindForce final : public ExternalForce {
 public:
  WindForce(const Wind& wind, const Eigen::VectorXd& lumpedArea) : wind_(wind), area_(lumpedArea) {}
  const char* name() const override { return "wind"; }
  double timeFactor(double t) const;
  void accumulate(double t, NodeMatrix& f) const override {
    f += (wind_.strength * timeFactor(t)) * area_ * wind_.direction.transpose();
  }

 private:
  Wind wind_;
  Eigen::VectorXd area_;
};

}  // namespace weft
