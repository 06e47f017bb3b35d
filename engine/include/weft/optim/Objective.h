#pragma once
// What an optimiser minimises: a function of a parameter vector, evaluated either with its
// gradient (evaluate) or alone (value), and what each kind of evaluation costs in simulated
// steps. DiffCloth's tables count a forward step as 1 and a backward step as 1 more, so for a
// simulation a gradient evaluation costs twice its step count and a value-only evaluation (what
// the gradient-free methods, CMA-ES and the (1+1)-ES, ask for) once. Analytic objectives (the
// tests' quadratic, Rosenbrock) cost nothing unless they say otherwise.

#include <Eigen/Core>

#include <vector>

namespace weft {

class Objective {
 public:
  virtual ~Objective() = default;
  virtual int dimension() const = 0;
  // The value at x; writes dL/dx into `gradient` (resized by the callee).
  virtual double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) = 0;
  // The value at x alone. The default computes the gradient and drops it (so it costs what an
  // evaluation costs, see stepsPerValue); objectives whose value is cheaper on its own override
  // both.
  virtual double value(const Eigen::VectorXd& x) {
    Eigen::VectorXd unused;
    return evaluate(x, unused);
  }
  // The values at several points, appended to `losses` in order: what a population of an
  // evolution strategy asks for at once. Throws what value() throws, with the values before the
  // failing point appended. The default evaluates one after another; an objective spread over
  // processes (OptimizationRun with WorkDistributor) evaluates them at once.
  virtual void values(const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses) {
    for (const Eigen::VectorXd& x : points) losses.push_back(value(x));
  }
  // How many points values() evaluates at once (1: one after another), so that a method can ask
  // for that many at a time.
  virtual int concurrency() const { return 1; }
  // The estimated relative error of the gradient the last evaluate() wrote (0 for analytic
  // objectives, whose gradients are exact to round-off).
  virtual double lastGradientError() const { return 0.0; }
  // Simulated steps one evaluate() costs (0 for analytic objectives).
  virtual long long stepsPerEvaluation() const { return 0; }
  // Simulated steps one value() costs: by default that of evaluate(), which the default value()
  // calls.
  virtual long long stepsPerValue() const { return stepsPerEvaluation(); }
};

}  // namespace weft
