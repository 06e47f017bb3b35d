#pragma once
// The backward pass over a recorded run (DiffCloth Sec. 4): for each step n = N-1 .. 0, with the
// recorded x_{n+1} and the step's recorded contacts,
//
//   g_hat   = dL/dx_{n+1} + (dL/dv_{n+1}) / h          (v_{n+1} = (x_{n+1} - x_n)/h)
//   K z     = g_hat                                     (Eq. 19, or Eq. 29 transposed with contact)
//   wbar    = R'^T z                                    (zero without contact; ContactAdjoint.h)
//   dL/dx_n += M z - (dL/dv_{n+1}) / h + (contact frames)  (Eq. 16: dx_{n+1}/dx_n = K^{-1} M)
//   dL/dv_n  = h M (z + wbar) + (contact frames)        (v_n enters the step and the free momentum)
//   dL/dtheta += -(z + wbar) . dG/dtheta + (contact law) (ParameterPartials, ContactAdjoint)
//
// and at n = 0 the initial-state gradients. One step of it is StepBackward's (StepBackward.h);
// the per-step solve is AdjointSolver's.

#include <weft/diff/AdjointSolver.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>
#include <weft/record/StepProgress.h>
#include <weft/record/Trajectory.h>

#include <Eigen/Core>

#include <string>

namespace weft {

// What is known of a gradient's error from its linear solves (the forward pass is taken as
// given). backpropagate fills it from one pass; backpropagateToAccuracy
// (diff/GradientErrorControl.h) from two passes at different tolerances.
struct GradientErrorEstimate {
  // |g - g_exact|_2 / |g|_2 over the parameters, estimated (0 for a zero gradient that is
  // exactly zero), and each parameter's |g_i - g_exact,i|.
  double relative = 0.0;
  Eigen::VectorXd absolute;
  double requested = 0.0;  // solver.backward.accuracy (0: not controlled)
  bool met = true;         // relative <= requested (true when not controlled)
  int passes = 1;          // backward passes made for this gradient
  double tolerance = 0.0;  // the returned pass's relative residual per step (0: direct)
  // How `relative` was obtained: "difference", the returned pass against one at a 100 times
  // looser tolerance (an upper estimate: the error falls with the tolerance); "fit", tolerance *
  // sqrt(growth) / 100 (diff/AdjointGrowth.h, a size, not a bound); "round-off", machine
  // epsilon times the adjoint's growth for a direct pass (a size, not a bound).
  std::string basis = "fit";
};

struct GradientResult {
  double loss = 0.0;
  Eigen::VectorXd gradient;  // dL/dtheta, in the ParameterSet's order
  NodeMatrix dLdx0, dLdv0;   // initial-state gradients
  // dL/dx_n for every state n = 0..N: the loss's derivative with respect to state n's positions
  // with its velocities held (dLdx[0] is dLdx0). The editor's vertex inspector shows it.
  std::vector<NodeMatrix> dLdx;
  AdjointSolverStats solver;
  double seconds = 0.0;
  // Of `seconds`: preparing Delta P (the projections' derivatives at x_{n+1}, Eq. 18) and the
  // contact part Delta R (ContactAdjoint::prepare: law Jacobians, frames, the coupling LU). The
  // linear solves are solver.seconds; the rest (losses, partials, state gradients) is the
  // remainder.
  double deltaPSeconds = 0.0, deltaRSeconds = 0.0;
  GradientErrorEstimate error;
};

// One backward pass: backpropagates `loss` through `trajectory` (recorded by Simulator::run, e.g.
// through runForwardPass), with the model it carries: the forward's constraints, obstacles and dt.
// Throws std::invalid_argument for a trajectory without a model (one read from a run folder).
// `progress` (optional) hears of every step, as backward pass `pass`.
GradientResult backpropagate(const Trajectory& trajectory, const TaskLoss& loss,
                             const ParameterSet& parameters, const BackwardSettings& settings,
                             const StepProgress& progress = {}, int pass = 1);

}  // namespace weft
