#pragma once
// The backward pass one step at a time (DiffCloth Sec. 4, Eqs. 16-19 and 29 with contact): for
// step n of a recorded run (state n -> n+1), from dL/dx_{n+1} and dL/dv_{n+1} (everything the
// loss owes to the states after n, through them), the step's part of dL/dx_n, dL/dv_n and its
// part of dL/dtheta:
//
//   g_hat = dL/dx_{n+1} + (dL/dv_{n+1}) / h,   K z = g_hat,   wbar = R'^T z
//   dL/dx_n += M z - (dL/dv_{n+1}) / h + (start-of-step terms, contact frames)
//   dL/dv_n  = h M (z + wbar) + (contact frames)
//   dL/dtheta += -(z + wbar) . dG/dtheta + (contact law)
//
// A step adaptive time stepping split is walked through its pieces. backpropagate() is this from
// the last step to the first; a policy acting between steps (DiffCloth Sec. 6.5) calls it step
// by step. The object keeps the adjoint solver (its warm start from the previous steps'
// solutions) and each dt's prepared system, so calls should go from late steps to early ones.

#include <weft/diff/AdjointGrowth.h>
#include <weft/diff/AdjointSolver.h>
#include <weft/diff/ParameterSet.h>
#include <weft/record/Trajectory.h>

#include <Eigen/Core>

#include <map>
#include <memory>

namespace weft {

class StepBackward {
 public:
  // Throws std::invalid_argument for a trajectory without a model (one read from a run folder).
  StepBackward(const Trajectory& trajectory, const ParameterSet& parameters,
               const BackwardSettings& settings);
  ~StepBackward();
  StepBackward(const StepBackward&) = delete;
  StepBackward& operator=(const StepBackward&) = delete;

  // Step n (0-based, 0 <= n < trajectory.stepCount()): adds the step's dL/dx_n to dLdx0, writes
  // dL/dv_n into dLdv0 and adds the step's dL/dtheta to `gradient` (the ParameterSet's order).
  // dLdx1 and dLdv1 may not alias dLdx0 or dLdv0. Throws NumericalError where the adjoint
  // solve fails (AdjointSolver).
  //
  // With dLdHandleOffsets (model().handles().size() x 3), also adds the step's dL/d(offset) of
  // each handle's target held over the step (Simulator::driveHandle): an attachment row adds
  // h^2 k (x_j - x_hat_j) to G, so -z . dG/d offset = h^2 k sum_j (z + wbar)_j, summed over the
  // pieces of a split step (ParameterPartials' handle term at unit knot weight).
  void step(int n, const NodeMatrix& dLdx1, const NodeMatrix& dLdv1, NodeMatrix& dLdx0,
            NodeMatrix& dLdv0, Eigen::VectorXd& gradient, NodeMatrix* dLdHandleOffsets = nullptr);
  // The initial state's own dependence on the parameters (cloths.K.initial_velocity), from
  // dL/dv_0: added once, after step 0.
  void addInitial(const NodeMatrix& dLdv0, Eigen::VectorXd& gradient) const;

  const AdjointSolverStats& stats() const;
  double adjointGrowth() const;
  double deltaPSeconds() const { return deltaPSeconds_; }
  double deltaRSeconds() const { return deltaRSeconds_; }

 private:
  struct Piece;
  Piece& pieceFor(const std::shared_ptr<const Model>& model);
  void backStep(Piece& a, const NodeMatrix& x0, const NodeMatrix& v0, const NodeMatrix& x1,
                double t1, const StepContacts* stepContacts, const NodeMatrix& dLdx1,
                NodeMatrix& dLdx0, int state, Eigen::VectorXd& gradient);

  const Trajectory& trajectory_;
  const ParameterSet& parameters_;
  bool contacts_;
  std::unique_ptr<Piece> whole_;
  std::map<const Model*, std::unique_ptr<Piece>> pieces_;  // by the split pieces' models
  std::unique_ptr<AdjointSolver> solver_;
  AdjointGrowth growth_;
  NodeMatrix rhs_, z_, wbar_, dLdv_, forceLike_, dLdxPiece_, dLdxPieceNext_, dLdvNext_;
  Eigen::MatrixX3d y_;
  NodeMatrix* handleSink_ = nullptr;  // step()'s dLdHandleOffsets while it runs
  double deltaPSeconds_ = 0.0, deltaRSeconds_ = 0.0;
};

}  // namespace weft
