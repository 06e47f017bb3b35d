// `weft gradient SCENE [--param PATH ...] [--set PATH=VALUE ...] [--json] [--threads N]`
// The task loss's gradient exactly as `weft optimize` gets it (the scene's own forward and
// backward settings, error-controlled to solver.backward.accuracy) with each component's error
// estimate: one line per parameter, or with --json a JSON list of {param, value,
// error_estimate, parameter_value}. The summary line goes to stdout after the table, or to
// stderr with --json.

#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"
#include "TaskParameters.h"

#include <weft/core/Error.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/SceneGradient.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

namespace weft::cli {

int applyThreads(const CommandLine& cl);  // SimulateCommand.cpp

int gradientCommand(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--param", "--set", "--threads"}, {"--json", "--quiet"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "gradient takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  applyThreads(cl);

  const TaskParameters task = loadTaskParameters(cl, file, "gradient");
  const Scene& scene = task.scene;
  const ParameterSet& parameters = task.parameters;

  const SceneGradient g = sceneGradient(scene, parameters);
  const GradientResult& r = g.result;
  if (!std::isfinite(r.loss) || !r.gradient.allFinite())
    throw NumericalError(0, "backward", "the loss or its gradient is not finite");

  if (cl.has("--json")) {
    nlohmann::json list = nlohmann::json::array();
    for (int k = 0; k < parameters.size(); ++k)
      list.push_back({{"param", parameters[k].path},
                      {"value", r.gradient[k]},
                      {"error_estimate", r.error.absolute[k]},
                      {"parameter_value", g.values[k]}});
    std::printf("%s\n", list.dump(2).c_str());
  } else {
    for (int k = 0; k < parameters.size(); ++k)
      std::printf("%s  gradient %.10e  error_estimate %.2e  (at %.10g)\n",
                  parameters[k].path.c_str(), r.gradient[k], r.error.absolute[k], g.values[k]);
  }
  const AdjointSolverStats& b = r.solver;
  char summary[640];
  std::snprintf(summary, sizeof summary,
                "gradient: %s: %d parameters, loss %.6e; %s; backward %s: %d solves, %lld "
                "iterations, %d fallbacks, adjoint growth %.2g, %.2f s; forward %.2f s (%d "
                "unconverged steps)",
                scene.name.c_str(), parameters.size(), r.loss,
                describeGradientError(r.error).c_str(), scene.solver.backward.method.c_str(),
                b.solves, b.iterations, b.fallbacks, b.adjointGrowth, r.seconds, g.forwardSeconds,
                g.unconvergedSteps);
  std::fprintf(cl.has("--json") ? stderr : stdout, "%s\n", summary);
  const std::string error = gradientErrorWarning(r.error);
  if (!error.empty()) std::fprintf(stderr, "warning: %s\n", error.c_str());
  std::fprintf(stderr, "%s", unconvergedGradientWarning(g.unconvergedSteps).c_str());
  return 0;
}

}  // namespace weft::cli
