// `weft gradcheck SCENE [--param NAME ...] [--eps E] [--json] [--set PATH=VALUE ...]
//                       [--backward gmres|fixed_point|direct] [--forward-tolerance T]
//                       [--backward-tolerance T] [--threads N]`
// Compares the adjoint gradient of the scene's task loss with central finite differences, one
// line per parameter (or, with --json, a JSON list of {param, adjoint, finite_difference,
// relative_error}). The summary line goes to stdout after the table, or to stderr with --json so
// that stdout stays one JSON document.

#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"
#include "TaskParameters.h"

#include <weft/core/Error.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/ParameterSet.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <string>

namespace weft::cli {

int applyThreads(const CommandLine& cl);  // SimulateCommand.cpp

int gradcheckCommand(const std::vector<std::string>& args) {
  CommandLine cl(args,
                 {"--param", "--eps", "--set", "--backward", "--forward-tolerance",
                  "--backward-tolerance", "--threads"},
                 {"--json", "--quiet"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "gradcheck takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  applyThreads(cl);
  GradientCheckOptions options;
  options.eps = cl.number("--eps", options.eps);
  if (!(options.eps > 0.0 && options.eps < 1.0))
    cl.fail("--eps", "must be in (0, 1) (a relative step)");
  options.forwardTolerance = cl.number("--forward-tolerance", options.forwardTolerance);
  if (!(options.forwardTolerance > 0.0)) cl.fail("--forward-tolerance", "must be > 0 (m/s^2)");
  options.backwardTolerance = cl.number("--backward-tolerance", options.backwardTolerance);
  if (!(options.backwardTolerance > 0.0))
    cl.fail("--backward-tolerance", "must be > 0 (a relative residual)");
  if (cl.has("--backward")) {
    const std::string m = cl.value("--backward", "");
    if (m != "gmres" && m != "fixed_point" && m != "direct")
      cl.fail("--backward", "must be one of gmres, fixed_point, direct, got '" + m + "'");
    options.backwardMethod = m;
  }

  const TaskParameters task = loadTaskParameters(cl, file, "gradcheck");
  const Scene& scene = task.scene;
  const ParameterSet& parameters = task.parameters;

  const GradientCheckReport report = checkGradient(scene, parameters, options);

  if (cl.has("--json")) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& e : report.entries)
      list.push_back({{"param", e.param},
                      {"adjoint", e.adjoint},
                      {"finite_difference", e.finiteDifference},
                      {"relative_error", e.relativeError},
                      {"error_estimate", e.errorEstimate}});
    std::printf("%s\n", list.dump(2).c_str());
  } else {
    for (const auto& e : report.entries)
      std::printf(
          "%s  adjoint %.10e  finite_difference %.10e  relative_error %.3e  error_estimate %.2e\n",
          e.param.c_str(), e.adjoint, e.finiteDifference, e.relativeError, e.errorEstimate);
  }
  const AdjointSolverStats& b = report.backward;
  char summary[512];
  std::snprintf(
      summary, sizeof summary,
      "gradcheck: %s: %zu parameters, loss %.6e, max relative error %.3e; backward %s: %d steps, "
      "%lld iterations (max %d per step), %d not converged, %d fallbacks, adjoint growth %.2g, "
      "%s; %d forward runs (%d unconverged steps), %.2f s",
      scene.name.c_str(), report.entries.size(), report.loss, report.maxRelativeError(),
      report.backwardMethod.c_str(), b.solves, b.iterations, b.maxIterations, b.notConverged,
      b.fallbacks, b.adjointGrowth, describeGradientError(report.error).c_str(), report.forwardRuns,
      report.unconvergedSteps, report.seconds);
  std::fprintf(cl.has("--json") ? stderr : stdout, "%s\n", summary);
  const std::string error = gradientErrorWarning(report.error);
  if (!error.empty()) std::fprintf(stderr, "warning: %s\n", error.c_str());
  std::fprintf(stderr, "%s", unconvergedGradientWarning(report.unconvergedSteps).c_str());
  return 0;
}

}  // namespace weft::cli
