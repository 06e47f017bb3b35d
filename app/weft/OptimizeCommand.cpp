// `weft optimize SCENE [--method lbfgsb|cmaes|es1p1|adam] [--seed S] [--budget STEPS] [--out DIR]
//                      [--max-evaluations N] [--learning-rate R] [--first-step L]
//                      [--min-curvature-step L] [--set PATH=VALUE ...] [--threads N] [--quiet]`
// --first-step and --min-curvature-step are L-BFGS-B's (optim/LbfgsbOptimizer.h): the first trial
// step's length and the shortest step whose curvature pair is kept, in optimiser coordinates
// (defaults 1 and 0, LBFGSpp's behaviour).
// Minimises the scene's task loss over its task.parameters and
// writes, into DIR (default out/optimize-<scene name>), staged so that a failed run never
// replaces a good folder:
//   loss.csv     evaluation,steps,wall_s,loss,<parameter paths...>  (one row per evaluation)
//   result.json  method, seed, initial/final parameters and loss, evaluations, steps, gradient
//                norm (null for the gradient-free methods), stop reason, timing, backward-solver
//                counts, and final_handles_entering_obstacles: the scene check's messages for
//                the final parameters (handles driven into an obstacle; also printed as warnings)
//   loss.png     loss against simulated steps (gnuplot; skipped, with a note, without it)
// The budget is in simulated steps as DiffCloth's tables count them: a forward step is one, a
// backward step one more, so one evaluation of a scene with N steps costs 2N for the
// gradient-based methods (lbfgsb, adam) and N for the gradient-free ones (cmaes, es1p1). The
// default budget is the same for every method: 100 gradient evaluations' worth.

#include "BuildInfo.h"
#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/bench/BenchTable.h>
#include <weft/contact/HandleObstacleCheck.h>
#include <weft/core/Error.h>
#include <weft/diff/AdjointGrowth.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/distributed/WorkDistributor.h>
#include <weft/io/StagedDirectory.h>
#include <weft/optim/OptimizationRun.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace weft::cli {

int applyThreads(const CommandLine& cl);  // SimulateCommand.cpp

namespace {

// The default budget: enough for 100 evaluations (L-BFGS-B usually needs far fewer).
constexpr long long kDefaultEvaluations = 100;

nlohmann::json parameterObject(const ParameterSpace& space, const Eigen::VectorXd& values) {
  nlohmann::json o = nlohmann::json::object();
  for (int i = 0; i < space.size(); ++i) o[space.parameters()[i].path] = values[i];
  return o;
}

}  // namespace

int optimizeCommand(const std::vector<std::string>& args) {
  CommandLine cl(args,
                 {"--method", "--seed", "--budget", "--out", "--max-evaluations", "--learning-rate",
                  "--first-step", "--min-curvature-step", "--smoothing", "--smoothing-pairs",
                  "--set", "--threads"},
                 {"--quiet"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "optimize takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  applyThreads(cl);
  const std::string method = cl.value("--method", "lbfgsb");
  if (!makeOptimizer(method, OptimizerSettings{}))
    cl.fail("--method", "must be one of lbfgsb, cmaes, es1p1, adam, got '" + method + "'");
  OptimizerSettings settings;
  settings.seed = static_cast<unsigned>(cl.integer("--seed", 0, 0, 2147483647));
  settings.maxEvaluations = cl.integer("--max-evaluations", 0, 0, 100000000);
  settings.learningRate = cl.number("--learning-rate", settings.learningRate);
  if (!(settings.learningRate > 0.0)) cl.fail("--learning-rate", "must be > 0");
  settings.lbfgsbFirstStep = cl.number("--first-step", settings.lbfgsbFirstStep);
  if (!(settings.lbfgsbFirstStep > 0.0 && std::isfinite(settings.lbfgsbFirstStep)))
    cl.fail("--first-step", "must be a finite length > 0 (optimiser coordinates)");
  settings.lbfgsbMinCurvatureStep =
      cl.number("--min-curvature-step", settings.lbfgsbMinCurvatureStep);
  if (!(settings.lbfgsbMinCurvatureStep >= 0.0 && std::isfinite(settings.lbfgsbMinCurvatureStep)))
    cl.fail("--min-curvature-step", "must be a finite length >= 0 (optimiser coordinates)");
  if ((cl.has("--first-step") || cl.has("--min-curvature-step")) && method != "lbfgsb")
    cl.fail(cl.has("--first-step") ? "--first-step" : "--min-curvature-step",
            "is an L-BFGS-B setting; --method is '" + method + "'");
  settings.smoothingSigma = cl.number("--smoothing", 0.0);
  if (!(settings.smoothingSigma >= 0.0 && std::isfinite(settings.smoothingSigma)))
    cl.fail("--smoothing", "must be a finite standard deviation >= 0 (optimiser coordinates)");
  settings.smoothingPairs = cl.integer("--smoothing-pairs", settings.smoothingPairs, 1, 10000);
  if (cl.has("--smoothing-pairs") && !(settings.smoothingSigma > 0.0))
    cl.fail("--smoothing-pairs", "needs --smoothing SIGMA > 0");
  if (settings.smoothingSigma > 0.0 && method != "lbfgsb" && method != "adam")
    cl.fail("--smoothing",
            "is for the gradient-based methods (lbfgsb, adam); --method is '" + method + "'");
  const double budgetOption = cl.number("--budget", 0.0);
  if (cl.has("--budget") &&
      !(budgetOption >= 1.0 && budgetOption <= 1e15 && std::floor(budgetOption) == budgetOption))
    cl.fail("--budget", "must be a positive whole number of simulated steps");

  const Scene scene = loadScene(file, parseOverrides(cl));
  printSceneWarnings(scene);
  if (!scene.task)
    throw InputError(file, "task",
                     "the scene has no task; optimize needs task.loss and parameters");
  OptimizationRun run(scene, method);  // the task's parameters
  const SimulationObjective& objective = run.objective();
  const bool usesGradient = run.usesGradient();
  const long long perEvaluation = run.stepsPerEvaluation(settings);
  settings.budget = cl.has("--budget") ? static_cast<long long>(budgetOption)
                                       : kDefaultEvaluations * objective.stepsPerEvaluation();
  if (settings.budget < perEvaluation)
    cl.fail("--budget", "must allow at least one evaluation (" + std::to_string(perEvaluation) +
                            " simulated steps: " + std::to_string(scene.time.steps) + " forward" +
                            (usesGradient ? " + " + std::to_string(scene.time.steps) + " backward)"
                                          : ", no backward)"));

  // The gradient-free methods spread their evaluations over MPI's ranks when launched by
  // mpirun/srun (each rank runs the same optimisation; rank 0 writes); the gradient-based ones
  // evaluate one point at a time, so rank 0 runs them alone.
  if (usesGradient && launchSize() > 1) {
    if (launchRank() != 0) throw QuietExit{0};
    std::fprintf(stderr,
                 "note: %s evaluates one point at a time: rank 0 runs it alone, the other "
                 "processes exit (cmaes and es1p1 use them)\n",
                 method.c_str());
  }
  const std::string outDir = cl.value("--out", "out/optimize-" + scene.name);
  std::optional<StagedDirectory> out;  // fails early on an unusable --out, before optimising
  if (launchRank() == 0) out.emplace(outDir);
  WorkDistributor* workers = usesGradient ? nullptr : &processWorkers();
  run.setWorkers(workers);

  const ParameterSpace& space = run.space();
  std::ostringstream csv;
  csv << "evaluation,steps,wall_s,loss";
  for (const SceneParameter& p : space.parameters()) csv << "," << p.path;
  csv << "\n";
  csv.precision(17);
  const bool quiet = cl.has("--quiet") || launchRank() != 0;
  OptimizationCallbacks callbacks;
  callbacks.evaluated = [&](const LogEntry& e, const Eigen::VectorXd& v) {
    if (!std::isfinite(e.loss) || !e.gradient.allFinite())
      throw NumericalError(
          0, "optimize",
          "loss or gradient is not finite at evaluation " + std::to_string(e.evaluation));
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.6f", e.seconds);
    csv << e.evaluation << "," << e.steps << "," << wall << "," << e.loss;
    for (int i = 0; i < v.size(); ++i) csv << "," << v[i];
    csv << "\n";
    if (!quiet)
      std::fprintf(stderr, "\revaluation %d, %lld steps, loss %.6e   ", e.evaluation, e.steps,
                   e.loss);
  };

  const auto start = std::chrono::steady_clock::now();
  const OptimizationOutcome outcome = run.run(settings, callbacks);  // from the scene's values
  const OptimizationResult& result = outcome.result;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!quiet) std::fprintf(stderr, "\n");
  if (workers && !workers->isRoot()) return 0;
  {
    std::ofstream file(out->file("loss.csv"));
    file << csv.str();
    file.close();
    if (!file) throw InputError(outDir, "loss.csv", "cannot write");
  }
  if (run.log().empty()) throw NumericalError(0, "optimize", "no evaluation was made");

  const OptimizationLog& log = run.log();
  const Eigen::VectorXd& finalValues = outcome.bestValues;
  // An answer whose handles pass through an obstacle is no motion a manipulator can make, however
  // low its loss (the Sock, docs/applications.md): checked as the scene itself was, at load.
  const std::vector<std::string> entering =
      handlesEnteringObstacles(objective.parameters().withValues(scene, finalValues));
  for (const std::string& w : entering)
    std::fprintf(stderr, "warning: the final parameters: %s\n", w.c_str());
  // The gradient-free methods never compute one: the report says null rather than spend a
  // backward pass outside the budget.
  const nlohmann::json null(nullptr);
  Eigen::VectorXd dLdtheta;
  if (result.hasGradient) dLdtheta = space.gradientToValues(result.x, result.gradient);
  nlohmann::json bounds = nlohmann::json::object();
  for (const SceneParameter& p : space.parameters())
    bounds[p.path] = {
        {"lower", std::isfinite(p.lower) ? nlohmann::json(p.lower) : nlohmann::json(nullptr)},
        {"upper", std::isfinite(p.upper) ? nlohmann::json(p.upper) : nlohmann::json(nullptr)},
        {"log_scale", p.logScale}};
  const AdjointSolverStats& b = objective.backwardStats();
  nlohmann::json report = {
      {"scene", file},
      {"build", buildInfoJson()},
      {"method", method},
      {"seed", settings.seed},
      {"budget", settings.budget},
      {"lbfgsb", method == "lbfgsb"
                     ? nlohmann::json{{"first_step", settings.lbfgsbFirstStep},
                                      {"min_curvature_step", settings.lbfgsbMinCurvatureStep}}
                     : null},
      {"initial_parameters", parameterObject(space, space.initialValues())},
      {"initial_loss", log.entries().front().loss},
      {"final_parameters", parameterObject(space, finalValues)},
      {"final_loss", result.loss},
      {"smoothing", settings.smoothingSigma > 0.0
                        ? nlohmann::json{{"sigma", settings.smoothingSigma},
                                         {"pairs", settings.smoothingPairs},
                                         {"final_loss_unsmoothed", outcome.unsmoothedLoss},
                                         {"last_gradient_variance", outcome.lastGradientVariance}}
                        : null},
      {"evaluations", result.evaluations},
      {"best_evaluation", log.best().evaluation},
      {"iterations", result.iterations},
      {"steps", result.steps},
      {"steps_per_evaluation", perEvaluation},
      {"uses_gradient", usesGradient},
      {"gradient", result.hasGradient ? parameterObject(space, dLdtheta) : null},
      {"gradient_norm", result.hasGradient ? nlohmann::json(dLdtheta.norm()) : null},
      {"gradient_error_estimate", result.hasGradient ? nlohmann::json(result.gradientError) : null},
      {"projected_gradient_norm",
       result.hasGradient ? nlohmann::json(result.projectedGradientNorm) : null},
      {"stop_reason", result.stopReason},
      {"bounds", bounds},
      {"seconds", seconds},
      {"processes", workers ? workers->description() : "serial"},
      {"backward",
       {{"method", scene.solver.backward.method},
        {"solves", b.solves},
        {"iterations", b.iterations},
        {"hessian_iterations", b.hessianIterations},
        {"hessian_factorizations", b.hessianFactorizations},
        {"not_converged", b.notConverged},
        {"fallbacks", b.fallbacks},
        {"adjoint_growth", b.adjointGrowth},
        {"accuracy", scene.solver.backward.accuracy},
        {"passes", objective.backwardPasses()},
        {"largest_error_estimate", objective.largestGradientError()},
        {"gradients_missing_accuracy", objective.gradientsMissingAccuracy()}}},
      {"unconverged_forward_steps", objective.unconvergedForwardSteps()},
      {"final_handles_entering_obstacles", entering},
  };
  if (usesGradient) {
    if (objective.gradientsMissingAccuracy() > 0)
      std::fprintf(stderr,
                   "warning: backward: %d gradients missed solver.backward.accuracy %.2g "
                   "(largest estimated relative error %.2g; result.json's backward section)\n",
                   objective.gradientsMissingAccuracy(), scene.solver.backward.accuracy,
                   objective.largestGradientError());
    else if (scene.solver.backward.accuracy <= 0.0 &&
             objective.largestGradientError() >= kAdjointGradientErrorWarning)
      std::fprintf(stderr, "warning: %s\n",
                   gradientErrorWarning(objective.lastGradientErrorEstimate()).c_str());
    std::fprintf(stderr, "%s",
                 unconvergedGradientWarning(objective.unconvergedForwardSteps()).c_str());
  }
  std::string plotNote;
  bench::PlotSeries series{"loss", {}, {}};
  for (const LogEntry& e : log.entries())
    series.x.push_back(static_cast<double>(e.steps)), series.y.push_back(e.loss);
  const bool plotted = bench::plotSeries(
      out->file("loss.png"), scene.name + ": " + method,
      usesGradient ? "simulated steps (forward + backward)" : "simulated steps (forward only)",
      "loss", {series}, false, log.best().loss > 0.0, plotNote);
  report["plot"] = plotted ? nlohmann::json("loss.png") : nlohmann::json(nullptr);
  if (!plotted) std::fprintf(stderr, "warning: %s\n", plotNote.c_str());
  {
    std::ofstream json(out->file("result.json"));
    json << report.dump(2) << "\n";
    if (!json) throw InputError(outDir, "result.json", "cannot write");
  }
  out->commit();

  std::string smoothingNote;
  if (settings.smoothingSigma > 0.0) {
    char note[160];
    std::snprintf(note, sizeof note, " (smoothed, sigma %.3g, %d pairs; unsmoothed final %.6e)",
                  settings.smoothingSigma, settings.smoothingPairs, outcome.unsmoothedLoss);
    smoothingNote = note;
  }
  std::printf(
      "optimize: %s: %s, %d evaluations, %lld simulated steps, loss %.6e -> %.6e%s, stop: %s, "
      "%.2f s -> %s\n",
      scene.name.c_str(), method.c_str(), result.evaluations, result.steps,
      log.entries().front().loss, result.loss, smoothingNote.c_str(), result.stopReason.c_str(),
      seconds, outDir.c_str());
  return 0;
}

}  // namespace weft::cli
