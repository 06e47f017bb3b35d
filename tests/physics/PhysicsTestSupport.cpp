#include "PhysicsTestSupport.h"

#include <weft/physics/ExternalForce.h>
#include <weft/physics/ProjectiveConstraint.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::test {

NodeMatrix energyGradient(const Simulator& sim, const NodeMatrix& x) {
  NodeMatrix grad = NodeMatrix::Zero(x.rows(), 3);
  for (const auto& c : sim.constraints()) {
    NodeMatrix weightedProjections = NodeMatrix::Zero(c->rowCount(), 3);
    c->project(x, weightedProjections);
    const NodeMatrix ax = c->selectionTransposed().transpose() * x;  // A x, rows x 3
    grad += c->selectionTransposed() * (c->weights().asDiagonal() * ax - weightedProjections);
  }
  return grad;
}

double constraintEnergy(const Simulator& sim, const NodeMatrix& x) {
  double energy = 0.0;
  for (const auto& c : sim.constraints()) {
    NodeMatrix weightedProjections = NodeMatrix::Zero(c->rowCount(), 3);
    energy += c->project(x, weightedProjections);
  }
  return energy;
}

NodeMatrix externalForces(const Simulator& sim, double t) {
  NodeMatrix f = NodeMatrix::Zero(sim.cloth().nodeCount(), 3);
  for (const auto& force : sim.forces()) force->accumulate(t, f);
  return f;
}

double massWeightedRms(const NodeMatrix& forces, const Eigen::VectorXd& mass) {
  return std::sqrt(
      (forces.rowwise().squaredNorm().transpose().array() / mass.transpose().array()).sum() /
      mass.sum());
}

NodeMatrix stepResidual(const Simulator& sim, const NodeMatrix& x0, const NodeMatrix& v0,
                        const NodeMatrix& x1, double t1) {
  const double h = sim.dt();
  const NodeMatrix inertia = sim.cloth().mass.asDiagonal() * (x1 - x0 - h * v0) / (h * h);
  return inertia - externalForces(sim, t1) + energyGradient(sim, x1);
}

double maxSpeed(const NodeMatrix& v) {
  return std::sqrt(v.rowwise().squaredNorm().maxCoeff());
}

std::pair<double, double> edgeStretchRange(const TriangleMesh& rest, const NodeMatrix& x) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const MeshEdge& e : buildEdges(rest)) {
    const double r =
        (x.row(e.a) - x.row(e.b)).norm() / (rest.vertices.row(e.a) - rest.vertices.row(e.b)).norm();
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  return {lo, hi};
}

}  // namespace weft::test
