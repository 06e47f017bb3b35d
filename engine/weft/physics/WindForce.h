#pragma once
#include <weft/physics/ExternalForce.h>
#include <weft/scene/Scene.h>

namespace weft {

// The per-node coefficient k of Eq. 35: the lumped area (a pressure wind), or with a falloff
// centre the inverse distance to it (the Flag's wind, Appendix B.4).
inline const Eigen::VectorXd& windCoefficients(const Wind& wind,
                                               const Eigen::VectorXd& lumpedArea) {
  return wind.falloffCenter ? wind.coefficients : lumpedArea;
}

// DiffCloth's sinusoidal wind (Appendix B.1, Eq. 35): each node receives
// strength * k_i * 0.5 (sin(2 pi frequency t + phase) + 1) * direction, k_i its lumped area or its
// inverse distance to the falloff centre; "constant" drops the time factor.
class WindForce final : public ExternalForce {
 public:
  WindForce(const Wind& wind, const Eigen::VectorXd& lumpedArea)
      : wind_(wind), area_(windCoefficients(wind, lumpedArea)) {}
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
