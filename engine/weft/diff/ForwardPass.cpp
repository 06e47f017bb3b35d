#include <weft/diff/ForwardPass.h>

#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <utility>

namespace weft {

ForwardPass runForwardPass(const Scene& scene, const StepProgress& progress) {
  return runForwardPass(Model::compile(scene), progress);
}

ForwardPass runForwardPass(std::shared_ptr<const Model> model, const StepProgress& progress) {
  ForwardPass pass;
  const int steps = model->stepCount();
  Simulator sim(std::move(model));
  int done = 0;
  sim.run(steps, pass.trajectory, [&](const StepStats&) {
    if (progress) progress(PassPhase::Forward, 1, ++done, steps);
  });
  for (const StepStats& s : pass.trajectory.steps) {
    if (!s.converged) ++pass.unconvergedSteps;
    pass.maxResidual = std::max(pass.maxResidual, s.residual);
    pass.solves += s.pdIterations;
  }
  return pass;
}

Scene withTightForwardSolver(const Scene& scene, double tolerance, int maxSolves) {
  nlohmann::json doc = scene.document;
  nlohmann::json& solver = doc["solver"];
  if (!solver.is_object()) solver = nlohmann::json::object();
  solver["method"] = "newton";
  solver["pd_tolerance"] = tolerance;
  solver["pd_iterations"] = maxSolves;
  return parseScene(doc, scene.file, scene.directory);
}

}  // namespace weft
