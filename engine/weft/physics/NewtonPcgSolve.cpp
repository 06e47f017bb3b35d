#include <weft/physics/NewtonPcgSolve.h>

#include <weft/contact/ActiveContactSet.h>

#include <cmath>

namespace weft {

bool NewtonPcgSolve::iterate(StepContext& ctx, ActiveContactSet* contacts) {
  // Newton on g (Eq. 3) with conjugate gradients preconditioned by the prefactorised P. The
  // Hessian is h^-2 (P - Delta P) with the exact projection derivative (the same Delta P the
  // adjoint uses, Sec. 4.1). The first preconditioned residual is exactly the PD step
  // x_global - x, so one CG iteration reproduces PD; further ones add the curvature PD leaves out
  // (the soft out-of-plane modes where P overestimates the stiffness), and convergence becomes
  // quadratic. Where the Hessian is indefinite (compressed triangles), CG stops at the negative
  // curvature, and a step that does not decrease g falls back to the PD step, which always does.
  //
  // With contact constraints (`contacts`), the same iteration runs in the subspace
  // {C d = 0} (projected PCG: residual, preconditioned residual and products projected), on g
  // plus the potential of the lagged slip friction; iterates stay feasible. The PD step is then
  // not a fallback (it leaves the subspace): a step the line search rejects ends the iteration.
  const SolverSettings& solver = ctx.settings;
  const double h2 = ctx.h * ctx.h;
  auto energyAt = [&](const NodeMatrix& x) {
    double e = ctx.localStep(x);
    if (contacts) e += contacts->frictionPotential(x);
    return e;
  };
  double energy = energyAt(ctx.iterate);
  double forcing = 0.5, previousResidual = 0.0;
  auto dot = [](const NodeMatrix& a, const NodeMatrix& b) { return (a.array() * b.array()).sum(); };
  const double velocityTolerance = solver.pdTolerance * ctx.h;
  while (ctx.stats.pdIterations < solver.pdIterations) {
    ctx.globalStep(contacts);
    const bool small = ctx.checkConvergence(
        contacts);  // also leaves r0 = b - P x = P (x_global - x) in ctx.residualVector
    if (contacts) {
      // Branch update at every iterate (a primal-dual active-set strategy): the branches and the
      // elastic solve converge together instead of one Newton solve per active set.
      // The lagged slip friction is re-aimed once the elastic part has converged.
      int changed = 0;
      ctx.timed(ctx.contactSolveModule, [&] {
        changed = contacts->update(ctx.iterate, ctx.fullResidual, velocityTolerance, small);
        if (changed > 0) contacts->projectPositions(ctx.iterate);
      });
      ++ctx.stats.contactSweeps;
      if (changed > 0 || contacts->lastChange() > velocityTolerance) {
        ctx.stats.converged = false;
        energy = energyAt(ctx.iterate);
        previousResidual = 0.0;
        forcing = 0.5;
        continue;
      }
    }
    if (small) {
      // A step whose contacts cycle ends here too; it counts as not converged.
      if (contacts && contacts->blocked() > 0) ctx.stats.converged = false;
      return ctx.stats.converged;
    }
    ctx.prepareDerivatives(false);
    if (contacts)
      ctx.timed(ctx.contactSolveModule, [&] { contacts->prepareFrictionHessian(ctx.iterate); });

    // PCG on K d = r0, preconditioner P^{-1}; z0 = P^{-1} r0 = ctx.change (no extra solve).
    if (contacts) {
      // z0 = Pi P^{-1} Pi r0, one more solve; ctx.change becomes the fallback direction.
      ctx.timed(ctx.solverModule, [&] {
        ctx.change = ctx.residualVector;
        ctx.system.solveInPlace(ctx.change);
        contacts->projectDirection(ctx.change);
      });
      ++ctx.stats.pdIterations;
    }
    ctx.direction.setZero();
    ctx.cgResidual = ctx.residualVector;
    ctx.cgPreconditioned = ctx.change;
    ctx.cgSearch = ctx.change;
    double rz = dot(ctx.cgResidual, ctx.cgPreconditioned);
    const double rz0 = rz;
    // Inexact Newton: the CG tolerance follows the residual's decrease (Eisenstat-Walker choice 2),
    // loose while far from the solution, tight once convergence is quadratic.
    if (previousResidual > 0.0) {
      const double ratio = ctx.stats.residual / previousResidual;
      const double safeguard = 0.9 * forcing * forcing;
      forcing = std::max(0.9 * ratio * ratio, safeguard > 0.1 ? safeguard : 0.0);
      forcing = std::min(0.5, std::max(forcing, 1e-6));
    }
    // No need to reduce the linear residual much below what the tolerance asks of the nonlinear
    // one: the linear model predicts a residual of about forcing * residual after the step.
    forcing = std::min(0.5, std::max(forcing, 0.25 * solver.pdTolerance / ctx.stats.residual));
    previousResidual = ctx.stats.residual;
    while (true) {
      ctx.multiplyNewtonMatrix(ctx.cgSearch, ctx.cgProduct, contacts);
      if (contacts) ctx.timed(ctx.solverModule, [&] { contacts->projectDirection(ctx.cgProduct); });
      double curvature = 0.0, alpha = 0.0;
      ctx.timed(ctx.solverModule, [&] {
        curvature = dot(ctx.cgSearch, ctx.cgProduct);
        if (curvature > 0.0) {
          alpha = rz / curvature;
          ctx.direction += alpha * ctx.cgSearch;
          ctx.cgResidual -= alpha * ctx.cgProduct;
        }
      });
      if (!(curvature > 0.0) || ctx.stats.pdIterations >= solver.pdIterations) break;
      ctx.timed(ctx.solverModule, [&] {
        ctx.cgPreconditioned = ctx.cgResidual;
        ctx.system.solveInPlace(ctx.cgPreconditioned);
        if (contacts) contacts->projectDirection(ctx.cgPreconditioned);
      });
      ++ctx.stats.pdIterations;
      const double rzNew = dot(ctx.cgResidual, ctx.cgPreconditioned);
      if (rzNew <= forcing * forcing * rz0) break;
      ctx.timed(ctx.solverModule,
                [&] { ctx.cgSearch = ctx.cgPreconditioned + (rzNew / rz) * ctx.cgSearch; });
      rz = rzNew;
    }
    if (ctx.direction.isZero(0.0)) ctx.direction = ctx.change;

    // Backtracking line search on g (Armijo); the PD step is the fallback, since it always
    // decreases g. grad g = -r0 / h^2.
    const double slope = -dot(ctx.residualVector, ctx.direction) / h2;
    double step = 1.0;
    bool accepted = false;
    for (int tries = 0; tries < 8 && !accepted; ++tries, step *= 0.5) {
      ctx.accelerated = ctx.iterate + step * ctx.direction;
      const double trial = energyAt(ctx.accelerated);
      if (trial <= energy + 1e-4 * step * slope + 1e-13 * std::abs(energy)) {
        ctx.iterate.swap(ctx.accelerated);
        energy = trial;
        accepted = true;
      }
    }
    if (!accepted) {
      if (contacts) return false;
      ctx.iterate = ctx.global;
      energy = ctx.localStep(ctx.iterate);
    }
  }
  return false;
}

}  // namespace weft
