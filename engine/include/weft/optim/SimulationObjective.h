#pragma once
// The scene's task loss as a function of its parameters, in ParameterSpace coordinates: each
// evaluation sets the parameters into the scene (through the strict loader), runs the forward
// pass and backpropagates the loss (DiffCloth Sec. 4.1, Eqs. 16-19); value() runs the forward
// pass alone. Cost, as the paper's tables count it: each forward step is one simulated step and
// each backward step one more, so one gradient evaluation costs 2 * time.steps and one
// value-only evaluation time.steps. Each gradient is made to meet solver.backward.accuracy
// (AccurateBackward: usually two backward passes); backwardPasses() counts them all, the step
// cost above one per gradient, as DiffCloth's tables count its single pass.

#include <weft/diff/AdjointSolver.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/TaskLoss.h>
#include <weft/optim/Objective.h>
#include <weft/optim/ParameterSpace.h>
#include <weft/record/StepProgress.h>

namespace weft {

class SimulationObjective : public Objective {
 public:
  // Throws InputError for a scene without a task, or with
  // parameters that cannot be resolved or bounded.
  SimulationObjective(const Scene& scene, const ParameterSet& parameters);

  int dimension() const override { return space_.size(); }
  double evaluate(const Eigen::VectorXd& z, Eigen::VectorXd& gradient) override;
  double value(const Eigen::VectorXd& z) override;
  long long stepsPerEvaluation() const override { return 2LL * scene_.time.steps; }
  long long stepsPerValue() const override { return scene_.time.steps; }

  // Counts a value() another process ran for this objective (a population spread over MPI
  // ranks), so that the totals below are the run's, wherever its evaluations ran.
  void countValueRunElsewhere(int unconvergedSteps, double seconds);

  // Heard after every forward and backward step of the evaluations from now on (a progress
  // display; a throw cancels within the evaluation). Empty: none.
  void setProgress(StepProgress progress) { progress_ = std::move(progress); }

  const ParameterSpace& space() const { return space_; }
  const ParameterSet& parameters() const { return parameters_; }
  const Scene& scene() const { return scene_; }
  // Totals over all evaluations.
  const AdjointSolverStats& backwardStats() const { return backward_; }
  // The last gradient's error estimate (diff/GradientErrorControl.h), the largest relative
  // estimate over all gradients, and how many missed solver.backward.accuracy.
  double lastGradientError() const override { return lastError_.relative; }
  const GradientErrorEstimate& lastGradientErrorEstimate() const { return lastError_; }
  double largestGradientError() const { return largestError_; }
  int gradientsMissingAccuracy() const { return missingAccuracy_; }
  int unconvergedForwardSteps() const { return unconverged_; }
  double seconds() const { return seconds_; }
  // Wall seconds in forward passes (of evaluate() and value()) and in backward passes (the adjoint
  // and the loss gradient, evaluate() only): DiffCloth Table 4's "Fwd." and "Back.".
  double forwardSeconds() const { return forwardSeconds_; }
  double backwardSeconds() const { return backwardSeconds_; }
  int forwardPasses() const { return forwardPasses_; }
  int backwardPasses() const { return backwardPasses_; }

 private:
  Scene scene_;
  ParameterSet parameters_;
  ParameterSpace space_;
  TaskLoss loss_;
  AccurateBackward backwardPass_;
  StepProgress progress_;
  GradientErrorEstimate lastError_;
  double largestError_ = 0.0;
  int missingAccuracy_ = 0;
  AdjointSolverStats backward_;
  int unconverged_ = 0;
  double seconds_ = 0.0;
  double forwardSeconds_ = 0.0;
  double backwardSeconds_ = 0.0;
  int forwardPasses_ = 0;
  int backwardPasses_ = 0;
};

}  // namespace weft
