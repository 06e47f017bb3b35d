#include <weft/physics/StepContext.h>

#include <weft/contact/FrictionalContact.h>

#include <cmath>

namespace weft {

StepContext::StepContext(const Model& compiled, const NodeMatrix& start,
                         const std::vector<std::unique_ptr<ProjectiveConstraint>>& constraints,
                         const std::vector<int>& constraintModule, SystemMatrix& system,
                         ModuleTimer& timer, int solverModule, FrictionalContact* contact,
                         int contactSolveModule)
    : settings(compiled.solver()),
      model(compiled.cloth()),
      h(compiled.dt()),
      start(start),
      constraints(constraints),
      constraintModule(constraintModule),
      system(system),
      timer(timer),
      solverModule(solverModule),
      contact(contact),
      contactSolveModule(contactSolveModule) {
  const int m = model.nodeCount();
  inverseMass = model.mass.cwiseInverse();
  massRoot = model.mass.cwiseSqrt();
  totalMass = model.mass.sum();
  for (auto* buf : {&y, &massY, &iterate, &global, &accelerated, &change, &rhs, &residualVector,
                    &direction, &cgResidual, &cgPreconditioned, &cgSearch, &cgProduct})
    buf->setZero(m, 3);
  if (contact)
    for (auto* buf : {&freeMomentum, &plainIterate, &fullResidual}) buf->setZero(m, 3);
  for (const auto& c : constraints) {
    projections.emplace_back(NodeMatrix::Zero(c->rowCount(), 3));
    derivativeRows.emplace_back(NodeMatrix::Zero(c->hasDerivative() ? c->rowCount() : 0, 3));
  }
}

double StepContext::localStep(const NodeMatrix& x, bool energy) {
  // Inertia term of g (DiffCloth Eq. 3): |x - y|^2_M / (2 h^2).
  double total = 0.0;
  if (energy) {
    for (int c = 0; c < 3; ++c) total += model.mass.dot((x.col(c) - y.col(c)).cwiseAbs2());
    total *= 0.5 / (h * h);
  }
  for (std::size_t c = 0; c < constraints.size(); ++c) {
    // A family whose projections are all zero only needs its energy (for the safeguard).
    if (constraints[c]->projectsToZero() && !energy) continue;
    const auto begin = ModuleTimer::Clock::now();
    const double e = constraints[c]->projectsToZero() ? constraints[c]->energy(x)
                                                      : constraints[c]->project(x, projections[c]);
    if (energy) total += e;
    timer.charge(constraintModule[c], ModuleTimer::secondsSince(begin));
  }
  return total;
}

void StepContext::globalStep(ActiveContactSet* contacts) {
  // Global step (DiffCloth Eq. 7): P x = M y + h^2 sum_i w_i A_i^T p_i, with the projections of
  // the last local step.
  timed(solverModule, [&] {
    rhs = massY;
    for (std::size_t c = 0; c < constraints.size(); ++c)
      if (!constraints[c]->projectsToZero()) constraints[c]->gather(projections[c], h * h, rhs);
    if (contacts) contacts->addFriction(iterate, h, rhs);  // slip friction as an impulse
    global = rhs;
    system.solveInPlace(global);
    change = global - iterate;
  });
  ++stats.pdIterations;
}

double StepContext::residualOf(const NodeMatrix& systemTimesChange) const {
  // P (x_global - x_k) = -h^2 grad g(x_k): the imbalance of Eq. 3 at the iterate, as a
  // mass-weighted RMS acceleration (m/s^2).
  const double sum = (systemTimesChange.rowwise().squaredNorm().transpose().array() *
                      inverseMass.transpose().array())
                         .sum();
  return std::sqrt(sum / totalMass) / (h * h);
}

void StepContext::multiplyNewtonMatrix(const NodeMatrix& in, NodeMatrix& out,
                                       ActiveContactSet* contacts) {
  // K = P - Delta P (Sec. 4.1) with Delta P = h^2 sum_i w_i A_i^T D_i A_i, D_i the projection
  // derivative: K = h^2 x (Hessian of g).
  system.multiply(in, out);
  for (std::size_t c = 0; c < constraints.size(); ++c) {
    if (!constraints[c]->hasDerivative()) continue;
    timed(constraintModule[c], [&] {
      constraints[c]->applyDerivative(in, derivativeRows[c]);
      constraints[c]->gather(derivativeRows[c], -h * h, out);
    });
  }
  if (contacts) timed(contactSolveModule, [&] { contacts->addFrictionHessian(in, out); });
}

bool StepContext::checkConvergence(ActiveContactSet* contacts) {
  // P (x_global - x_k): the imbalance of the step's equations at the iterate (residualOf).
  timed(solverModule, [&] {
    system.multiply(change, residualVector);
    if (contacts) {
      // With contact constraints only the imbalance in the free directions must vanish; the rest
      // is the contact impulse (kept whole for the multipliers).
      fullResidual = residualVector;
      contacts->projectDirection(residualVector);
    }
    stats.residual = residualOf(residualVector);
  });
  stats.converged = stats.residual < settings.pdTolerance;
  return stats.converged;
}

void StepContext::prepareDerivatives(bool definite) {
  for (std::size_t c = 0; c < constraints.size(); ++c)
    if (constraints[c]->hasDerivative())
      timed(constraintModule[c], [&] { constraints[c]->prepareDerivative(iterate, definite); });
}

}  // namespace weft
