#include <weft/optim/LbfgsbOptimizer.h>

#include <weft/core/Error.h>

#include <LBFGSpp/BFGSMat.h>
#include <LBFGSpp/Cauchy.h>
#include <LBFGSpp/LineSearchMoreThuente.h>
#include <LBFGSpp/Param.h>
#include <LBFGSpp/SubspaceMin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace weft {
namespace {

// The largest alpha with x + alpha d inside the box.
double stepToTheBox(const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                    const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  double step = std::numeric_limits<double>::infinity();
  for (int i = 0; i < x.size(); ++i) {
    if (d[i] > 0.0)
      step = std::min(step, (upper[i] - x[i]) / d[i]);
    else if (d[i] < 0.0)
      step = std::min(step, (lower[i] - x[i]) / d[i]);
  }
  return step;
}

// The stationarity measure LBFGSpp stops on: |P(x - g) - x|_inf, P the projection onto the box.
double projectedStepNorm(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  return ((x - g).cwiseMax(lower).cwiseMin(upper) - x).cwiseAbs().maxCoeff();
}

}  // namespace

std::string LbfgsbOptimizer::run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper) {
  using Cauchy = LBFGSpp::Cauchy<double>;
  using SubspaceMin = LBFGSpp::SubspaceMin<double>;
  using LineSearch = LBFGSpp::LineSearchMoreThuente<double>;
  LBFGSpp::LBFGSBParam<double> param;
  param.epsilon = settings().gradientTolerance;
  param.epsilon_rel = 0.0;  // absolute test only: optimiser coordinates are already scaled to O(1)
  param.past = 1;
  param.delta = settings().lossTolerance;
  param.max_iterations = settings().maxIterations;
  param.check_param();
  const double firstStep = settings().lbfgsbFirstStep;
  const double minCurvatureStep = settings().lbfgsbMinCurvatureStep;

  auto f = [&](const Eigen::VectorXd& at, Eigen::VectorXd& gradient) {
    return evaluate(at, gradient);
  };
  const int n = static_cast<int>(x.size());
  LBFGSpp::BFGSMat<double, true> bfgs;
  bfgs.reset(n, param.m);
  Eigen::VectorXd g(n), xPrevious(n), gPrevious(n), d(n), xCauchy(n), c, s(n), y(n);
  std::vector<int> newActive, free;
  x = x.cwiseMax(lower).cwiseMin(upper);
  double fx = f(x, g);
  iterations_ = 0;
  if (projectedStepNorm(x, g, lower, upper) <= param.epsilon) {
    iterations_ = 1;  // as LBFGSpp counts a start that is already stationary
    return "converged: projected gradient";
  }
  // The first direction: towards the generalised Cauchy point of the initial (identity) matrix,
  // normalised, so a trial step's length is the step itself.
  Cauchy::get_cauchy_point(bfgs, x, g, lower, upper, xCauchy, c, newActive, free);
  d = xCauchy - x;
  d.normalize();
  try {
    for (int k = 1;; ++k) {
      iterations_ = k;
      xPrevious = x;
      gPrevious = g;
      const double fPrevious = fx;
      const double stepMax = std::min(param.max_step, stepToTheBox(x, d, lower, upper));
      // Later directions come from the quasi-Newton model, whose natural step is 1.
      double step = std::min(k == 1 ? firstStep : 1.0, stepMax);
      LineSearch::LineSearch(f, fx, x, g, step, stepMax, d, xPrevious, param);

      if (projectedStepNorm(x, g, lower, upper) <= param.epsilon)
        return "converged: projected gradient";
      // LBFGSpp's test with past = 1: the loss change over the last iteration, relative.
      if (std::abs(fPrevious - fx) <=
          param.delta * std::max({std::abs(fx), std::abs(fPrevious), 1.0}))
        return "converged: loss change";
      if (param.max_iterations != 0 && k >= param.max_iterations) return "max iterations";

      s = x - xPrevious;
      y = g - gPrevious;
      // The curvature condition s'y > eps |y|^2 keeps the matrix positive definite.
      if (s.dot(y) > std::numeric_limits<double>::epsilon() * y.squaredNorm() &&
          s.norm() >= minCurvatureStep)
        bfgs.add_correction(s, y);

      x = x.cwiseMax(lower).cwiseMin(upper);
      Cauchy::get_cauchy_point(bfgs, x, g, lower, upper, xCauchy, c, newActive, free);
      SubspaceMin::subspace_minimize(bfgs, x, xCauchy, g, lower, upper, c, newActive, free,
                                     param.max_submin, d);
    }
  } catch (const InputError&) {
    throw;
  } catch (const NumericalError&) {
    throw;
  } catch (const std::runtime_error& e) {
    // The line search could not find a sufficient decrease: in practice the loss has reached the
    // noise floor of the forward solver's stopping tolerance, where the exact-step gradient and
    // the loss disagree at the last digits. The best point logged is the answer.
    return std::string("line search: ") + e.what();
  } catch (const std::logic_error& e) {
    return std::string("line search: ") + e.what();
  }
}

}  // namespace weft
