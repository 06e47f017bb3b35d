#include <weft/physics/ContactNewtonSolve.h>

#include <weft/contact/FrictionalContact.h>
#include <weft/physics/NewtonPcgSolve.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>

namespace weft {
namespace {

// The Newton contact solve (ContactNewtonSolve::solveNewton).
// K+ is refactorised when a GMRES solve needed more than this many iterations (the iterate and
// the branches moved far from where it was factorised).
constexpr int kRefactorIterations = 20;
// GMRES iterations a step's first linear solve may take with P before K+ is factorised.
constexpr int kPIterations = 5;
// Where one factorisation of K+ costs more than this many iterations with P (keepStiffnessFactor_),
// a step starts from the previous step's factor of K+ instead of P.
constexpr double kKeepFactorAbovePIterations = 30.0;
// Seconds per flop of CHOLMOD's supernodal factorisation of K+ over those of an iteration with P,
// measured (docs/how-it-works/contact.md, "Measured on the way").
constexpr double kFactorTimePerFlopRatio = 0.7;
constexpr int kGmresRestart = 100;
// Backtracking stops below this step length; then a full Newton step is still taken if its
// residual stays below kRelaxedGrowth times the best one so far (a non-monotone step, at most
// kRelaxedSteps in a row: after a branch switch the next linearisation corrects the full step,
// while the backtracking would creep along the old branch). The step's result is the best
// iterate visited.
constexpr double kMinStep = 1e-3;
constexpr double kRelaxedGrowth = 100.0;
constexpr int kRelaxedSteps = 3;
// An attempt adaptive time stepping would split (StepContext::splittable) gives up after this
// many Newton iterations in a row that kept every branch and lowered a residual still more than
// kCreepingAbove times the tolerance by less than a tenth each: the line search is creeping along
// a kink of G (a collapsing element, a node at a branch boundary), where the rest of the budget
// rarely converges and the halves do (the T-shirt's layers: 20 iterations at 0.1-1 % each). A
// tenth, not a half: damped steps that gain 12-30 % each are on their way to a branch switch
// (Slope's landing step converges two iterations after them). (Near the tolerance the creep is
// rounding, which halves do not cure and the PD continuation does.)
constexpr int kCreepingIterations = 2;
constexpr double kCreepingRatio = 0.9;
constexpr double kCreepingAbove = 100.0;
// Diagnostics: WEFT_CONTACT_TRACE=a-b (or =a) prints each Newton contact iteration of steps a..b
// to stderr (residual, GMRES iterations, step length, branch changes).
// Read once, by a static initialiser, which is thread-safe: simulators may run on several
// threads at once (`weft bench applications --jobs`, the editor's workers).
bool traceContactStep(int step) {
  static const std::pair<int, int> range = [] {
    int first = 0, last = -1;
    if (const char* e = std::getenv("WEFT_CONTACT_TRACE"))
      if (std::sscanf(e, "%d-%d", &first, &last) == 1) last = first;
    return std::pair<int, int>(first, last);
  }();
  return step >= range.first && step <= range.second;
}

}  // namespace

ContactNewtonSolve::ContactNewtonSolve(const StepContext& ctx) : pd_(ctx) {
  const int m = ctx.model.nodeCount();
  // The law mass m~ (solveNewton): the geometric mean of the lumped mass and P's diagonal.
  lawMass_ = (ctx.model.mass.array() * ctx.system.matrix().diagonal().array()).sqrt().matrix();
  lawInput_.setZero(m, 3);
  pinnedPart_.setZero(m, 3);
  // From operation counts, not timings, so that runs repeat exactly.
  keepStiffnessFactor_ =
      kFactorTimePerFlopRatio * ctx.system.factor().blockFactorFlopRatio(
                                    static_cast<double>(ctx.system.matrix().nonZeros())) >
      kKeepFactorAbovePIterations;
}

void ContactNewtonSolve::prepareContacts(StepContext& ctx) {
  ctx.contact->prepareSolve(&lawMass_);
}

void ContactNewtonSolve::solve(StepContext& ctx) {
  // A step without contacts, with solver.method "newton": Newton-PCG with its line search on g
  // (see PdContactSolve::solve).
  if (ctx.contact->perNodeSolver().empty() && ctx.settings.method == SolverMethod::Newton) {
    NewtonPcgSolve::iterate(ctx, nullptr);
    return;
  }
  solveNewton(ctx);
  // A stalled attempt that adaptive time stepping will split is given up: the halves converge
  // for less than the PD iteration's continuation costs.
  if (!ctx.stats.converged && !ctx.splittable && std::isfinite(ctx.stats.residual) &&
      ctx.stats.pdIterations < ctx.solveLimit)
    finishWithPerNodeIterations(ctx);
}

void ContactNewtonSolve::solveNewton(StepContext& ctx) {
  // Semismooth Newton on G(x) = P x - b(x) - h r(f(x)) = 0, the fixed point of the "pd" contact
  // iteration x <- P^-1 (b(x) + h r(f(x))) (DiffCloth Eqs. 10-12): the same per-node law (Eq. 8),
  // so the same solution, and the same convergence test (the mass-weighted RMS of G,
  // residualOf). Two choices differ from the PD iteration, neither changes the solution:
  //  - The law is solved with the mass m~_i = sqrt(m_i P_ii) instead of the lumped m_i
  //    (ContactSolver::setContacts; the augmentation parameter of Alart and Curnier's
  //    formulation). The law decides a contact's branch from its free velocity
  //    w = v + (b - P x) / (h m~): with m~ = m the elastic imbalance of an unconverged iterate is
  //    amplified by P_ii / m_i and the branches of rim nodes flip from one iterate to the next;
  //    with m~ = P_ii the decisions follow the iterate's velocity, which lags when a resting
  //    cloth starts to slide. The geometric mean converges where each of them fails
  //    (docs/how-it-works/contact.md, "Measured on the way").
  //  - Its Jacobian, with K = P - Delta P (Sec. 4.1) and R' = dr/df from each contact's branch
  //    (ContactLawJacobian.h), J = K + R' (K - M~) (the transpose of the backward pass's
  //    operator, Eq. 29, with M~ for M), is not symmetric, so J d = -G is solved by GMRES (on
  //    M^-1/2 J d = -M^-1/2 G, so that it minimises the convergence test's norm), right-
  //    preconditioned by preconditionContact. P is a poor preconditioner here: P^-1 K has one
  //    small eigenvalue per node, between m/P_ii and a few hundredths: the out-of-plane modes
  //    PD's quadratic stretch energy makes as stiff as in-plane stretching, and GMRES needs
  //    tens of iterations per decade of residual (docs/how-it-works/contact.md). A factor of the
  //    clamped Hessian K+ brings that to a few. Each step starts with P (where contacts pin the
  //    normal motion, as on Slope, it needs 1-4 iterations); once a solve takes more than
  //    kPIterations, K+ is factorised at the current iterate, the solve continues from where it
  //    was, and K+ is refactorised whenever a later solve needs more than kRefactorIterations.
  // The step is damped by backtracking on the residual norm; where that fails (the direction
  // crosses a branch switch), a full step is still taken if it does not raise the residual more
  // than kRelaxedGrowth-fold over the best (non-monotone), and the step's result is the best
  // iterate visited.
  ContactSolver& contacts = ctx.contact->perNodeSolver();
  const SolverSettings& solver = ctx.settings;
  const bool trace = traceContactStep(ctx.stats.step);
  NodeMatrix& residual = ctx.cgResidual;  // G at ctx.iterate
  NodeMatrix& trialResidual = ctx.cgProduct;
  NodeMatrix& step = ctx.direction;
  NodeMatrix& rhs = ctx.cgSearch;
  NodeMatrix& best = ctx.plainIterate;
  const Eigen::VectorXd& lawMass = lawMass_;
  auto applyJacobian = [&](const NodeMatrix& in, NodeMatrix& out) {
    ctx.multiplyNewtonMatrix(in, out);
    ctx.timed(ctx.contactSolveModule, [&] {
      lawInput_ = out - lawMass.asDiagonal() * in;
      contacts.addLawJacobian(lawInput_, out);
      out = ctx.massRoot.cwiseInverse().asDiagonal() * out;
    });
  };
  auto precondition = [&](const NodeMatrix& scaled, NodeMatrix& z) {
    applyPreconditioner(ctx, scaled, z);
  };

  double measure = PdContactSolve::residual(ctx, ctx.iterate, residual, lawMass_);
  bool atIterate = true;  // ctx.rhs and the contact impulses belong to ctx.iterate
  double bestMeasure = measure;
  best = ctx.iterate;
  // Where a factorisation of K+ costs more than kKeepFactorAbovePIterations iterations with P
  // (about 24x24 quads and up), the factor of an earlier step is kept as the preconditioner
  // (refactorised when a solve with it is slow, as within a step).
  bool factored = stiffnessFactored_ && keepStiffnessFactor_;
  stiffnessFactored_ = factored;  // (applyPreconditioner uses P until K+ is factorised)
  double forcing = 0.1, previous = 0.0;
  int lastIterations = 0, relaxed = 0, iteration = 0, creeping = 0;
  bool clamped = false;  // the Jacobian's K: exact (P - Delta P) until a line search fails, then K+
  // K+ at the iterate, leaving the derivatives J's K uses prepared (the clamped ones already are).
  auto refactorStiffness = [&] {
    ctx.prepareDerivatives(true);
    factorizeStiffness(ctx);
    if (!clamped) ctx.prepareDerivatives(false);
  };
  if (trace)
    std::fprintf(stderr, "step %d: newton contact solve, residual %.3e\n", ctx.stats.step, measure);
  while (true) {
    ctx.stats.residual = measure;
    ctx.stats.converged = measure < solver.pdTolerance;
    if (ctx.stats.converged || !std::isfinite(measure) || ctx.stats.pdIterations >= ctx.solveLimit)
      break;
    if (factored && lastIterations > kRefactorIterations)
      refactorStiffness();
    else
      ctx.prepareDerivatives(clamped);
    int changed = 0;
    ctx.timed(ctx.contactSolveModule, [&] { changed = contacts.linearize(); });
    // Inexact Newton: the linear tolerance follows the residual's decrease (Eisenstat-Walker 2).
    if (previous > 0.0) {
      const double ratio = measure / previous;
      forcing =
          std::min(0.1, std::max({0.9 * ratio * ratio, 1e-6, 0.25 * solver.pdTolerance / measure}));
    }
    previous = measure;
    ctx.timed(ctx.solverModule,
              [&] { rhs = -(ctx.massRoot.cwiseInverse().asDiagonal() * residual); });
    // Each step starts with P as the preconditioner (enough where contacts pin the cloth's
    // normal motion, as on Slope); K+ is factorised once a solve with P is slow.
    const int budget = std::max(1, ctx.solveLimit - ctx.stats.pdIterations);
    GmresResult linear =
        gmres_.solve(applyJacobian, precondition, rhs, step, forcing,
                     factored ? budget : std::min(budget, kPIterations), kGmresRestart);
    if (!factored && !linear.converged && ctx.stats.pdIterations < ctx.solveLimit) {
      factored = true;
      refactorStiffness();
      const int spent = linear.iterations;
      linear =
          gmres_.solve(applyJacobian, precondition, rhs, step, forcing,
                       std::max(1, ctx.solveLimit - ctx.stats.pdIterations), kGmresRestart, true);
      linear.iterations += spent;
    }
    lastIterations = linear.iterations;
    // A non-finite direction (a singular block in J) is a failed one; trying it would leave
    // non-finite impulses in the contact solver, which warm-starts from them.
    const bool finite = step.allFinite();
    bool accepted = false;
    double trial = measure, alpha = 1.0;
    for (; finite && alpha > kMinStep && !accepted; alpha *= 0.5) {
      ctx.timed(ctx.solverModule, [&] { ctx.accelerated = ctx.iterate + alpha * step; });
      trial = PdContactSolve::residual(ctx, ctx.accelerated, trialResidual, lawMass_);
      accepted = trial <= (1.0 - 1e-4 * alpha) * measure;
    }
    if (accepted) {
      alpha *= 2.0;  // (the loop halved it once more)
      relaxed = 0;
    } else if (finite && relaxed < kRelaxedSteps) {
      alpha = 1.0;
      ctx.timed(ctx.solverModule, [&] { ctx.accelerated = ctx.iterate + step; });
      trial = PdContactSolve::residual(ctx, ctx.accelerated, trialResidual, lawMass_);
      accepted = std::isfinite(trial) && trial < kRelaxedGrowth * bestMeasure;
      relaxed += accepted;
    }
    ++iteration;
    if (trace)
      std::fprintf(stderr,
                   "  %2d: %2d branch changes, gmres %3d (%.1e), step %.3f%s, residual %.3e -> "
                   "%.3e, %d solves\n",
                   iteration, changed, linear.iterations, linear.residual, accepted ? alpha : 0.0,
                   relaxed > 0 && accepted ? " (non-monotone)" : "", measure, trial,
                   ctx.stats.pdIterations);
    atIterate = accepted;
    // A failed line search with the exact K: the direction was nearly singular, not wrong (on the
    // crumpling corner the directional finite differences of G matched J d to O(alpha), while
    // single nodes were sent 0.4 m and G was already 28-fold off its linearisation at alpha =
    // 1e-3). K = P - Delta P is indefinite where the cloth is compressed and buckles; the rest of
    // the step uses the clamped K+ (the preconditioner's matrix) in J, which keeps the elastic
    // part of every direction a descent one, at linear convergence. Exact K is tried first
    // because it converges quadratically where it is definite.
    if (!accepted && !clamped) {
      clamped = true;
      measure = PdContactSolve::residual(ctx, ctx.iterate, residual, lawMass_);
      atIterate = true;
      continue;
    }
    if (!accepted) break;  // stalled: the best iterate is the result
    creeping = changed == 0 && trial > kCreepingRatio * measure &&
                       trial > kCreepingAbove * solver.pdTolerance
                   ? creeping + 1
                   : 0;
    ctx.iterate.swap(ctx.accelerated);
    residual.swap(trialResidual);
    measure = trial;
    if (measure < bestMeasure) {
      bestMeasure = measure;
      best = ctx.iterate;
    }
    if (ctx.splittable && creeping >= kCreepingIterations) break;
  }
  if (!(measure <= bestMeasure)) {
    ctx.iterate = best;
    atIterate = false;
  }
  if (!atIterate) measure = PdContactSolve::residual(ctx, ctx.iterate, residual, lawMass_);
  if (trace) traceResidualNodes(ctx, residual);
  ctx.stats.residual = measure;
  ctx.stats.converged = measure < solver.pdTolerance;
  // The step's result is the checked iterate itself (its contacts are the recorded ones). One PD
  // global solve past it, as the PD iteration ends, would not be a contraction with the law mass
  // m~: for a stuck node it maps a displacement error d to (I - P^-1 M~) d, which grows smooth
  // errors by up to P_ii / m_i.
  ctx.timed(ctx.solverModule, [&] { ctx.global = ctx.iterate; });
}

void ContactNewtonSolve::finishWithPerNodeIterations(StepContext& ctx) {
  // The semismooth Newton solve stalled (its line search on the residual norm found no
  // decrease): the PD contact iteration continues from its result with the rest of the budget.
  // Where Newton stalls the residual can sit on a few nodes away from any contact, where a
  // stretch or bending projection's derivative is discontinuous (a collapsed or flipped element)
  // and the residual norm is not smooth; the PD iteration needs no derivative there. It runs with
  // the lumped mass in the law (the PD iteration is not a contraction with Newton's m~, see
  // solveNewton's end), which does not change the solution, and the free momentum it
  // hands the law is then the lumped mass's too: built with m~, the law saw the velocity
  // (m~ / m) v (about 55 v on the Sock), which leaves a stick or slip decision unchanged but
  // closes a gap at m / m~ of its rate, so the continuation converged to other equations. The
  // better of the two results is the step's.
  newtonResult_ = ctx.iterate;
  const double newtonResidual = ctx.stats.residual;
  ctx.timed(ctx.contactSolveModule, [&] { ctx.contact->prepareSolve(nullptr); });
  pd_.iterate(ctx);
  const bool better = ctx.stats.converged || ctx.stats.residual < newtonResidual;
  // Kept, the PD iteration's result comes with its contact state, the impulses and branches its
  // last global solve used: that is what the step records (contact_forces.npy, the backward
  // pass). Resetting the solver to the law mass here had cleared them (setContacts starts every
  // contact at take-off with no impulse): 7 of the Sock's 400 steps, pressed on the foot, were
  // recorded free of contact.
  if (!better) {
    // Back to Newton's iterate, with the contact impulses (to be recorded) evaluated there.
    ctx.timed(ctx.contactSolveModule, [&] { ctx.contact->prepareSolve(&lawMass_); });
    ctx.iterate = newtonResult_;
    ctx.stats.residual = PdContactSolve::residual(ctx, ctx.iterate, ctx.fullResidual, lawMass_);
    ctx.stats.converged = ctx.stats.residual < ctx.settings.pdTolerance;
    ctx.timed(ctx.solverModule, [&] { ctx.global = ctx.iterate; });
  }
  // (Otherwise the PD iteration's last global solution is the step's result, as on its own.)
}

bool ContactNewtonSolve::factorizeStiffness(StepContext& ctx) {
  // K+ = P - Delta P+ at ctx.iterate (the derivatives must have been prepared `definite`),
  // assembled from the constraints' element blocks and factorised by CHOLMOD (symbolic analysis
  // kept). (The active-set solve's friction Hessian is not part of it: that solve never gets here.)
  bool ok = false;
  ctx.timed(ctx.solverModule, [&] {
    if (!stiffnessAssembly_) {
      stiffnessAssembly_ = std::make_unique<HessianAssembly>(ctx.system.matrix());
      stiffnessCholesky_.orderByNodes(ctx.system.matrix());
    }
    stiffnessAssembly_->assemble(ctx.constraints, -ctx.h * ctx.h, stiffness_);
    ok = stiffnessCholesky_.factorize(stiffness_);
  });
  stiffnessFactored_ = ok;
  return ok;
}

void ContactNewtonSolve::applyPreconditioner(StepContext& ctx, const NodeMatrix& scaled,
                                             NodeMatrix& z) {
  // Right preconditioner B of the Newton contact solve. The velocities the branches prescribe
  // (stick: all of u, slip: u_N) have rows m~ in J, so B inverts them exactly per node; the rest
  // is solved with K+ (or P when K+ could not be factorised) restricted to the free directions.
  ContactSolver& contacts = ctx.contact->perNodeSolver();
  const int m = ctx.model.nodeCount();
  ctx.timed(ctx.solverModule, [&] {
    z.resize(m, 3);
    lawInput_ = ctx.massRoot.asDiagonal() * scaled;  // (a free buffer here)
    const NodeMatrix& r = lawInput_;
    pinnedPart_.setZero(m, 3);
    contacts.pinnedVelocity(r, pinnedPart_);
    if (!stiffnessFactored_) {
      ctx.system.multiply(pinnedPart_, z);
      z = r - z;
      contacts.removePinned(z);
      ctx.system.solveInPlace(z);
    } else {
      // A NodeMatrix's storage is the flat vector K+ acts on (HessianAssembly's index).
      const Eigen::Index n = 3 * static_cast<Eigen::Index>(m);
      coupling_.resize(m, 3);
      Eigen::Map<Eigen::VectorXd>(coupling_.data(), n).noalias() =
          stiffness_ * Eigen::Map<const Eigen::VectorXd>(pinnedPart_.data(), n);
      z = r - coupling_;
      contacts.removePinned(z);
      stiffnessCholesky_.solveInPlace(z.data(), 1);
    }
    contacts.removePinned(z);
    z += pinnedPart_;
  });
  ++ctx.stats.pdIterations;
}

void ContactNewtonSolve::traceResidualNodes(const StepContext& ctx,
                                            const NodeMatrix& residual) const {
  // Where the step's residual sits (WEFT_CONTACT_TRACE): the nodes holding the largest shares of
  // the squared, mass-weighted residual (residualOf), with their positions and contact branches.
  // On the Sock, a stalled step's residual sat on the four nodes of one bending hinge
  // (scripts/trace-stall-hinges.py names the hinge).
  constexpr int kShown = 8;
  const Eigen::VectorXd weighted = residual.rowwise().squaredNorm().cwiseProduct(ctx.inverseMass);
  const Eigen::VectorXd share = weighted / std::max(1e-300, weighted.sum());
  std::vector<int> order(static_cast<std::size_t>(share.size()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  const auto shown = order.begin() + std::min<std::ptrdiff_t>(kShown, share.size());
  std::partial_sort(order.begin(), shown, order.end(),
                    [&](int a, int b) { return share[a] > share[b]; });
  for (auto it = order.begin(); it != shown; ++it)
    std::fprintf(stderr, "  residual at node %d: share %.3f, x (%.4f, %.4f, %.4f), contact %s\n",
                 *it, share[*it], ctx.iterate(*it, 0), ctx.iterate(*it, 1), ctx.iterate(*it, 2),
                 branchName(ctx.contact->perNodeSolver().branchOfNode(*it)));
}

void ContactNewtonSolve::record(const StepContext& ctx, StepContacts& out) const {
  ctx.contact->record(out);
}

}  // namespace weft
