#pragma once
// Bending, one constraint per interior edge (hinge) with one row: the cotangent-weighted
// discrete mean-curvature vector e = sum_k w_k x_k over the hinge's four nodes (Bergou et al.
// 2006, Wardetzky et al. 2007, as used by Bouaziz et al. 2014 and DiffCloth). The projection
// keeps the rest curvature magnitude: p = |e_rest| e/|e|, and p = 0 for a flat rest hinge, which
// makes the energy purely quadratic. Weight: bend stiffness (N m) * 3 / (A0 + A1).
//
// The magnitude projection forgets which side a hinge curves to, and its energy
// (|e| - |e_rest|)^2 / 2 is concave across e where |e| < |e_rest|, with Hessian eigenvalue
// 1 - |e_rest|/|e| (about -4 at a fifth of the rest curvature), its force turning round as e
// passes zero. A tube's hinges pressed flat against an obstacle sit there, and the Sock's step
// solves stalled on them (docs/applications.md, "Where the forward solve stalls"). The
// "oriented" model (material.bend_model) instead carries the rest curvature vector with the
// hinge's frame: p = F(x_n) c, where F = [t, N^, t x N^] (t along the edge, N^ = N/|N| with
// N = n0/|n0| + n1/|n1| from the two triangles' normals) is taken at the step's start x_n and
// c = F(X)^T e_rest holds e_rest's components in the rest frame (so p = e_rest at rest, on the
// rest shape's side whatever the mesh's winding). Within a step p is a constant, so the hinge's
// energy is quadratic and convex (no derivative, P alone); the frame lags one step behind, and
// the adjoint carries dp/dx_n back (addStartGradient).

#include <weft/physics/ProjectiveConstraint.h>

#include <memory>
#include <vector>

namespace weft {

struct ClothModel;
struct Scene;

struct Hinge {
  int nodes[4];     // edge (0, 1), opposite vertices 2 (in triangle 0) and 3 (in triangle 1)
  double cot[4];    // w_k
  double restNorm;  // |sum_k w_k X_k| at rest; 0 for a flat hinge
  double weight;
  bool oriented = false;          // material.bend_model "oriented" (and curved at rest)
  Vec3 restLocal = Vec3::Zero();  // c: e_rest in the rest frame [t, N^, t x N^]
};

class BendingConstraint final : public ProjectiveConstraint {
 public:
  BendingConstraint(std::vector<Hinge> hinges, int nodes);
  const char* name() const override { return "bending"; }
  std::unique_ptr<ProjectiveConstraint> clone() const override {
    return std::make_unique<BendingConstraint>(*this);
  }
  double project(const NodeMatrix& x, NodeMatrix& weightedProjections) const override;
  bool projectsToZero() const override { return allFlat_; }
  double energy(const NodeMatrix& x) const override;
  bool hasDerivative() const override { return !allFlat_; }
  void prepareDerivative(const NodeMatrix& x, bool definite) override;
  void applyDerivative(const NodeMatrix& dx, NodeMatrix& weightedRows) const override;
  bool derivativeBlocks(DerivativeBlockSink& sink) const override;
  void beginStep(double time, const NodeMatrix& start) override;
  bool dependsOnStart() const override { return anyOriented_; }
  void addStartGradient(const NodeMatrix& start, const NodeMatrix& q, double scale,
                        NodeMatrix& out) const override;
  const std::vector<Hinge>& hinges() const { return hinges_; }

 private:
  std::vector<Hinge> hinges_;
  bool allFlat_ = true;
  bool anyOriented_ = false;
  // Per hinge: the oriented target p at the step's start (beginStep; empty before the first).
  std::vector<Vec3> target_;
  // Per hinge at the prepared state: dp = scale (I - u u^T) de, u = e/|e|, scale = |e_rest|/|e|.
  std::vector<Vec3> unit_;
  std::vector<double> scale_;
};

// Hinges of every interior manifold edge of the cloths with bend > 0.
std::vector<Hinge> buildHinges(const NodeMatrix& rest, const TriangleIndices& triangles,
                               double stiffness, bool oriented = false);
BendingConstraint makeBendingConstraint(const Scene& scene, const ClothModel& model);

}  // namespace weft
