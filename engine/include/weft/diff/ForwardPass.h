#pragma once
// The forward run a gradient is taken of: the scene simulated for its time.steps, every state
// recorded (the backward pass rebuilds each step's Delta P from the recorded x_{n+1}).

#include <weft/physics/Model.h>
#include <weft/record/StepProgress.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/Scene.h>

#include <memory>

namespace weft {

struct ForwardPass {
  Trajectory trajectory;
  int unconvergedSteps = 0;  // steps that stopped at solver.pd_iterations above pd_tolerance
  double maxResidual = 0.0;  // largest accepted residual (m/s^2)
  long long solves = 0;      // solves with P over the run
};

// The model simulated for its time.steps; the trajectory refers to it. `progress` (optional)
// hears of every step.
ForwardPass runForwardPass(std::shared_ptr<const Model> model, const StepProgress& progress = {});
// The same for a scene compiled here.
ForwardPass runForwardPass(const Scene& scene, const StepProgress& progress = {});

// The scene with the forward solver tightened for gradients: Newton-PCG (whose quadratic
// convergence reaches round-off in a few iterations), pd_tolerance = `tolerance` (m/s^2) and a
// generous iteration cap. The adjoint differentiates the exact step equations, so the gradient it
// gives is that of the run only as far as each step is converged; finite differences of a loosely
// converged run are dominated by the solver's stopping noise. Returns a revalidated scene.
Scene withTightForwardSolver(const Scene& scene, double tolerance, int maxSolves = 20000);

}  // namespace weft
