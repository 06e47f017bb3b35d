#pragma once
// Bending, one constraint per interior edge (hinge) with one row: the cotangent-weighted
// discrete mean-curvature vector e = sum_k w_k x_k over the hinge's four nodes (Bergou et al.
// 2006, Wardetzky et al. 2007, as used by Bouaziz et al. 2014 and DiffCloth). The projection
// keeps the rest curvature magnitude: p = |e_rest| e/|e|, and p = 0 for a flat rest hinge, which
// makes the energy purely quadratic. Weight: bend stiffness (N m) * 3 / (A0 + A1).

#include <weft/physics/ProjectiveConstraint.h>

#include <vector>

namespace weft {

struct ClothModel;
struct Scene;

struct Hinge {
  int nodes[4];     // edge (0, 1), opposite vertices 2 (in triangle 0) and 3 (in triangle 1)
  double cot[4];    // w_k
  double restNorm;  // |sum_k w_k X_k| at rest; 0 for a flat hinge
  double weight;
};

class BendingConstraint final : public ProjectiveConstraint {
 public:
  BendingConstraint(std::vector<Hinge> hinges, int nodes);
  const char* name() const override { return "bending"; }
  double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const override;
  bool projectsToZero() const override { return allFlat_; }
  double energy(const NodeMatrix& x) const override;
  bool hasDerivative() const override { return !allFlat_; }
  void prepareDerivative(const NodeMatrix& x, bool definite) override;
  void applyDerivative(const NodeMatrix& dx, NodeMatrix& weightedRows) const override;
  bool derivativeBlocks(DerivativeBlockSink& sink) const override;
  const std::vector<Hinge>& hinges() const { return hinges_; }

 private:
  std::vector<Hinge> hinges_;
  bool allFlat_ = true;
  // Per hinge at the prepared state: dp = scale (I - u u^T) de, u = e/|e|, scale = |e_rest|/|e|.
  std::vector<Vec3> unit_;
  std::vector<double> scale_;
};

// Hinges of every interior manifold edge of the cloths with bend > 0.
std::vector<Hinge> buildHinges(const NodeMatrix& rest, const TriangleIndices& triangles,
                               double stiffness);
BendingConstraint makeBendingConstraint(const Scene& scene, const ClothModel& model);

}  // namespace weft
