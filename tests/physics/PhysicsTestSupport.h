#pragma once
// Physics quantities computed independently of the solver loop, from the public pieces of the
// Simulator (constraints, forces, masses), to check what the solver claims.

#include <weft/physics/Simulator.h>

namespace weft::test {

// grad W(x) = sum over constraint families of A^T W (A x - p(x)) (DiffCloth Eq. 4-5): the
// negated internal force. Attachment targets are those of the simulator's current step.
NodeMatrix energyGradient(const Simulator& sim, const NodeMatrix& x);

// Total energy W(x) of the constraint families, as their projections report it.
double constraintEnergy(const Simulator& sim, const NodeMatrix& x);

// Sum of the external forces (gravity, wind, nodal forces) at time t.
NodeMatrix externalForces(const Simulator& sim, double t);

// Mass-weighted RMS of a nodal force field as an acceleration (m/s^2):
// sqrt(sum_i |r_i|^2 / m_i / sum_i m_i), the measure the solver's pd_tolerance uses.
double massWeightedRms(const NodeMatrix& forces, const Eigen::VectorXd& mass);

// Residual of the implicit-Euler step n -> n+1 (DiffCloth Eq. 3 gradient):
// M (x1 - x0 - h v0) / h^2 - f_ext(t1) + grad W(x1). Uses the simulator's constraints, whose
// attachment targets must be those of the step (i.e. call right after that step).
NodeMatrix stepResidual(const Simulator& sim, const NodeMatrix& x0, const NodeMatrix& v0,
                        const NodeMatrix& x1, double t1);

double maxSpeed(const NodeMatrix& v);

// Smallest and largest ratio of current to rest length over all mesh edges.
std::pair<double, double> edgeStretchRange(const TriangleMesh& rest, const NodeMatrix& x);

}  // namespace weft::test
