#pragma once
// What an optimiser minimises: a smooth function of a parameter vector with its gradient, and what
// one evaluation costs in simulated steps. Analytic objectives (the tests' quadratic, Rosenbrock)
// cost nothing; SimulationObjective costs a forward and a backward pass.

#include <Eigen/Core>

namespace weft {

class Objective {
 public:
  virtual ~Objective() = default;
  virtual int dimension() const = 0;
  // The value at x; writes dL/dx into `gradient` (resized by the callee).
  virtual double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) = 0;
  // Simulated steps one evaluation costs (0 for analytic objectives).
  virtual long long stepsPerEvaluation() const { return 0; }
};

}  // namespace weft
