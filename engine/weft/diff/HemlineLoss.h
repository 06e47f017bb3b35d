#pragma once
// Hemline height (task.loss.hemline; DiffCloth Appendix B, Dress, Eq. 34: L = sum_{p in P}
// (h_p - h)^2 over the points P on the bottom of the dress, h_p their y coordinate, h the height
// the hemline reaches when the twirling dress forms the desired apex angle):
//
//   L = weight * sum_{n in S} (1/|V|) sum_{i in V} (up . x_n,i - height)^2   (m^2),
//
// V the hemline vertices (global indices), S the chosen states (default: the last), `up` a unit
// vector (default +Y, the paper's y). The mean over V, where Eq. 34 sums, keeps the loss's scale
// independent of how finely the hemline is meshed. The target height is given directly or from
// an apex angle: a cone with apex at height a (along `up`) and opening angle alpha puts a hem at
// slant distance l from the apex at height a - l cos(alpha/2) (targetHemlineHeight).

#include <weft/diff/LossTerm.h>

#include <vector>

namespace weft {

// The hem height of a cone with apex height `apexHeight`, full opening angle `apexAngleDeg`
// (degrees, 0..180) and slant length `slantLength` from the apex to the hem.
double targetHemlineHeight(double apexAngleDeg, double apexHeight, double slantLength);

class HemlineLoss final : public LossTerm {
 public:
  HemlineLoss(std::vector<int> vertices, std::vector<int> states, const Vec3& up, double height,
              double weight);
  const char* name() const override { return "hemline"; }
  double value(const Trajectory& trajectory) const override;
  void addGradient(const Trajectory& trajectory, std::vector<NodeMatrix>& gradient) const override;
  double height() const { return height_; }

 private:
  std::vector<int> vertices_;
  std::vector<int> states_;
  Vec3 up_;
  double height_;
  double weight_;
};

}  // namespace weft
