#pragma once
// Analytic objectives for the optimiser tests: an anisotropic quadratic bowl and Rosenbrock's
// valley, with nominal costs in "simulated steps" so that the budget can be exercised (a value
// alone costs half a gradient evaluation, as for a simulation), and a wrapper counting which kind
// of evaluation a method asked for.

#include <weft/optim/Objective.h>

#include <Eigen/Core>

#include <limits>

namespace weft::test {

// 0.5 (x - c)^T diag(w) (x - c): an anisotropic bowl centred at c.
class Quadratic : public Objective {
 public:
  Quadratic(Eigen::VectorXd centre, Eigen::VectorXd weights)
      : c_(std::move(centre)), w_(std::move(weights)) {}
  int dimension() const override { return static_cast<int>(c_.size()); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    g = w_.cwiseProduct(x - c_);
    return 0.5 * (x - c_).dot(g);
  }
  double value(const Eigen::VectorXd& x) override {
    return 0.5 * (x - c_).dot(w_.cwiseProduct(x - c_));
  }
  long long stepsPerEvaluation() const override { return 10; }  // to exercise the budget
  long long stepsPerValue() const override { return 5; }

 private:
  Eigen::VectorXd c_, w_;
};

// (1 - x)^2 + 100 (y - x^2)^2, minimum 0 at (1, 1).
class Rosenbrock : public Objective {
 public:
  int dimension() const override { return 2; }
  double evaluate(const Eigen::VectorXd& p, Eigen::VectorXd& g) override {
    const double x = p[0], y = p[1];
    g.resize(2);
    g[0] = -2.0 * (1.0 - x) - 400.0 * x * (y - x * x);
    g[1] = 200.0 * (y - x * x);
    return (1.0 - x) * (1.0 - x) + 100.0 * (y - x * x) * (y - x * x);
  }
};

// Forwards to `inner`, counting gradient evaluations and value-only ones.
class CountingObjective : public Objective {
 public:
  explicit CountingObjective(Objective& inner) : inner_(inner) {}
  int dimension() const override { return inner_.dimension(); }
  double evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& g) override {
    ++gradients;
    return inner_.evaluate(x, g);
  }
  double value(const Eigen::VectorXd& x) override {
    ++values;
    return inner_.value(x);
  }
  long long stepsPerEvaluation() const override { return inner_.stepsPerEvaluation(); }
  long long stepsPerValue() const override { return inner_.stepsPerValue(); }
  int gradients = 0, values = 0;

 private:
  Objective& inner_;
};

inline const double kInf = std::numeric_limits<double>::infinity();

}  // namespace weft::test
