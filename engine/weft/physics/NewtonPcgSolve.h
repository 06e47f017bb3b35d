#pragma once
// solver.method = "newton" without contact (the default), and the steps of contact scenes that
// have no contact to solve: Newton on the implicit-Euler energy g (DiffCloth Eq. 3) with
// conjugate gradients preconditioned by the prefactorised P, an Armijo line search and the PD
// step as the fallback. With an ActiveContactSet the same iteration runs on its constraints
// (ActiveSetSolve).

#include <weft/physics/StepSolver.h>

namespace weft {

class ActiveContactSet;

class NewtonPcgSolve final : public StepSolver {
 public:
  void solve(StepContext& ctx) override { iterate(ctx, nullptr); }
  // Newton-PCG iterations from ctx.iterate until the residual is below tolerance (true) or the
  // solve budget (solver.pd_iterations) is spent. With `contacts`, iterates stay on its
  // constraints and its slip friction acts.
  static bool iterate(StepContext& ctx, ActiveContactSet* contacts);
};

}  // namespace weft
