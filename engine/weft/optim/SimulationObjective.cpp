#include <weft/optim/SimulationObjective.h>

#include <weft/diff/ForwardPass.h>

#include <algorithm>
#include <chrono>

namespace weft {

SimulationObjective::SimulationObjective(const Scene& scene, const ParameterSet& parameters)
    : scene_(scene),
      parameters_(parameters),
      space_(scene, parameters),
      loss_(scene),
      backwardPass_(scene.solver.backward) {}

namespace {
double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

double SimulationObjective::evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& gradient) {
  const auto start = std::chrono::steady_clock::now();
  const ForwardPass forward =
      runForwardPass(parameters_.compile(scene_, space_.toValues(z)), progress_);
  unconverged_ += forward.unconvergedSteps;
  const double forwardSeconds = secondsSince(start);
  forwardSeconds_ += forwardSeconds;
  ++forwardPasses_;
  const GradientResult r =
      backwardPass_.differentiate(forward.trajectory, loss_, parameters_, progress_);
  lastError_ = r.error;
  largestError_ = std::max(largestError_, r.error.relative);
  if (!r.error.met) ++missingAccuracy_;
  gradient = space_.gradientToCoordinates(z, r.gradient);
  addSolverCosts(backward_, r.solver);
  const double seconds = secondsSince(start);
  backwardSeconds_ += seconds - forwardSeconds;
  backwardPasses_ += r.error.passes;
  seconds_ += seconds;
  return r.loss;
}

double SimulationObjective::value(const Eigen::VectorXd& z) {
  // The forward pass and the loss of its trajectory, nothing recorded for a backward pass to use:
  // what a gradient-free method pays per evaluation (time.steps simulated steps).
  const auto start = std::chrono::steady_clock::now();
  const ForwardPass forward =
      runForwardPass(parameters_.compile(scene_, space_.toValues(z)), progress_);
  unconverged_ += forward.unconvergedSteps;
  const double loss = loss_.value(forward.trajectory.model->scene(), forward.trajectory);
  const double seconds = secondsSince(start);
  forwardSeconds_ += seconds;
  ++forwardPasses_;
  seconds_ += seconds;
  return loss;
}

void SimulationObjective::countValueRunElsewhere(int unconvergedSteps, double seconds) {
  unconverged_ += unconvergedSteps;
  forwardSeconds_ += seconds;
  seconds_ += seconds;
  ++forwardPasses_;
}

}  // namespace weft
