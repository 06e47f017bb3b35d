#include <weft/diff/GmresSolver.h>

#include <weft/diff/AdjointSystem.h>

#include <algorithm>
#include <cmath>

namespace weft {

const char* GmresSolver::name() const {
  switch (preconditioner_) {
    case Preconditioner::P:
      return "gmres";
    case Preconditioner::ClampedHessian:
      return "gmres (hessian)";
    case Preconditioner::Automatic:
      return switched_ ? "gmres (auto: hessian)" : "gmres (auto: p)";
  }
  return "gmres";
}

LinearSolveResult GmresSolver::solve(AdjointSystem& system, const NodeMatrix& rhs, NodeMatrix& z) {
  const int factorizationsBefore = factorizations_;
  stepHessianIterations_ = 0;
  if (history_.capacity() > 0) history_.guess(rhs, z);
  LinearSolveResult r = solveFrom(system, rhs, z);
  if (history_.capacity() > 0)
    history_.add(z, rhs - gmres_.residual());  // K z, from the residual the solve ended with
  r.hessianIterations = stepHessianIterations_;
  r.factorizations = factorizations_ - factorizationsBefore;
  return r;
}

LinearSolveResult GmresSolver::solveFrom(AdjointSystem& system, const NodeMatrix& rhs,
                                         NodeMatrix& z) {
  auto multiplyK = [&](const NodeMatrix& in, NodeMatrix& out) { system.multiplyK(in, out); };
  bool hessian = false;
  auto precondition = [&](const NodeMatrix& in, NodeMatrix& out) {
    out = in;
    system.precondition(out, hessian);
  };
  if (preconditioner_ != Preconditioner::Automatic || !system.hasDeltaP()) {
    // Without Delta P the clamped Hessian is P itself.
    hessian = preconditioner_ == Preconditioner::ClampedHessian && system.hasDeltaP() &&
              system.factorClampedHessian();
    factorizations_ += hessian;
    const GmresResult r = gmres_.solve(multiplyK, precondition, rhs, z, tolerance_, maxIterations_,
                                       restart_, warmStart_, minIterations());
    if (hessian) stepHessianIterations_ = r.iterations;
    return {r.converged, false, r.iterations, r.residual};
  }
  // Automatic (see the header): start with the Hessian after a step it served well, except every
  // kAutomaticReprobe-th such step, which probes P first. Its factor is kept across steps until a
  // solve with it needs more than kAutomaticRefactor iterations.
  GmresResult r;
  if (switched_ && hessianRun_ < kAutomaticReprobe) {
    const bool fresh = !factorValid_ || lastIterations_ > kAutomaticRefactor;
    if (fresh) {
      factorizations_ += (factorValid_ = system.factorClampedHessian());
      if (factorValid_) runCost_ += system.hessianFactorCost();
    }
    if (factorValid_) {
      hessian = true;
      ++hessianRun_;
      ++hessianSteps_;
      r = gmres_.solve(multiplyK, precondition, rhs, z, tolerance_, maxIterations_, restart_,
                       warmStart_, minIterations());
      lastIterations_ = r.iterations;
      runCost_ += system.hessianIterationCost() * r.iterations;
      ++runSteps_;
      stepHessianIterations_ = r.iterations;
      // A fresh factor that needs many iterations does not model this K (contacts, Delta R).
      switched_ = !fresh || r.iterations <= kAutomaticPIterations;
      return {r.converged, false, r.iterations, r.residual};
    }
  }
  // A step after a run of Hessian steps checks whether P has become the cheaper: it gives P as
  // many iterations as the run's steps cost on average (factorisations and iterations with H, in
  // iterations with P). Any other step gives P as many iterations as a factorisation costs,
  // shared among the steps a factor serves (counted in this pass, starting from a prior of
  // kAutomaticPriorReuse), before buying one: the ski-rental rule, never far from the better
  // choice made in hindsight.
  const bool reprobe = switched_;
  const double stepsPerFactor =
      double(hessianSteps_ + kAutomaticPriorReuse) / double(factorizations_ + 1);
  const double budget =
      reprobe ? runCost_ / std::max(1, runSteps_) : system.hessianFactorCost() / stepsPerFactor;
  const int pBudget =
      std::max(kAutomaticPIterations, static_cast<int>(std::lround(std::min(budget, 1e6))));
  hessianRun_ = 0;
  r = gmres_.solve(multiplyK, precondition, rhs, z, tolerance_, std::min(maxIterations_, pBudget),
                   restart_, warmStart_, minIterations());
  switched_ = false;
  if (!r.converged && r.iterations < maxIterations_ &&
      (factorValid_ = system.factorClampedHessian())) {
    // P is slow here: continue from the z it reached, preconditioned by the Hessian. A new run of
    // Hessian steps starts, its cost counted from this factorisation.
    ++factorizations_;
    ++hessianSteps_;
    hessian = true;
    const int spent = r.iterations;
    r = gmres_.solve(multiplyK, precondition, rhs, z, tolerance_, maxIterations_ - spent, restart_,
                     /*warmStart=*/true, std::max(0, minIterations() - spent));
    switched_ = r.converged && r.iterations <= kAutomaticPIterations;
    lastIterations_ = r.iterations;
    runCost_ = system.hessianFactorCost() + system.hessianIterationCost() * r.iterations;
    runSteps_ = 1;
    stepHessianIterations_ = r.iterations;
    r.iterations += spent;
  }
  return {r.converged, false, r.iterations, r.residual};
}

}  // namespace weft
