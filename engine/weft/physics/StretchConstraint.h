#pragma once
// Membrane stretching, one constraint per triangle with two rows (the columns of the 3x2
// deformation gradient F = [x1-x0, x2-x0] D^{-1}); the projection is the closest matrix with
// orthonormal columns (as-rigid-as-possible, Bouaziz et al. 2014, as DiffCloth uses).
// Weight per row: stretch stiffness (N/m) times rest area, so W = k A |F - R|^2 / 2.

#include <weft/physics/ProjectiveConstraint.h>

#include <memory>
#include <vector>

namespace weft {

struct ClothModel;
struct Scene;

class StretchConstraint final : public ProjectiveConstraint {
 public:
  // One triangle per entry of `triangles` (global node indices), stiffness per triangle.
  StretchConstraint(const NodeMatrix& rest, const TriangleIndices& triangles,
                    const std::vector<double>& stiffness);
  const char* name() const override { return "stretch"; }
  std::unique_ptr<ProjectiveConstraint> clone() const override {
    return std::make_unique<StretchConstraint>(*this);
  }
  double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const override;
  int triangleCount() const { return static_cast<int>(nodes_.size()); }
  bool hasDerivative() const override { return true; }
  void prepareDerivative(const NodeMatrix& x, bool definite) override;
  void applyDerivative(const NodeMatrix& dx, NodeMatrix& weightedRows) const override;
  bool derivativeBlocks(DerivativeBlockSink& sink) const override;

  // Deformation gradient coefficients: F column c = sum_j coeff[t](c, j) x_{node j}.
  using Coefficients = Eigen::Matrix<double, 2, 3>;
  const Coefficients& coefficients(int t) const { return coeff_[t]; }
  // Closest 3x2 matrix with orthonormal columns to F, computed in the triangle's own frame.
  static Eigen::Matrix<double, 3, 2> project(const Eigen::Matrix<double, 3, 2>& f, const Vec3& x0,
                                             const Vec3& x1, const Vec3& x2);

 private:
  std::vector<Eigen::Vector3i> nodes_;
  std::vector<Coefficients> coeff_;
  // Per triangle at the prepared state: dQ(dF) = rot * QJ <QJ, dF>/2 + n (n^T dF) B, with Q the
  // projection, n the unit normal, rot = 2/(s1+s2) and B = S^{-1} for S = Q^T F (clamped to
  // min(1, .) when definite).
  struct Derivative {
    Eigen::Matrix<double, 3, 2> q;
    Vec3 n;
    double rot;
    double b00, b01, b11;
  };
  std::vector<Derivative> derivative_;
};

// Builds the stretch constraint for every cloth of the scene with stretch > 0.
StretchConstraint makeStretchConstraint(const Scene& scene, const ClothModel& model);

}  // namespace weft
