#pragma once
// The backward pass over a recorded run without contact (DiffCloth Sec. 4.1): for each step
// n = N-1 .. 0, with the recorded x_{n+1},
//
//   g_hat   = dL/dx_{n+1} + (dL/dv_{n+1}) / h          (v_{n+1} = (x_{n+1} - x_n)/h)
//   K z     = g_hat,  K = P - Delta P(x_{n+1})         (Eq. 19; K symmetric, so K^T = K)
//   dL/dx_n += M z - (dL/dv_{n+1}) / h                 (Eq. 16: dx_{n+1}/dx_n = K^{-1} M)
//   dL/dv_n  = h M z                                    (the same system, Sec. 4.1 end)
//   dL/dtheta += -z . dG/dtheta                          (ParameterPartials)
//
// and at n = 0 the initial-state gradients. The per-step solve is AdjointSolver's.

#include <weft/diff/AdjointSolver.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>
#include <weft/physics/Trajectory.h>
#include <weft/scene/Scene.h>

#include <Eigen/Core>

namespace weft {

struct GradientResult {
  double loss = 0.0;
  Eigen::VectorXd gradient;  // dL/dtheta, in the ParameterSet's order
  NodeMatrix dLdx0, dLdv0;   // initial-state gradients
  AdjointSolverStats solver;
  double seconds = 0.0;
};

// Throws InputError naming the obstacle or self-collision path: gradients through contact are
// not yet supported.
void requireContactFree(const Scene& scene);

// Backpropagates `loss` through `trajectory` (recorded from `scene` by runForwardPass).
GradientResult backpropagate(const Scene& scene, const Trajectory& trajectory, const TaskLoss& loss,
                             const ParameterSet& parameters, const BackwardSettings& settings);

}  // namespace weft
