// `weft bench applications [--tasks a,b] [--methods m,n] [--seeds N[,task=M...]] [--budget STEPS]
//                          [--quick]
//                          [--out DIR] [--threads N] [--jobs J] [--resume] [--paper-meshes [DIR]]
//                          [--first-step L] [--min-curvature-step L]`:
// DiffCloth's comparison of gradient-based and gradient-free optimisation (Sec. 5.2 and Fig. 4, the
// Flying Napkin; Sec. 6, Tables 2-3; Appendix C, Tables 5-6). Every task scene is optimised by
// L-BFGS-B (adjoint gradients), CMA-ES and the (1+1)-ES (values alone) from the same random
// starting point per seed, each run with the same budget of simulated steps (a forward step 1, a
// backward step 1 more, as the paper counts them). Writes, staged, into DIR (default
// out/bench-applications):
//   applications.csv  task,method,seed,evaluation,steps,wall_s,loss: every evaluation of every run
//   applications.md   the Table 2 analogue (final loss and loss at L-BFGS-B's convergence step
//                     count, as % of the minimum initial loss), the Table 3 / Fig. 4 analogue
//                     (steps to converge and to reach a loss threshold, speedups) and the
//                     Table 4 analogue (seconds per forward and backward pass, share of
//                     converged iterative backward solves), the same beside DiffCloth's
//                     published figures, the Tables 5-6 analogue (every seed), and for tasks
//                     with handles and obstacles how deep each run's best point puts a handle
//                     target inside an obstacle
//   passes.csv        the Table 4 analogue
//   loss_<task>.png   loss against steps, the minimum envelope over seeds (Fig. 4 bottom left)
//   speedup.png       speedup against the parameter count (Fig. 4 bottom right)
//   runs/             every (task, method, seed) run as <task>_<method>_<seed>.csv (the rows of
//                     applications.csv), settings.json (budget, quick, paper meshes) and
//                     parameters/<task>_<method>_<seed>.csv: evaluation, then the value of each
//                     task parameter (scene units) that evaluation simulated
//   paper_scenes/     with --paper-meshes: the scenes as run (<task>.json, targets beside them)
// Runs are written as they finish, atomically, into DIR.partial/ (kept when the comparison is
// killed or fails); --resume reads the runs stored there (or in DIR/runs/ of a finished
// comparison) instead of running them again, and refuses runs stored with other settings.
// --seeds N,task=M,... runs M seeds of the tasks named and N of the others (seeds are not
// settings of the store: more seeds of a task resume from the runs of fewer).
// A store made by a build with other app/weft/ or bench/ sources (same engine and assets) can be
// tabulated again when all its runs are made, not added to.
// --methods m,n (of lbfgsb, cmaes, es1p1) makes the runs of those methods only; stored runs of the
// others are still read back and tabulated, so a comparison too long for one sitting (the Sock's
// runs take hours each) can be made a method at a time, and one method rerun after a fix (its run
// files deleted from the store) without repeating the others.
// --first-step and --min-curvature-step are L-BFGS-B's settings (optim/LbfgsbOptimizer.h), for
// every task; without them L-BFGS-B is LBFGSpp's. They are stored with the runs (settings.json,
// absent = the default, so stores made before they existed resume as they were).
// --jobs J makes J runs at once, each on its own thread with --threads OpenMP threads (on this
// 2-core machine: --jobs 2 --threads 1); the stored runs are the same whatever J, their wall
// seconds are not.

#include "ApplicationsBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"
#include "BuildRecord.h"
#include "HandleDepth.h"
#include "LossEnvelope.h"
#include "PaperMeshScenes.h"
#include "PaperTables.h"
#include "SpeedupAim.h"
#include "StoredParameters.h"
#include "StoredRun.h"

#include <weft/core/Error.h>
#include <weft/core/ProcessCpuTime.h>
#include <weft/diff/ParameterSet.h>
#include <weft/distributed/WorkDistributor.h>
#include <weft/io/AtomicFile.h>
#include <weft/io/StagedDirectory.h>
#include <weft/optim/OptimizationRun.h>
#include <weft/optim/StartingPoint.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

namespace weft::bench {
namespace {

// "Steps to reach": the envelope at or below this fraction of the minimum initial loss (the
// paper's Fig. 4 uses an absolute 0.01 in its own loss units; a fraction carries over to tasks
// whose losses differ in scale).
constexpr double kThresholdFraction = 0.01;
// DiffCloth Sec. 5.2: Fig. 4's speedup is the ratio of steps "when their losses reach 0.01".
constexpr double kFig4SpeedupLoss = 0.01;
// "Converged": the loss within this fraction of the total decrease of its final value (the paper
// counts steps "until convergence" without saying when; L-BFGS-B's own stop, a relative loss
// change of 1e-12, is reached only after a long tail of tiny gains).
constexpr double kConvergedFraction = 0.01;
// Seconds of a run between two of its progress lines on stderr.
constexpr double kProgressSeconds = 300.0;

// DiffCloth Table 4 and Table 3's "Iter. Conv. %" for one task: one gradient evaluation (forward
// pass, then backward pass) at the scene's own parameter values, timed apart.
struct PassTiming {
  bool measured = false;
  std::string failure;  // a NumericalError that ended the pass
  int steps = 0;
  double timeStep = 0.0;
  double forwardSeconds = 0.0, backwardSeconds = 0.0, cpuSeconds = 0.0;
  int backwardSolves = 0, notConverged = 0;
  int unconvergedForwardSteps = 0;
  double adjointGrowth = 1.0;
};

struct TaskResult {
  const ApplicationTask* task = nullptr;
  int parameters = 0;
  long long budget = 0;
  std::vector<ApplicationRun> runs;
  std::optional<paper::PaperScene> paperScene;  // --paper-meshes, for tasks that have one
  int garmentVertices = 0;
  PassTiming timing;
  std::vector<StartingPoint> starts;  // seed s at s - 1 (StartingPoint.h)
  int seeds = 0;                      // seeds 1..seeds (--seeds)
  bool handles = false;  // handles and obstacles: ApplicationRun::handleDepth is measured
};

PassTiming timePasses(const Scene& scene, const ParameterSet& parameters) {
  PassTiming timing;
  timing.steps = scene.time.steps;
  timing.timeStep = scene.time.dt;
  SimulationObjective objective(scene, parameters);
  const Eigen::VectorXd z = objective.space().toCoordinates(objective.space().initialValues());
  Eigen::VectorXd gradient;
  const double cpu = processCpuSeconds();
  try {
    objective.evaluate(z, gradient);
    timing.measured = true;
  } catch (const NumericalError& e) {
    timing.failure = e.what();
  }
  timing.cpuSeconds = processCpuSeconds() - cpu;
  timing.forwardSeconds = objective.forwardSeconds();
  timing.backwardSeconds = objective.backwardSeconds();
  timing.backwardSolves = objective.backwardStats().solves;
  timing.notConverged = objective.backwardStats().notConverged;
  timing.unconvergedForwardSteps = objective.unconvergedForwardSteps();
  timing.adjointGrowth = objective.backwardStats().adjointGrowth;
  return timing;
}

// "3 seed(s) per task (1..3)", then the tasks that have another count: ", sock 2 (1..2)".
std::string describeSeeds(const std::vector<TaskResult>& results) {
  std::map<int, int> tasksWith;
  for (const TaskResult& r : results) ++tasksWith[r.seeds];
  int common = results.empty() ? 0 : results.front().seeds;
  for (const auto& [n, k] : tasksWith)
    if (k > tasksWith[common]) common = n;
  const auto range = [](int n) { return " (1.." + std::to_string(n) + ")"; };
  std::string text = std::to_string(common) + " seed(s) per task" + range(common);
  for (const TaskResult& r : results)
    if (r.seeds != common)
      text += ", " + std::string(r.task->name) + " " + std::to_string(r.seeds) + range(r.seeds);
  return text;
}

std::string percent(double loss, double reference) {
  if (!(reference > 0.0) || !std::isfinite(loss)) return "-";
  return formatNumber(100.0 * loss / reference, 3);
}

// The first step count at which a run's running minimum (or an envelope) is within
// kConvergedFraction of the decrease from `initial` to its final value.
long long convergenceSteps(const LossCurve& envelope, double initial) {
  const double final = envelope.loss.back();
  return stepsToReach(envelope, final + kConvergedFraction * std::max(0.0, initial - final));
}

namespace fs = std::filesystem;

std::string runFileName(const ApplicationTask& task, int method, int seed) {
  return std::string(task.name) + "_" + kApplicationMethods[method].name + "_" +
         std::to_string(seed) + ".csv";
}

// The parameter values of every evaluation of a run (issue 7: "every run records ... the
// parameters at each evaluation"), beside its run file in the store's parameters/ folder.
// Written before the run file, so that a stored run always has them.
void writeParameterFile(const std::string& path, const ParameterSpace& space,
                        const OptimizationLog& log) {
  std::vector<std::string> header{"evaluation"};
  for (const SceneParameter& p : space.parameters()) header.push_back(p.path);
  std::string text = joinCsvLine(header);
  for (const LogEntry& e : log.entries()) {
    std::vector<std::string> row{std::to_string(e.evaluation)};
    const Eigen::VectorXd values = space.toValues(e.x);
    for (int i = 0; i < values.size(); ++i) row.push_back(formatNumber(values[i], 17));
    text += joinCsvLine(row);
  }
  writeFileAtomically(path, text);
}

// What a stored run depends on besides its task, method and seed.
nlohmann::json runSettings(const ApplicationsBenchOptions& options) {
  const OptimizerSettings& lbfgsb = options.lbfgsb;
  const OptimizerSettings defaults;
  auto unlessDefault = [](double value, double fallback) {
    return value == fallback ? nlohmann::json(nullptr) : nlohmann::json(value);
  };
  return {{"format", "weft bench applications runs 2"},
          {"budget",
           options.budget > 0 ? nlohmann::json(options.budget) : nlohmann::json("task default")},
          {"quick", options.quick},
          {"paper_meshes", options.paperMeshes.empty() ? nlohmann::json(nullptr)
                                                       : nlohmann::json(options.paperMeshes)},
          {"lbfgsb_first_step", unlessDefault(lbfgsb.lbfgsbFirstStep, defaults.lbfgsbFirstStep)},
          {"lbfgsb_min_curvature_step",
           unlessDefault(lbfgsb.lbfgsbMinCurvatureStep, defaults.lbfgsbMinCurvatureStep)},
          {"build", options.build}};
}

std::string describeSetting(const std::string& key, const nlohmann::json& v) {
  if (key == "budget")
    return v.is_number() ? "--budget " + v.dump()
           : v.is_null() ? "no budget"
                         : "each task's default budget";
  if (key == "quick") return v == nlohmann::json(true) ? "--quick" : "no --quick";
  if (key == "paper_meshes")
    return v.is_string() ? "--paper-meshes " + v.get<std::string>() : "the tasks' own meshes";
  if (key == "lbfgsb_first_step")
    return v.is_number() ? "--first-step " + v.dump() : "L-BFGS-B's default first step";
  if (key == "lbfgsb_min_curvature_step")
    return v.is_number() ? "--min-curvature-step " + v.dump()
                         : "L-BFGS-B's default curvature pairs";
  return v.is_null() ? "none" : v.is_string() ? v.get<std::string>() : v.dump();
}

// Throws unless the settings stored in `file` are `settings`; returns the stored settings.
// *appDiffers (when given) receives the refusal for runs made by other app/weft/ or bench/ sources
// instead of the throw: such a build may still tabulate a store whose runs are all made.
nlohmann::json checkStoredSettings(const std::string& file, const nlohmann::json& settings,
                                   std::string* appDiffers = nullptr) {
  nlohmann::json stored;
  try {
    std::ifstream in(file);
    stored = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "<json>", std::string("invalid JSON: ") + e.what());
  }
  for (const char* key : {"format", "budget", "quick", "paper_meshes", "lbfgsb_first_step",
                          "lbfgsb_min_curvature_step"}) {
    const nlohmann::json have = stored.contains(key) ? stored[key] : nlohmann::json(nullptr);
    if (have != settings[key])
      throw InputError(file, key,
                       "the stored runs were made with " + describeSetting(key, have) +
                           ", this command asks for " + describeSetting(key, settings[key]) +
                           "; resume with the same settings, or use another --out");
  }
  // The build: runs made by different engines, CLIs or task assets are not one comparison (the
  // T-shirt's and Sphere's targets are even recorded by the build). The commit alone may differ
  // (a docs commit). A store or build without git information is not checked.
  const nlohmann::json have = stored.value("build", nlohmann::json());
  const nlohmann::json& want = settings["build"];
  if (isKnownBuild(have) && isKnownBuild(want))
    for (const char* key : {"engine", "app", "assets", "modified"}) {
      const nlohmann::json a = have.value(key, nlohmann::json()),
                           b = want.value(key, nlohmann::json());
      if (a == b) continue;
      const std::string made = "the stored runs were made by " + describeBuild(have) + ", whose ";
      const std::string mine = " differ from this build's (" + describeBuild(want) + ")";
      if (std::string(key) == "app" && appDiffers)
        *appDiffers = made + "app/ sources" + mine;
      else
        throw InputError(file, std::string("build.") + key,
                         made +
                             (std::string(key) == "modified" ? std::string("uncommitted changes")
                                                             : std::string(key) + "/ sources") +
                             mine +
                             "; their results would not be one comparison: use another --out");
    }
  return stored;
}

// The run store: DIR.partial/ while the comparison runs. Returns the number of stored runs.
// *storedBuild: the build that made the store's first runs (settings.json's "build");
// *appDiffers: checkStoredSettings's; *copied: whether the store was made here, a copy of the
// finished comparison's runs.
int openRunStore(const std::string& store, const std::string& finished, bool resume,
                 const nlohmann::json& settings, nlohmann::json* storedBuild,
                 std::string* appDiffers, bool* copied) {
  std::error_code ec;
  const std::string settingsFile = store + "/settings.json";
  if (fs::exists(store, ec) && !resume)
    throw InputError(store, "--resume",
                     "holds the runs of an unfinished comparison: pass --resume to continue it, or "
                     "remove the folder to start over");
  if (resume && !fs::exists(store, ec) && fs::is_regular_file(finished + "/settings.json", ec)) {
    // A finished comparison: continue from its runs (more seeds, more tasks) without touching it.
    checkStoredSettings(finished + "/settings.json", settings, appDiffers);
    fs::create_directories(store, ec);
    fs::copy(finished, store, fs::copy_options::recursive, ec);
    *copied = true;
    if (ec)
      throw InputError(store, "--resume",
                       "cannot copy the runs of " + finished + ": " + ec.message());
  }
  if (fs::exists(settingsFile, ec)) {
    *storedBuild =
        checkStoredSettings(settingsFile, settings, appDiffers).value("build", nlohmann::json());
  } else {
    *storedBuild = settings["build"];
    fs::create_directories(store, ec);
    if (ec) throw InputError(store, "--out", "cannot create the run folder: " + ec.message());
    writeFileAtomically(settingsFile, settings.dump(2) + "\n");
  }
  fs::create_directories(store + "/parameters", ec);
  if (ec) throw InputError(store, "--out", "cannot create the run folder: " + ec.message());
  int stored = 0;
  for (const auto& entry : fs::directory_iterator(store, ec))
    if (entry.path().extension() == ".csv") ++stored;
  return stored;
}

// The scene of a task that has runs to make (or a pass to time), loaded once.
struct TaskScene {
  std::optional<Scene> scene;
  std::optional<ParameterSet> parameters;
  std::optional<SimulationObjective> probe;  // the box and the starting values
};

// A run still to make.
struct Job {
  std::size_t task;
  int seed, method;
  ApplicationRun run;
};

// One invocation's state, shared by the steps below.
struct Comparison {
  const ApplicationsBenchOptions& options;
  std::string store;                // DIR.partial/: the runs, stored as they finish
  std::vector<TaskResult> results;  // one per task, in options.tasks' order
  std::vector<TaskScene> loaded;    // beside results
  nlohmann::json storedBuild;       // openRunStore's
  std::string appDiffers;           // openRunStore's
  bool storeCopied = false;         // openRunStore's
  int storedRuns = 0, newRuns = 0, resumedRuns = 0;
};

// Every task's budget, checked before anything runs.
std::vector<TaskResult> checkedTasks(const ApplicationsBenchOptions& options) {
  std::vector<TaskResult> results;
  for (std::size_t t = 0; t < options.tasks.size(); ++t) {
    const ApplicationTask* task = options.tasks[t];
    const std::string file = assetFile(task->scene);
    const Scene scene = loadScene(file, {});
    const ParameterSet parameters = ParameterSet::fromTask(scene);
    if (parameters.empty()) throw InputError(file, "task.parameters", "no parameters to optimise");
    TaskResult result;
    result.task = task;
    result.seeds = options.seeds[t];
    result.parameters = parameters.size();
    result.garmentVertices = scene.vertexCount();
    result.budget = options.budget > 0 ? options.budget
                    : options.quick    ? task->quickBudget
                                       : task->budget;
    const long long perGradient = 2LL * scene.time.steps;
    if (result.budget < perGradient)
      throw InputError("weft", "--budget",  // the option's error, as the command line reports it
                       "must allow at least one gradient evaluation of " + std::string(task->name) +
                           " (" + std::to_string(perGradient) + " simulated steps)");
    results.push_back(std::move(result));
  }
  return results;
}

const TaskScene& loadTaskScene(Comparison& c, std::size_t t) {
  TaskScene& ts = c.loaded[t];
  if (ts.scene) return ts;
  const TaskResult& result = c.results[t];
  const std::string file = assetFile(result.task->scene);
  if (!result.paperScene)
    ts.scene = loadScene(file, {});
  else
    ts.scene = parseScene(result.paperScene->document, file, fs::path(file).parent_path().string());
  for (const std::string& w : ts.scene->warnings)
    std::fprintf(stderr, "warning: %s: %s\n", result.task->name, w.c_str());
  ts.parameters = ParameterSet::fromTask(*ts.scene);
  ts.probe.emplace(*ts.scene, *ts.parameters);
  return ts;
}

// Each seed's start, drawn once per task (the draws re-check the handles against the obstacles)
// and shared by the task's jobs and the report.
void drawStarts(Comparison& c, std::size_t t) {
  TaskResult& result = c.results[t];
  if (!result.starts.empty()) return;
  const TaskScene& ts = loadTaskScene(c, t);
  for (int seed = 1; seed <= result.seeds; ++seed)
    result.starts.push_back(drawStartingPoint(*ts.scene, *ts.parameters, ts.probe->space(),
                                              static_cast<unsigned>(seed)));
}

// Stored runs are read back; the others become jobs.
std::vector<Job> readStoredRuns(Comparison& c) {
  std::vector<Job> jobs;
  for (std::size_t t = 0; t < c.results.size(); ++t) {
    TaskResult& result = c.results[t];
    const ApplicationTask* task = result.task;
    const paper::PaperMesh* paperMesh =
        c.options.paperMeshes.empty() ? nullptr : paper::paperMeshFor(task->name);
    if (paperMesh) {
      std::fprintf(stderr, "applications: %s on %s...\n", task->name, paperMesh->file);
      result.paperScene =
          paper::makePaperScene(assetFile(task->scene), *paperMesh, c.options.paperMeshes,
                                c.store + "/targets", /*reuseTarget=*/true);
      result.garmentVertices = result.paperScene->vertices;
    }
    for (int seed = 1; seed <= result.seeds; ++seed)
      for (int m = 0; m < kApplicationMethodCount; ++m) {
        const std::string runFile = c.store + "/" + runFileName(*task, m, seed);
        if (fs::exists(runFile)) {
          ApplicationRun run = readRunFile(runFile, *task, m, seed);
          ++c.resumedRuns;
          if (!run.curve.steps.empty()) result.runs.push_back(std::move(run));
          continue;
        }
        if (!c.options.methods[m]) continue;
        drawStarts(c, t);
        jobs.push_back({t, seed, m, {}});
      }
  }
  return jobs;
}

void refuseRunsOfAnotherApp(const Comparison& c, const std::vector<Job>& jobs) {
  // Runs made by other app/weft/ or bench/ sources (the CLI, this bench, the task budgets) are read
  // back only to be tabulated again (a new table, a corrected report); a run this build made would
  // not be one comparison with them, and a stored run must fit this build's budget.
  if (c.appDiffers.empty()) return;
  if (!jobs.empty()) {
    std::error_code ec;
    if (c.storeCopied) fs::remove_all(c.store, ec);  // the finished comparison is left as it was
    throw InputError(c.store + "/settings.json", "build.app",
                     c.appDiffers + ": it may tabulate them, but not add runs to them (" +
                         std::to_string(jobs.size()) +
                         " run(s) are still to be made); build the commit that made them to "
                         "continue, or use another --out");
  }
  for (const TaskResult& r : c.results)
    for (const ApplicationRun& run : r.runs)
      if (run.curve.steps.back() > r.budget)
        throw InputError(c.store + "/" + runFileName(*r.task, run.method, run.seed), "steps",
                         "the stored run used " + std::to_string(run.curve.steps.back()) +
                             " steps, over this build's budget of " + std::to_string(r.budget) +
                             " for " + r.task->name);
}

// One run: the task's OptimizationRun from the seed's start, its rows and its parameter values
// stored as soon as it ends.
void makeRun(Comparison& c, Job& job) {
  const ApplicationTask* task = c.results[job.task].task;
  const TaskScene& ts = c.loaded[job.task];
  const int m = job.method;
  const Eigen::VectorXd& start = c.results[job.task].starts[job.seed - 1].coordinates;
  std::fprintf(stderr, "applications: %s, %s, seed %d...\n", task->name,
               kApplicationMethods[m].name, job.seed);
  OptimizationRun optimization(*ts.scene, kApplicationMethods[m].name);  // the task's parameters
  OptimizerSettings settings;
  settings.budget = c.results[job.task].budget;
  settings.seed = static_cast<unsigned>(job.seed);
  settings.lbfgsbFirstStep = c.options.lbfgsb.lbfgsbFirstStep;
  settings.lbfgsbMinCurvatureStep = c.options.lbfgsb.lbfgsbMinCurvatureStep;
  // A run can take hours (the Sock's); one progress line per kProgressSeconds of it.
  double reported = 0.0;
  double best = std::numeric_limits<double>::infinity();
  OptimizationCallbacks callbacks;
  callbacks.evaluated = [&, budget = settings.budget](const LogEntry& e, const Eigen::VectorXd&) {
    best = std::min(best, e.loss);
    if (e.seconds - reported < kProgressSeconds) return;
    reported = e.seconds;
    std::fprintf(stderr,
                 "applications: %s, %s, seed %d: evaluation %d, %lld of %lld steps, best "
                 "loss %s, %.0f s\n",
                 task->name, kApplicationMethods[m].name, job.seed, e.evaluation, e.steps, budget,
                 formatNumber(best, 4).c_str(), e.seconds);
  };
  ApplicationRun& run = job.run;
  run.method = m;
  run.seed = job.seed;
  try {
    run.stop = optimization.run(settings, start, callbacks).result.stopReason;
  } catch (const NumericalError& e) {
    // A sample the forward solver cannot simulate ends that run, not the benchmark.
    run.stop = std::string("numerical failure: ") + e.what();
    std::fprintf(stderr, "warning: %s, %s, seed %d: %s\n", task->name, kApplicationMethods[m].name,
                 job.seed, e.what());
  }
  for (const LogEntry& e : optimization.log().entries()) {
    run.curve.steps.push_back(e.steps);
    run.curve.loss.push_back(e.loss);
    run.seconds = e.seconds;
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.6f", e.seconds);
    run.rows.push_back({task->name, kApplicationMethods[m].name, std::to_string(job.seed),
                        std::to_string(e.evaluation), std::to_string(e.steps), wall,
                        formatNumber(e.loss, 17)});
  }
  const std::string name = runFileName(*task, m, job.seed);
  writeParameterFile(c.store + "/parameters/" + name, optimization.space(), optimization.log());
  writeRunFile(c.store + "/" + name, run);  // from here on the run survives a kill
}

// The runs to make, `jobs` at a time (--jobs), each on its own thread with --threads OpenMP
// threads: the runs are independent and each is deterministic, so the stored runs do not depend
// on how many ran at once (only their wall seconds do, through the load).
void makeRuns(Comparison& c, std::vector<Job>& jobs) {
  WorkDistributor* workers = c.options.workers;
  if (workers && workers->size() > 1) {
    // One run per work item, made and stored by the rank that takes it; rank 0 reads the others'
    // back from the store. A failed run (bad input) is reported with its rank once every other
    // run has been made and stored.
    const std::vector<WorkItemResult> made = workers->map(jobs.size(), [&](std::size_t j) {
      makeRun(c, jobs[j]);
      return std::string();
    });
    for (std::size_t j = 0; j < jobs.size(); ++j)
      if (!made[j].ok)
        std::fprintf(stderr, "error: %s, %s, seed %d (rank %d): %s\n",
                     c.results[jobs[j].task].task->name, kApplicationMethods[jobs[j].method].name,
                     jobs[j].seed, made[j].rank, made[j].message.c_str());
    if (const WorkItemResult* failed = firstFailure(made)) rethrowFailure(*failed);
    c.newRuns = static_cast<int>(jobs.size());
    if (!workers->isRoot()) return;
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      Job& job = jobs[j];
      if (made[j].rank != 0) {
        const ApplicationTask& task = *c.results[job.task].task;
        job.run = readRunFile(c.store + "/" + runFileName(task, job.method, job.seed), task,
                              job.method, job.seed);
      }
      if (!job.run.curve.steps.empty()) c.results[job.task].runs.push_back(std::move(job.run));
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::mutex failureMutex;
  std::exception_ptr failure;
  const auto work = [&]() {
    omp_set_num_threads(c.options.threads);  // (a new thread starts from OpenMP's default)
    for (std::size_t j = next++; j < jobs.size(); j = next++) {
      try {
        makeRun(c, jobs[j]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
        next = jobs.size();  // no new runs; the running ones finish and are stored
      }
    }
  };
  {
    std::vector<std::thread> workers;
    const std::size_t count =
        std::min<std::size_t>(static_cast<std::size_t>(c.options.jobs), jobs.size());
    for (std::size_t w = 1; w < count; ++w) workers.emplace_back(work);
    work();
    for (std::thread& w : workers) w.join();
  }
  omp_set_num_threads(c.options.threads);
  if (failure) std::rethrow_exception(failure);
  c.newRuns = static_cast<int>(jobs.size());
  for (Job& job : jobs)
    if (!job.run.curve.steps.empty()) c.results[job.task].runs.push_back(std::move(job.run));
}

// What the tables need besides the runs: the passes timed, the starts, the handles' depths.
void measureTasks(Comparison& c) {
  for (std::size_t t = 0; t < c.results.size(); ++t) {
    TaskResult& result = c.results[t];
    std::stable_sort(result.runs.begin(), result.runs.end(),
                     [](const ApplicationRun& a, const ApplicationRun& b) {
                       return a.seed != b.seed ? a.seed < b.seed : a.method < b.method;
                     });
    // Table 4: not stored with the runs, so measured again by every invocation (one gradient
    // evaluation, small next to the runs themselves), one task at a time after all runs.
    const TaskScene& ts = loadTaskScene(c, t);
    std::fprintf(stderr, "applications: %s, one forward and backward pass, timed...\n",
                 result.task->name);
    result.timing = timePasses(*ts.scene, *ts.parameters);
    drawStarts(c, t);
    // Where each run's answer puts the handles, from the values stored with the run: an answer
    // that drives a handle through the body is not a motion a manipulator can make, however low
    // its loss (the Sock, docs/applications.md).
    result.handles = hasHandlesAndObstacles(*ts.scene);
    if (result.handles)
      for (ApplicationRun& run : result.runs) {
        const std::string file =
            c.store + "/parameters/" + runFileName(*result.task, run.method, run.seed);
        const Eigen::VectorXd values =
            storedParameterValues(file, *ts.parameters, bestEvaluation(run));
        run.handleDepth = deepestHandleTargetDepth(ts.parameters->withValues(*ts.scene, values));
      }
  }
}

// The tables of applications.md (and applications.csv, passes.csv), filled a task at a time.
struct Tables {
  BenchTable csv{kRunColumns};
  BenchTable losses{{"task", "parameters", "seeds", "budget (steps)", "min initial loss",
                     "L-BFGS-B final %", "CMA-ES final %", "CMA-ES equal-step %",
                     "(1+1)-ES final %", "(1+1)-ES equal-step %"}};
  BenchTable steps{{"task", "parameters", "threshold", "L-BFGS-B conv. steps", "CMA-ES conv. steps",
                    "(1+1)-ES conv. steps", "L-BFGS-B steps to threshold",
                    "CMA-ES steps to threshold", "(1+1)-ES steps to threshold", "CMA-ES speedup",
                    "(1+1)-ES speedup"}};
  BenchTable passes{{"task", "DoF", "time steps", "h [s]", "forward s", "backward s",
                     "CPU s (both)", "iter. conv. %", "unconverged forward steps", "adjoint growth",
                     "L-BFGS-B s per evaluation (runs)", "runs' wall s (all)"}};
  BenchTable beside{{"task", "source", "parameters", "seeds", "L-BFGS-B final %", "CMA-ES final %",
                     "CMA-ES equal-step %", "(1+1)-ES final %", "(1+1)-ES equal-step %",
                     "L-BFGS-B conv. steps", "CMA-ES conv. steps", "(1+1)-ES conv. steps",
                     "CMA-ES / L-BFGS-B steps", "iter. conv. %", "forward s", "backward s"}};
  BenchTable handles{{"task", "seed", "L-BFGS-B (mm)", "CMA-ES (mm)", "(1+1)-ES (mm)"}};
  BenchTable aims{{"task", "target", "target loss", "L-BFGS-B steps", "CMA-ES steps",
                   "(1+1)-ES steps", "CMA-ES / L-BFGS-B", "L-BFGS-B in a fifth of CMA-ES's steps"}};
  BenchTable perSeed{{"task", "seed", "initial loss", "L-BFGS-B final", "CMA-ES final",
                      "(1+1)-ES final", "L-BFGS-B %", "CMA-ES %", "(1+1)-ES %",
                      "L-BFGS-B conv. steps", "CMA-ES conv. steps", "(1+1)-ES conv. steps",
                      "L-BFGS-B wall s", "CMA-ES wall s", "(1+1)-ES wall s"}};
  // Points, not lines: the tasks are not one family (the napkins and wind_sysid share an axis).
  std::vector<PlotSeries> speedup{{"CMA-ES / L-BFGS-B", {}, {}, "points pointsize 2"},
                                  {"(1+1)-ES / L-BFGS-B", {}, {}, "points pointsize 2"}};
  std::vector<std::string> plotNotes;
};

// A method without runs (--methods) shows "-", never "> budget".
constexpr long long kNoRuns = -2;

// One task's runs as curves: each method's minimum envelope over seeds and what the tables read
// off it.
struct TaskCurves {
  const TaskResult& r;
  double minInitial = std::numeric_limits<double>::infinity();
  LossCurve envelope[kApplicationMethodCount];
  long long toThreshold[kApplicationMethodCount];
  double threshold = 0.0;
  long long lbfgsbConverged = 0;

  explicit TaskCurves(const TaskResult& result) : r(result) {
    for (const ApplicationRun& run : r.runs)
      minInitial = std::min(minInitial, run.curve.loss.front());
    for (int m = 0; m < kApplicationMethodCount; ++m) {
      std::vector<LossCurve> curves;
      for (const ApplicationRun& run : r.runs)
        if (run.method == m) curves.push_back(run.curve);
      envelope[m] = minimumEnvelope(curves);
    }
    lbfgsbConverged = converged(0);
    threshold = kThresholdFraction * minInitial;
    for (int m = 0; m < kApplicationMethodCount; ++m)
      toThreshold[m] = envelope[m].loss.empty() ? kNoRuns : stepsToReach(envelope[m], threshold);
  }
  double finalLoss(int m) const {
    return envelope[m].loss.empty() ? std::numeric_limits<double>::quiet_NaN()
                                    : envelope[m].loss.back();
  }
  long long converged(int m) const {
    return envelope[m].loss.empty() ? kNoRuns : convergenceSteps(envelope[m], minInitial);
  }
  std::string stepsText(long long s) const {
    return s == kNoRuns ? "-" : s < 0 ? "> " + std::to_string(r.budget) : std::to_string(s);
  }
  // The share of the pass's backward steps whose iterative solve converged (Table 3).
  std::string iterConverged() const {
    const PassTiming& t = r.timing;
    return t.measured && t.backwardSolves > 0
               ? formatNumber(100.0 * (t.backwardSolves - t.notConverged) / t.backwardSolves, 4)
               : "-";
  }
};

// DiffCloth Table 2: final losses and losses at L-BFGS-B's convergence step count.
void addLossRow(const TaskCurves& k, BenchTable& losses) {
  const TaskResult& r = k.r;
  const double minInitial = k.minInitial;
  const LossCurve* envelope = k.envelope;
  const long long lbfgsbConverged = k.lbfgsbConverged;
  const auto finalLoss = [&](int m) { return k.finalLoss(m); };
  losses.add({r.task->name, std::to_string(r.parameters), std::to_string(r.seeds),
              std::to_string(r.budget), formatNumber(minInitial, 4),
              percent(finalLoss(0), minInitial), percent(finalLoss(1), minInitial),
              percent(lossAt(envelope[1], lbfgsbConverged), minInitial),
              percent(finalLoss(2), minInitial),
              percent(lossAt(envelope[2], lbfgsbConverged), minInitial)});
}

// DiffCloth Table 3 and Fig. 4: steps to converge and to the threshold, speedups (also plotted
// against the parameter count).
void addStepRow(const TaskCurves& k, BenchTable& steps, std::vector<PlotSeries>& speedup) {
  const TaskResult& r = k.r;
  const long long* toThreshold = k.toThreshold;
  const double threshold = k.threshold;
  const auto converged = [&](int m) { return k.converged(m); };
  const auto stepsText = [&](long long s) { return k.stepsText(s); };
  std::string speedupText[2];
  for (int m = 1; m < kApplicationMethodCount; ++m) {
    if (toThreshold[0] < 0 || toThreshold[m] == kNoRuns) {
      speedupText[m - 1] = "-";
    } else if (toThreshold[m] < 0) {
      speedupText[m - 1] = "> " + formatNumber(double(r.budget) / toThreshold[0], 3);
    } else {
      const double ratio = double(toThreshold[m]) / toThreshold[0];
      speedupText[m - 1] = formatNumber(ratio, 3);
      speedup[m - 1].x.push_back(r.parameters);
      speedup[m - 1].y.push_back(ratio);
    }
  }
  steps.add({r.task->name, std::to_string(r.parameters), formatNumber(threshold, 3),
             stepsText(converged(0)), stepsText(converged(1)), stepsText(converged(2)),
             stepsText(toThreshold[0]), stepsText(toThreshold[1]), stepsText(toThreshold[2]),
             speedupText[0], speedupText[1]});
}

// DiffCloth Table 4: seconds per pass, and the runs' own seconds.
void addPassRow(const TaskCurves& k, BenchTable& passes) {
  const TaskResult& r = k.r;
  const std::string iterConverged = k.iterConverged();
  const PassTiming& t = r.timing;
  double lbfgsbSeconds = 0.0, runSeconds = 0.0;
  std::size_t lbfgsbEvaluations = 0;
  for (const ApplicationRun& run : r.runs) {
    runSeconds += run.seconds;
    if (run.method == 0) lbfgsbSeconds += run.seconds, lbfgsbEvaluations += run.curve.steps.size();
  }
  passes.add({r.task->name, std::to_string(3 * r.garmentVertices), std::to_string(t.steps),
              formatNumber(t.timeStep, 4),
              t.measured ? formatNumber(t.forwardSeconds, 3) : "failed: " + t.failure,
              t.measured ? formatNumber(t.backwardSeconds, 3) : "-", formatNumber(t.cpuSeconds, 3),
              iterConverged, std::to_string(t.unconvergedForwardSteps),
              t.measured ? formatNumber(t.adjointGrowth, 3) : "-",
              lbfgsbEvaluations ? formatNumber(lbfgsbSeconds / lbfgsbEvaluations, 3) : "-",
              formatNumber(runSeconds, 4)});
}

// This comparison's figures above DiffCloth's published ones, for the tasks the paper has.
void addPaperRows(const TaskCurves& k, BenchTable& beside) {
  const TaskResult& r = k.r;
  const PassTiming& t = r.timing;
  const double minInitial = k.minInitial;
  const LossCurve* envelope = k.envelope;
  const long long lbfgsbConverged = k.lbfgsbConverged;
  const std::string iterConverged = k.iterConverged();
  const auto finalLoss = [&](int m) { return k.finalLoss(m); };
  const auto converged = [&](int m) { return k.converged(m); };
  const auto stepsText = [&](long long s) { return k.stepsText(s); };
  if (const paper::PublishedTaskFigures* p = paper::publishedFigures(r.task->name)) {
    const auto ratio = [](long long a, long long b) {
      return a > 0 && b > 0 ? formatNumber(double(a) / double(b), 3) : std::string("-");
    };
    beside.add({r.task->name, "Weft", std::to_string(r.parameters), std::to_string(r.seeds),
                percent(finalLoss(0), minInitial), percent(finalLoss(1), minInitial),
                percent(lossAt(envelope[1], lbfgsbConverged), minInitial),
                percent(finalLoss(2), minInitial),
                percent(lossAt(envelope[2], lbfgsbConverged), minInitial), stepsText(converged(0)),
                stepsText(converged(1)), stepsText(converged(2)), ratio(converged(1), converged(0)),
                iterConverged, t.measured ? formatNumber(t.forwardSeconds, 3) : "-",
                t.measured ? formatNumber(t.backwardSeconds, 3) : "-"});
    beside.add({p->title, "DiffCloth", std::to_string(p->parameters), std::to_string(p->seeds),
                formatNumber(p->finalPercent[0], 4), formatNumber(p->finalPercent[1], 4),
                formatNumber(p->equalStepPercent[0], 4), formatNumber(p->finalPercent[2], 4),
                formatNumber(p->equalStepPercent[1], 4), std::to_string(p->convergenceSteps[0]),
                std::to_string(p->convergenceSteps[1]), std::to_string(p->convergenceSteps[2]),
                ratio(p->convergenceSteps[1], p->convergenceSteps[0]),
                formatNumber(p->iterativeConvergedPercent, 4), formatNumber(p->forwardSeconds, 4),
                formatNumber(p->backwardSeconds, 4)});
  }
}

// The aim (SpeedupAim.h): each envelope's steps to the paper's L-BFGS-B loss.
void addAimRow(const TaskCurves& k, BenchTable& aims) {
  const TaskResult& r = k.r;
  const double minInitial = k.minInitial;
  const LossCurve* envelope = k.envelope;
  const auto stepsText = [&](long long s) { return k.stepsText(s); };
  {
    const paper::PublishedTaskFigures* p = paper::publishedFigures(r.task->name);
    const bool napkin = std::string(r.task->name).rfind("napkin_", 0) == 0;
    if ((p || napkin) && !envelope[0].loss.empty() && !envelope[1].loss.empty()) {
      const double target = p ? p->finalPercent[0] / 100.0 * minInitial : kFig4SpeedupLoss;
      long long reach[kApplicationMethodCount];
      for (int m = 0; m < kApplicationMethodCount; ++m)
        reach[m] = envelope[m].loss.empty() ? kNoRuns : stepsToReach(envelope[m], target);
      const SpeedupAim aim = judgeSpeedupAim(reach[0], reach[1], r.budget);
      aims.add({r.task->name,
                p ? "paper's L-BFGS-B " + formatNumber(p->finalPercent[0], 4) + " %"
                  : "Fig. 4 loss " + formatNumber(kFig4SpeedupLoss, 3),
                formatNumber(target, 4), stepsText(reach[0]), stepsText(reach[1]),
                stepsText(reach[2]),
                std::isnan(aim.ratio) ? std::string("-")
                                      : (aim.lowerBound ? "> " : "") + formatNumber(aim.ratio, 3),
                aim.text});
    }
  }
}

// DiffCloth Tables 5-6 (every seed), and for tasks with handles and obstacles how deep each run's
// best point puts a handle target inside one.
void addSeedRows(const TaskResult& r, BenchTable& perSeed, BenchTable& handles) {
  for (int seed = 1; seed <= r.seeds; ++seed) {
    const ApplicationRun* bySeed[kApplicationMethodCount] = {nullptr, nullptr, nullptr};
    for (const ApplicationRun& run : r.runs)
      if (run.seed == seed) bySeed[run.method] = &run;
    if (!bySeed[0] && !bySeed[1] && !bySeed[2]) continue;
    const ApplicationRun* any = bySeed[0] ? bySeed[0] : bySeed[1] ? bySeed[1] : bySeed[2];
    const double initial = any->curve.loss.front();
    std::vector<std::string> row = {r.task->name, std::to_string(seed), formatNumber(initial, 4)};
    std::vector<std::string> finals, percents, conv, walls;
    for (int m = 0; m < kApplicationMethodCount; ++m) {
      if (!bySeed[m]) {
        finals.push_back("-"), percents.push_back("-"), conv.push_back("-"), walls.push_back("-");
        continue;
      }
      const LossCurve best = minimumEnvelope({bySeed[m]->curve});
      finals.push_back(formatNumber(best.loss.back(), 4));
      percents.push_back(percent(best.loss.back(), initial));
      conv.push_back(std::to_string(convergenceSteps(best, initial)));
      walls.push_back(formatNumber(bySeed[m]->seconds, 3));
    }
    for (const auto* group : {&finals, &percents, &conv, &walls})
      row.insert(row.end(), group->begin(), group->end());
    perSeed.add(row);
    if (r.handles) {
      std::vector<std::string> depths = {r.task->name, std::to_string(seed)};
      for (int m = 0; m < kApplicationMethodCount; ++m)
        depths.push_back(bySeed[m] ? formatNumber(1e3 * bySeed[m]->handleDepth, 3) : "-");
      handles.add(depths);
    }
  }
}

// Fig. 4 bottom left: the minimum envelope over seeds against steps.
void plotTaskLosses(const TaskCurves& k, StagedDirectory& out, std::vector<std::string>& notes) {
  const TaskResult& r = k.r;
  const LossCurve* envelope = k.envelope;
  const double minInitial = k.minInitial;
  std::vector<PlotSeries> plot;
  for (int m = 0; m < kApplicationMethodCount; ++m) {
    PlotSeries s{kApplicationMethods[m].title, {}, {}, "steps"};
    for (std::size_t i = 0; i < envelope[m].steps.size(); ++i)
      s.x.push_back(static_cast<double>(envelope[m].steps[i])), s.y.push_back(envelope[m].loss[i]);
    plot.push_back(std::move(s));
  }
  std::string reason;
  if (!plotSeries(
          out.file(std::string("loss_") + r.task->name + ".png"),
          std::string(r.task->name) + ": minimum loss over " + std::to_string(r.seeds) + " seed(s)",
          "simulated steps (L-BFGS-B: forward + backward; ES: forward)", "loss", plot, false,
          minInitial > 0.0, reason))
    notes.push_back(reason);
}

Tables tabulate(const Comparison& c, StagedDirectory& out) {
  Tables tables;
  for (const TaskResult& r : c.results)
    for (int seed = 1; seed <= r.seeds; ++seed)
      for (int m = 0; m < kApplicationMethodCount; ++m)
        for (const ApplicationRun& run : r.runs)
          if (run.seed == seed && run.method == m)
            for (const auto& row : run.rows) tables.csv.add(row);
  for (const TaskResult& r : c.results) {
    const TaskCurves k(r);
    addLossRow(k, tables.losses);
    addPassRow(k, tables.passes);
    addPaperRows(k, tables.beside);
    addAimRow(k, tables.aims);
    addStepRow(k, tables.steps, tables.speedup);
    addSeedRows(r, tables.perSeed, tables.handles);
    plotTaskLosses(k, out, tables.plotNotes);
  }
  std::vector<PlotSeries>& speedup = tables.speedup;
  std::vector<std::string>& plotNotes = tables.plotNotes;
  if (!speedup[0].x.empty() || !speedup[1].x.empty()) {
    std::string reason;
    if (!plotSeries(out.file("speedup.png"),
                    "Steps to reach 1% of the minimum initial loss, relative to L-BFGS-B",
                    "parameters", "speedup of L-BFGS-B", speedup, true, false, reason))
      plotNotes.push_back(reason);
  }
  return tables;
}

// The runs (and their settings) go with the tables, so that a later --resume can extend them.
void copyRuns(const Comparison& c, StagedDirectory& out) {
  {
    std::error_code ec;
    fs::create_directories(out.file("runs"), ec);
    for (const auto& entry : fs::directory_iterator(c.store, ec))
      if (entry.is_regular_file() &&
          (entry.path().extension() == ".csv" || entry.path().filename() == "settings.json"))
        fs::copy_file(entry.path(), fs::path(out.file("runs")) / entry.path().filename(), ec);
    if (!ec && fs::is_directory(c.store + "/parameters"))
      fs::copy(c.store + "/parameters", out.file("runs/parameters"), fs::copy_options::recursive,
               ec);
    if (ec) throw InputError(out.file("runs"), "output", "cannot copy the runs: " + ec.message());
  }
}

// The paper-mesh scenes as run, each with its target beside it (the mesh stays where it is);
// returns the report's notes on them.
std::string writePaperScenes(const Comparison& c, StagedDirectory& out) {
  std::string meshNotes;
  for (const TaskResult& r : c.results) {
    if (!r.paperScene) {
      if (!c.options.paperMeshes.empty())
        meshNotes += "- " + std::string(r.task->name) + ": the task's own mesh (" +
                     std::to_string(r.garmentVertices) +
                     " vertices; no paper mesh for this task)\n";
      continue;
    }
    const paper::PaperScene& p = *r.paperScene;
    std::error_code ec;
    fs::create_directories(out.file("paper_scenes"), ec);
    nlohmann::json doc = p.document;
    if (!p.target.empty()) {
      const std::string local = fs::path(p.target).filename().string();
      fs::copy_file(p.target, out.file("paper_scenes/" + local), ec);
      if (ec) throw InputError(out.file("paper_scenes"), "output", "cannot copy " + p.target);
      for (const char* term : {"trajectory", "final"})
        if (doc["task"]["loss"].contains(term)) doc["task"]["loss"][term]["target"] = local;
    }
    writeFileAtomically(out.file("paper_scenes/" + std::string(r.task->name) + ".json"),
                        doc.dump(2) + "\n");
    std::string shifts;
    for (const paper::HandleShift& h : p.handleShifts)
      shifts += (shifts.empty() ? " Handle paths' later knots moved with their vertices: " : "; ") +
                h.path + " " + formatNumber(1e3 * h.distance, 3) + " mm";
    if (!shifts.empty()) shifts += ".";
    std::string remaps;
    for (const paper::IndexRemap& m : p.remaps)
      remaps += (remaps.empty() ? "" : "; ") + m.path + " " + std::to_string(m.original) + " -> " +
                std::to_string(m.count) + " vertices, farthest " +
                formatNumber(1000.0 * m.maxDistance, 3) + " mm";
    const paper::PaperMesh* pm = paper::paperMeshFor(r.task->name);
    meshNotes += "- " + std::string(r.task->name) + ": `" + p.meshFile + "` (" +
                 std::to_string(p.vertices) + " vertices, the task's own garment " +
                 std::to_string(p.originalVertices) + "), rotated (" +
                 formatNumber(p.rotateDeg.x(), 5) + ", " + formatNumber(p.rotateDeg.y(), 5) + ", " +
                 formatNumber(p.rotateDeg.z(), 5) + ") deg (" + pm->why + "), scaled by " +
                 formatNumber(p.scale, 6) + ", translated (" + formatNumber(p.translate.x(), 4) +
                 ", " + formatNumber(p.translate.y(), 4) + ", " + formatNumber(p.translate.z(), 4) +
                 ") m. Remapped: " + remaps + "." + shifts +
                 (p.target.empty() ? ""
                  : r.paperScene->document["task"]["loss"].contains("trajectory")
                      ? " Target motion recorded on this mesh from the scene's hidden values."
                      : " Target: this rest shape translated as the task's own target is.") +
                 " Scene: paper_scenes/" + r.task->name + ".json\n";
  }
  return meshNotes;
}

// applications.md: the setup, the build, the meshes and starts, then the tables.
void writeReport(const Comparison& c, const Tables& tables, const std::string& meshNotes,
                 double benchSeconds, StagedDirectory& out) {
  {
    std::string taskList;
    for (const TaskResult& r : c.results)
      taskList += (taskList.empty() ? "" : ",") + std::string(r.task->name);
    double runSeconds = 0.0;
    for (const TaskResult& r : c.results)
      for (const ApplicationRun& run : r.runs) runSeconds += run.seconds;
    const std::string setup =
        "Machine: " + machineDescription() + ", " + std::to_string(c.options.threads) +
        " thread(s) per run, " +
        std::to_string(std::min<int>(c.options.jobs, std::max<int>(1, c.newRuns))) +
        " run(s) at a time. " + describeSeeds(c.results) + ", " + formatNumber(benchSeconds, 4) +
        " s in this invocation (" + std::to_string(c.newRuns) + " run(s) made, " +
        std::to_string(c.resumedRuns) +
        " read back from stored run files; a run's wall s is its own). The runs' wall seconds add "
        "up to " +
        formatNumber(runSeconds, 4) + " s (" + formatNumber(runSeconds / 3600.0, 3) +
        " h), each measured while it ran. Each seed draws one "
        "starting point (uniform within a quarter of each "
        "parameter's box width "
        "around the scene's values; box widths capped at 2 optimiser units; a draw whose handle "
        "targets enter an obstacle is drawn again), shared by the three methods; "
        "the evolution strategies are also seeded with it. Every run has the same budget of "
        "simulated steps: "
        "L-BFGS-B pays a forward and a backward step per simulated step (2 x time.steps per "
        "evaluation), "
        "CMA-ES and the (1+1)-ES a forward step only (time.steps per evaluation). Losses are the "
        "minimum "
        "envelope over seeds of each run's best loss so far (DiffCloth Sec. 5.2).";
    std::ofstream md(out.file("applications.md"));
    md << "# Gradient-based vs gradient-free optimisation (weft bench applications)\n\n"
       << "Tasks: " << taskList << ". " << setup << "\n\n";
    {
      // Which sources made the runs: checked equal on --resume (checkStoredSettings) when both
      // builds are known, but for the commit itself.
      const nlohmann::json& current = c.options.build;
      const std::string now = describeBuild(current);
      md << "Build: ";
      if (c.storedBuild.is_null())
        md << "the stored runs carry no build record (made before builds were recorded); tables "
              "written by "
           << now;
      else if (!isKnownBuild(c.storedBuild) || !isKnownBuild(current))
        md << "runs made by " << describeBuild(c.storedBuild) << "; tables written by " << now
           << " (not compared: no git record)";
      else if (c.storedBuild == current)
        md << "runs made by " << now;
      else if (!c.appDiffers.empty())
        md << "runs made by " << describeBuild(c.storedBuild) << "; tables written by " << now
           << " (same engine and assets; its app/weft/ differs, so it made no runs)";
      else
        md << "runs made by " << describeBuild(c.storedBuild) << "; tables written by " << now
           << " (same engine, CLI and assets)";
      md << ".\n\n";
    }
    if (c.options.paperMeshes.empty()) {
      md << "Meshes: every task on its own mesh (assets/meshes, or a grid).\n\n";
    } else {
      md << "## Meshes\n\nGarment tasks on the DiffCloth release's own garment meshes "
            "(`--paper-meshes "
         << c.options.paperMeshes
         << "`): each is rotated into the task's frame, scaled uniformly so that its largest "
            "bounding-box extent equals that of the task's own garment, and translated so that the "
            "two bounding-box centres coincide; every vertex list of the scene is remapped to the "
            "nearest vertices of the new mesh (repeats dropped, except keypoints).\n\n"
         << meshNotes << "\n";
    }
    {
      std::string redrawn, unavoidable;
      for (const TaskResult& r : c.results)
        for (std::size_t i = 0; i < r.starts.size(); ++i) {
          const std::string name = std::string(r.task->name) + " seed " + std::to_string(i + 1);
          if (!r.starts[i].handlesOutsideObstacles)
            unavoidable += (unavoidable.empty() ? "" : ", ") + name;
          else if (r.starts[i].draws > 1)
            redrawn += (redrawn.empty() ? "" : ", ") + name + " (" +
                       std::to_string(r.starts[i].draws) + " draws)";
        }
      md << "Starts: "
         << (redrawn.empty()
                 ? "every seed's first draw kept its handles outside the obstacles."
                 : "drawn again because a handle's targets entered an obstacle: " + redrawn + ".");
      if (!unavoidable.empty())
        md << " Handles inside an obstacle at the start (the scene's own values, or no draw out of "
           << kMaxStartingPointDraws << ", kept them out): " << unavoidable << ".";
      md << "\n\n";
    }
    {
      const OptimizerSettings defaults;
      if (c.options.lbfgsb.lbfgsbFirstStep != defaults.lbfgsbFirstStep ||
          c.options.lbfgsb.lbfgsbMinCurvatureStep != defaults.lbfgsbMinCurvatureStep)
        md << "L-BFGS-B: first trial step " << formatNumber(c.options.lbfgsb.lbfgsbFirstStep, 4)
           << " (optimiser coordinates; LBFGSpp's is 1), curvature pairs of steps shorter than "
           << formatNumber(c.options.lbfgsb.lbfgsbMinCurvatureStep, 4)
           << " left out (optim/LbfgsbOptimizer.h).\n\n";
    }
    tables.losses.writeMarkdown(
        md, "Loss reached (DiffCloth Table 2)",
        "Final %: the method's final loss as a percentage of the minimum initial "
        "loss over seeds. Equal-step %: "
        "the evolution strategy's loss after as many simulated steps as L-BFGS-B "
        "needed to converge (see below), "
        "as the same percentage.");
    md << "\n";
    tables.steps.writeMarkdown(
        md, "Steps to converge and to reach a threshold (DiffCloth Table 3, Fig. 4)",
        "Conv. steps: the first step count at which the envelope is within 1% of "
        "its total decrease (from the "
        "minimum initial loss) of its final value. Threshold: 1% of the minimum "
        "initial loss; steps to threshold "
        "is the first step count at which the envelope reaches it ('> budget': not "
        "within the budget). Speedup: "
        "the evolution strategy's steps to the threshold over L-BFGS-B's (Fig. 4 "
        "bottom right); '> x' when the "
        "strategy did not reach it within the budget.");
    md << "\n";
    tables.passes.writeMarkdown(
        md, "Seconds per pass (DiffCloth Table 4)",
        "One gradient evaluation at the scene's own parameter values, run by this invocation: "
        "forward s and backward s are the wall seconds of its forward pass and of its backward "
        "pass "
        "(adjoint and parameter gradient), CPU s the process CPU time of both; iter. conv. %: the "
        "share of its backward steps whose iterative solve converged without the direct fallback "
        "(Table 3). L-BFGS-B s per evaluation: the mean over the stored L-BFGS-B runs (forward and "
        "backward together, wall, under whatever load the runs met); runs' wall s: the sum over "
        "all the task's runs. DoF: 3 x the cloth's nodes. "
        "Adjoint growth: max |z_n| over the first nonzero |z_n| of the backward pass; the "
        "iterative "
        "solve's gradient error is of the order of tolerance x sqrt(growth) / 100 "
        "(diff/AdjointGrowth.h).");
    md << "\n";
    if (!tables.beside.rows().empty()) {
      tables.beside.writeMarkdown(
          md, "Beside the paper (DiffCloth Tables 2-4)",
          "Each task with a row in the paper: this comparison's figures (Weft) above the paper's "
          "(DiffCloth), same definitions as the tables above. The paper's losses are in its own "
          "units on its own scenes and meshes, its seconds are on an 80-core workstation and its "
          "steps to convergence are counted by an unstated rule; the percentages and step ratios "
          "are what carries over.");
      md << "\n";
    }
    if (!tables.aims.rows().empty()) {
      tables.aims.writeMarkdown(
          md, "Steps to the paper's loss (the issue's aim)",
          "The steps each method's envelope needs to reach the paper's L-BFGS-B final loss "
          "(Table 2: that percentage of this comparison's minimum initial loss; the Flying Napkin: "
          "Fig. 4's loss 0.01), '> budget' when it does not. The aim: L-BFGS-B reaches it with at "
          "most a fifth of CMA-ES's steps (a ratio of 5 or more; '> x' when CMA-ES does not reach "
          "it, x being the budget over L-BFGS-B's steps).");
      md << "\n";
    }
    tables.perSeed.writeMarkdown(
        md, "Every seed (DiffCloth Tables 5-6)",
        "Final: the run's best loss; %: of that seed's initial loss; conv. steps: as above, for "
        "the single run; wall s: the run's wall-clock seconds.");
    if (!tables.handles.rows().empty()) {
      md << "\n";
      tables.handles.writeMarkdown(
          md, "Handles at each run's best point",
          "Tasks whose handles move among obstacles: how deep the handle targets of each run's "
          "best evaluation go inside an obstacle (mm, its skin not counted; 0: they stay "
          "outside), sampled at every step's end time from the parameter values stored with "
          "the run (runs/parameters/). Not in the paper: a loss on the cloth alone can reward "
          "paths through the body, which no manipulator can follow.");
    }
    if (!md) throw InputError(out.file("applications.md"), "output", "write failed");
  }
}

}  // namespace

int runApplicationsBench(const ApplicationsBenchOptions& options, const std::string& outDir) {
  omp_set_num_threads(options.threads);
  const std::unique_ptr<WorkDistributor> serial =
      options.workers ? nullptr : makeSerialDistributor();
  WorkDistributor& workers = options.workers ? *options.workers : *serial;
  std::optional<StagedDirectory> staged;  // rank 0's
  std::string finalDir = outDir;
  while (finalDir.size() > 1 && finalDir.back() == '/') finalDir.pop_back();
  const auto benchStart = std::chrono::steady_clock::now();
  Comparison c{options, finalDir + ".partial", checkedTasks(options), {}, {}, {}, false, 0, 0, 0};
  c.loaded.resize(c.results.size());
  std::vector<Job> jobs;
  // Rank 0 opens (or creates) the store and reads it first; the others then read the same store
  // (as a resume: it exists now), so every rank finds the same runs still to make.
  workers.rootFirst([&] {
    if (workers.isRoot()) staged.emplace(outDir);
    c.storedRuns =
        openRunStore(c.store, finalDir + "/runs", options.resume || !workers.isRoot(),
                     runSettings(options), &c.storedBuild, &c.appDiffers, &c.storeCopied);
    jobs = readStoredRuns(c);
    refuseRunsOfAnotherApp(c, jobs);
  });
  if (c.storedRuns > 0 && workers.isRoot())
    std::fprintf(stderr, "applications: %d stored run(s) in %s\n", c.storedRuns, c.store.c_str());
  if (workers.size() > 1 && workers.isRoot())
    std::fprintf(stderr, "applications: %zu run(s) to make over %s\n", jobs.size(),
                 workers.description().c_str());
  makeRuns(c, jobs);
  if (!workers.isRoot()) return 0;
  StagedDirectory& out = *staged;
  measureTasks(c);

  const double benchSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - benchStart).count();
  Tables tables = tabulate(c, out);
  for (const std::string& note : tables.plotNotes)
    std::fprintf(stderr, "warning: %s\n", note.c_str());
  tables.csv.writeCsv(out.file("applications.csv"));
  tables.passes.writeCsv(out.file("passes.csv"));
  copyRuns(c, out);
  const std::string meshNotes = writePaperScenes(c, out);
  writeReport(c, tables, meshNotes, benchSeconds, out);
  out.commit();
  {
    std::error_code ec;
    fs::remove_all(c.store, ec);  // everything it held is in DIR/runs now
  }
  std::printf(
      "bench applications: %zu task(s) x %d method(s), %s, %d run(s) made, %d resumed, "
      "%s meshes, %.1f s -> %s/applications.{csv,md}, loss_<task>.png, runs/\n",
      c.results.size(),
      static_cast<int>(std::count(options.methods.begin(), options.methods.end(), true)),
      describeSeeds(c.results).c_str(), c.newRuns, c.resumedRuns,
      options.paperMeshes.empty() ? "own" : "paper", benchSeconds, outDir.c_str());
  return 0;
}

}  // namespace weft::bench
