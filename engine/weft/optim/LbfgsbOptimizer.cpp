#include <weft/optim/LbfgsbOptimizer.h>

#include <weft/core/Error.h>

#include <LBFGSB.h>

#include <stdexcept>

namespace weft {

std::string LbfgsbOptimizer::run(Eigen::VectorXd x, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper) {
  LBFGSpp::LBFGSBParam<double> param;
  param.epsilon = settings().gradientTolerance;
  param.epsilon_rel = 0.0;  // absolute test only: optimiser coordinates are already scaled to O(1)
  param.past = 1;
  param.delta = settings().lossTolerance;
  param.max_iterations = settings().maxIterations;
  LBFGSpp::LBFGSBSolver<double> solver(param);

  int calls = 0;
  auto f = [&](const Eigen::VectorXd& at, Eigen::VectorXd& gradient) {
    ++calls;
    return evaluate(at, gradient);
  };
  double fx = 0.0;
  try {
    iterations_ = solver.minimize(f, x, fx, lower, upper);
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
  const LogEntry& last = log().entries().back();
  if (projectedGradientNorm(last.x, last.gradient, lower, upper) <= param.epsilon)
    return "converged: projected gradient";
  if (param.max_iterations > 0 && iterations_ >= param.max_iterations) return "max iterations";
  return "converged: loss change";
}

}  // namespace weft
