// `weft bench applications [--tasks a,b] [--seeds N] [--budget STEPS] [--quick] [--out DIR]
//                          [--threads N]`: DiffCloth's comparison of gradient-based and
// gradient-free optimisation (Sec. 5.2 and Fig. 4, the Flying Napkin; Sec. 6, Tables 2-3;
// Appendix C, Tables 5-6). Every task scene is optimised by L-BFGS-B (adjoint gradients),
// CMA-ES and the (1+1)-ES (values alone) from the same random starting point per seed, each run
// with the same budget of simulated steps (a forward step 1, a backward step 1 more, as the
// paper counts them). Writes, staged, into DIR (default out/bench-applications):
//   applications.csv  task,method,seed,evaluation,steps,wall_s,loss: every evaluation of every run
//   applications.md   the Table 2 analogue (final loss and loss at L-BFGS-B's convergence step
//                     count, as % of the minimum initial loss), the Table 3 / Fig. 4 analogue
//                     (steps to converge and to reach a loss threshold, speedups) and the
//                     Tables 5-6 analogue (every seed)
//   loss_<task>.png   loss against steps, the minimum envelope over seeds (Fig. 4 bottom left)
//   speedup.png       speedup against the parameter count (Fig. 4 bottom right)

#include "../CommandLine.h"
#include "BenchAssets.h"
#include "BenchTable.h"
#include "LossEnvelope.h"

#include <weft/core/Error.h>
#include <weft/diff/ParameterSet.h>
#include <weft/io/StagedDirectory.h>
#include <weft/optim/Optimizer.h>
#include <weft/optim/SearchBox.h>
#include <weft/optim/SimulationObjective.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

namespace weft::cli {
namespace {

// The tasks, one line each: the name --tasks takes, the scene below assets/, and the budget of
// simulated steps per run (the same for every method), normally and under --quick.
struct ApplicationTask {
  const char* name;
  const char* scene;
  long long budget;
  long long quickBudget;
};
const ApplicationTask kTasks[] = {
    {"napkin_4x4", "scenes/napkin_4x4.json", 20000, 2500},
    {"napkin_5x5", "scenes/napkin_5x5.json", 20000, 2500},
    {"napkin_7x7", "scenes/napkin_7x7.json", 20000, 2500},
    {"napkin_10x10", "scenes/napkin_10x10.json", 20000, 2500},
    {"wind_sysid", "scenes/wind_sysid.json", 3000, 600},
    // Sec. 6.4 and 6.3 (Table 3: L-BFGS-B converged in 6800 and 2750 steps, the ES in up to
    // 24800 and 10000); quick: 6 and 6 gradient evaluations.
    {"flag", "scenes/flag.json", 7200, 1200},
    {"dress", "scenes/dress.json", 6000, 1500},
    // Sec. 6.1, the T-shirt (Table 3: L-BFGS-B converged in 4500 steps, the ES in about 50000): 10
    // gradient evaluations of its 250 steps, about 0.25 s of one core a step; quick: 2.
    {"tshirt", "scenes/tshirt.json", 5000, 1000},
    // Sec. 6.1-6.2 (Table 3: L-BFGS-B converged in 2450, 11200 and 17600 steps). The Sock's forward
    // contact solve does not converge once the sock reaches the foot (README, "Tasks").
    {"sphere_sysid", "scenes/sphere_sysid.json", 7000, 1400},
    {"hat", "scenes/hat.json", 12000, 1600},
    {"sock", "scenes/sock.json", 17600, 1600},
};
const char* const kQuickTask = "napkin_4x4";

struct Method {
  const char* name;   // makeOptimizer's
  const char* title;  // the paper's
};
const Method kMethods[] = {{"lbfgsb", "L-BFGS-B"}, {"cmaes", "CMA-ES"}, {"es1p1", "(1+1)-ES"}};
constexpr int kMethodCount = 3;

// "Steps to reach": the envelope at or below this fraction of the minimum initial loss (the
// paper's Fig. 4 uses an absolute 0.01 in its own loss units; a fraction carries over to tasks
// whose losses differ in scale).
constexpr double kThresholdFraction = 0.01;
// "Converged": the loss within this fraction of the total decrease of its final value (the paper
// counts steps "until convergence" without saying when; L-BFGS-B's own stop, a relative loss
// change of 1e-12, is reached only after a long tail of tiny gains).
constexpr double kConvergedFraction = 0.01;

struct Run {
  int method = 0;
  int seed = 0;
  LossCurve curve;
  double seconds = 0.0;
  std::string stop;
};

struct TaskResult {
  const ApplicationTask* task = nullptr;
  int parameters = 0;
  long long budget = 0;
  std::vector<Run> runs;
};

// Seed s's starting point, shared by every method (Table 2: "All methods start the optimization
// with the same initial random seed set"): uniform within a quarter of each variable's box width
// (SearchBox's width, capped for open boxes) on either side of the scene's values, projected
// into the box. Its own random stream, apart from the evolution strategies' (seeded with s too).
Eigen::VectorXd randomStart(const ParameterSpace& space, unsigned seed) {
  const Eigen::VectorXd z0 = space.toCoordinates(space.initialValues());
  const SearchBox box(z0, space.lowerCoordinates(), space.upperCoordinates());
  std::seed_seq sequence{seed, 0x5eedu};
  std::mt19937_64 random(sequence);
  std::uniform_real_distribution<double> uniform(-0.25, 0.25);
  Eigen::VectorXd u(z0.size());
  for (int i = 0; i < u.size(); ++i) u[i] = uniform(random);
  return box.repairedCoordinates(u);
}

std::vector<const ApplicationTask*> selectTasks(const CommandLine& cl, bool quick) {
  std::string known;
  for (const ApplicationTask& t : kTasks)
    known += (known.empty() ? "" : ", ") + std::string(t.name);
  const std::string list = cl.value("--tasks", quick ? kQuickTask : "");
  std::vector<const ApplicationTask*> out;
  if (list.empty()) {
    for (const ApplicationTask& t : kTasks) out.push_back(&t);
    return out;
  }
  std::stringstream items(list);
  for (std::string name; std::getline(items, name, ',');) {
    const ApplicationTask* found = nullptr;
    for (const ApplicationTask& t : kTasks)
      if (name == t.name) found = &t;
    if (!found) cl.fail("--tasks", "unknown task '" + name + "' (known: " + known + ")");
    if (std::find(out.begin(), out.end(), found) == out.end()) out.push_back(found);
  }
  if (out.empty())
    cl.fail("--tasks", "expects a comma-separated list of tasks (known: " + known + ")");
  return out;
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

}  // namespace

int applicationsBenchmark(const CommandLine& cl, const std::string& outDir) {
  const bool quick = cl.has("--quick");
  const std::vector<const ApplicationTask*> tasks = selectTasks(cl, quick);
  const int seeds = cl.integer("--seeds", quick ? 1 : 3, 1, 100);
  const int threads = cl.integer("--threads", 1, 1, 1024);
  omp_set_num_threads(threads);
  const double budgetOption = cl.number("--budget", 0.0);
  if (cl.has("--budget") &&
      !(budgetOption >= 1.0 && budgetOption <= 1e15 && std::floor(budgetOption) == budgetOption))
    cl.fail("--budget", "must be a positive whole number of simulated steps");
  StagedDirectory out(outDir);
  const auto benchStart = std::chrono::steady_clock::now();

  BenchTable csv({"task", "method", "seed", "evaluation", "steps", "wall_s", "loss"});
  std::vector<TaskResult> results;
  for (const ApplicationTask* task : tasks) {
    const std::string file = assetFile(task->scene);
    const Scene scene = loadScene(file, {});
    const ParameterSet parameters = ParameterSet::fromTask(scene);
    if (parameters.empty()) throw InputError(file, "task.parameters", "no parameters to optimise");
    const SimulationObjective probe(scene, parameters);  // the box and the starting values
    TaskResult result;
    result.task = task;
    result.parameters = parameters.size();
    result.budget = cl.has("--budget") ? static_cast<long long>(budgetOption)
                    : quick            ? task->quickBudget
                                       : task->budget;
    if (result.budget < probe.stepsPerEvaluation())
      cl.fail("--budget", "must allow at least one gradient evaluation of " +
                              std::string(task->name) + " (" +
                              std::to_string(probe.stepsPerEvaluation()) + " simulated steps)");
    for (int seed = 1; seed <= seeds; ++seed) {
      const Eigen::VectorXd start = randomStart(probe.space(), static_cast<unsigned>(seed));
      for (int m = 0; m < kMethodCount; ++m) {
        std::fprintf(stderr, "applications: %s, %s, seed %d...\n", task->name, kMethods[m].name,
                     seed);
        SimulationObjective objective(scene, parameters);
        OptimizerSettings settings;
        settings.budget = result.budget;
        settings.seed = static_cast<unsigned>(seed);
        std::unique_ptr<Optimizer> optimizer = makeOptimizer(kMethods[m].name, settings);
        Run run;
        run.method = m;
        run.seed = seed;
        try {
          run.stop = optimizer
                         ->minimize(objective, start, objective.space().lowerCoordinates(),
                                    objective.space().upperCoordinates())
                         .stopReason;
        } catch (const NumericalError& e) {
          // A sample the forward solver cannot simulate ends that run, not the benchmark.
          run.stop = std::string("numerical failure: ") + e.what();
          std::fprintf(stderr, "warning: %s, %s, seed %d: %s\n", task->name, kMethods[m].name, seed,
                       e.what());
        }
        for (const LogEntry& e : optimizer->log().entries()) {
          run.curve.steps.push_back(e.steps);
          run.curve.loss.push_back(e.loss);
          run.seconds = e.seconds;
          char wall[32];
          std::snprintf(wall, sizeof wall, "%.6f", e.seconds);
          csv.add({task->name, kMethods[m].name, std::to_string(seed), std::to_string(e.evaluation),
                   std::to_string(e.steps), wall, formatNumber(e.loss, 17)});
        }
        if (!run.curve.steps.empty()) result.runs.push_back(std::move(run));
      }
    }
    results.push_back(std::move(result));
  }
  const double benchSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - benchStart).count();

  BenchTable losses({"task", "parameters", "seeds", "budget (steps)", "min initial loss",
                     "L-BFGS-B final %", "CMA-ES final %", "CMA-ES equal-step %",
                     "(1+1)-ES final %", "(1+1)-ES equal-step %"});
  BenchTable steps({"task", "parameters", "threshold", "L-BFGS-B conv. steps", "CMA-ES conv. steps",
                    "(1+1)-ES conv. steps", "L-BFGS-B steps to threshold",
                    "CMA-ES steps to threshold", "(1+1)-ES steps to threshold", "CMA-ES speedup",
                    "(1+1)-ES speedup"});
  BenchTable perSeed({"task", "seed", "initial loss", "L-BFGS-B final", "CMA-ES final",
                      "(1+1)-ES final", "L-BFGS-B %", "CMA-ES %", "(1+1)-ES %",
                      "L-BFGS-B conv. steps", "CMA-ES conv. steps", "(1+1)-ES conv. steps",
                      "L-BFGS-B wall s", "CMA-ES wall s", "(1+1)-ES wall s"});
  // Points, not lines: the tasks are not one family (the napkins and wind_sysid share an axis).
  std::vector<PlotSeries> speedup = {{"CMA-ES / L-BFGS-B", {}, {}, "points pointsize 2"},
                                     {"(1+1)-ES / L-BFGS-B", {}, {}, "points pointsize 2"}};
  std::vector<std::string> plotNotes;
  for (const TaskResult& r : results) {
    double minInitial = std::numeric_limits<double>::infinity();
    for (const Run& run : r.runs) minInitial = std::min(minInitial, run.curve.loss.front());
    LossCurve envelope[kMethodCount];
    for (int m = 0; m < kMethodCount; ++m) {
      std::vector<LossCurve> curves;
      for (const Run& run : r.runs)
        if (run.method == m) curves.push_back(run.curve);
      envelope[m] = minimumEnvelope(curves);
    }
    const auto finalLoss = [&](int m) {
      return envelope[m].loss.empty() ? std::numeric_limits<double>::quiet_NaN()
                                      : envelope[m].loss.back();
    };
    const auto converged = [&](int m) {
      return envelope[m].loss.empty() ? -1 : convergenceSteps(envelope[m], minInitial);
    };
    const long long lbfgsbConverged = converged(0);
    const double threshold = kThresholdFraction * minInitial;
    long long toThreshold[kMethodCount];
    for (int m = 0; m < kMethodCount; ++m)
      toThreshold[m] = envelope[m].loss.empty() ? -1 : stepsToReach(envelope[m], threshold);
    const auto stepsText = [&](long long s) {
      return s < 0 ? "> " + std::to_string(r.budget) : std::to_string(s);
    };
    std::string speedupText[2];
    for (int m = 1; m < kMethodCount; ++m) {
      if (toThreshold[0] < 0) {
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
    losses.add({r.task->name, std::to_string(r.parameters), std::to_string(seeds),
                std::to_string(r.budget), formatNumber(minInitial, 4),
                percent(finalLoss(0), minInitial), percent(finalLoss(1), minInitial),
                percent(lossAt(envelope[1], lbfgsbConverged), minInitial),
                percent(finalLoss(2), minInitial),
                percent(lossAt(envelope[2], lbfgsbConverged), minInitial)});
    steps.add({r.task->name, std::to_string(r.parameters), formatNumber(threshold, 3),
               stepsText(converged(0)), stepsText(converged(1)), stepsText(converged(2)),
               stepsText(toThreshold[0]), stepsText(toThreshold[1]), stepsText(toThreshold[2]),
               speedupText[0], speedupText[1]});

    for (int seed = 1; seed <= seeds; ++seed) {
      const Run* bySeed[kMethodCount] = {nullptr, nullptr, nullptr};
      for (const Run& run : r.runs)
        if (run.seed == seed) bySeed[run.method] = &run;
      if (!bySeed[0] && !bySeed[1] && !bySeed[2]) continue;
      const Run* any = bySeed[0] ? bySeed[0] : bySeed[1] ? bySeed[1] : bySeed[2];
      const double initial = any->curve.loss.front();
      std::vector<std::string> row = {r.task->name, std::to_string(seed), formatNumber(initial, 4)};
      std::vector<std::string> finals, percents, conv, walls;
      for (int m = 0; m < kMethodCount; ++m) {
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
    }

    std::vector<PlotSeries> plot;
    for (int m = 0; m < kMethodCount; ++m) {
      PlotSeries s{kMethods[m].title, {}, {}, "steps"};
      for (std::size_t i = 0; i < envelope[m].steps.size(); ++i)
        s.x.push_back(static_cast<double>(envelope[m].steps[i])),
            s.y.push_back(envelope[m].loss[i]);
      plot.push_back(std::move(s));
    }
    std::string reason;
    if (!plotSeries(
            out.file(std::string("loss_") + r.task->name + ".png"),
            std::string(r.task->name) + ": minimum loss over " + std::to_string(seeds) + " seed(s)",
            "simulated steps (L-BFGS-B: forward + backward; ES: forward)", "loss", plot, false,
            minInitial > 0.0, reason))
      plotNotes.push_back(reason);
  }
  if (!speedup[0].x.empty() || !speedup[1].x.empty()) {
    std::string reason;
    if (!plotSeries(out.file("speedup.png"),
                    "Steps to reach 1% of the minimum initial loss, relative to L-BFGS-B",
                    "parameters", "speedup of L-BFGS-B", speedup, true, false, reason))
      plotNotes.push_back(reason);
  }
  for (const std::string& note : plotNotes) std::fprintf(stderr, "warning: %s\n", note.c_str());

  csv.writeCsv(out.file("applications.csv"));
  {
    std::string taskList;
    for (const TaskResult& r : results)
      taskList += (taskList.empty() ? "" : ",") + std::string(r.task->name);
    const std::string setup =
        "Machine: " + machineDescription() + ", " + std::to_string(threads) + " thread(s). " +
        std::to_string(seeds) + " seed(s) per task (1.." + std::to_string(seeds) + "), " +
        formatNumber(benchSeconds, 4) +
        " s in all. Each seed draws one starting point (uniform within a quarter of each "
        "parameter's box width "
        "around the scene's values; box widths capped at 2 optimiser units), shared by the three "
        "methods; "
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
    losses.writeMarkdown(md, "Loss reached (DiffCloth Table 2)",
                         "Final %: the method's final loss as a percentage of the minimum initial "
                         "loss over seeds. Equal-step %: "
                         "the evolution strategy's loss after as many simulated steps as L-BFGS-B "
                         "needed to converge (see below), "
                         "as the same percentage.");
    md << "\n";
    steps.writeMarkdown(md,
                        "Steps to converge and to reach a threshold (DiffCloth Table 3, Fig. 4)",
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
    perSeed.writeMarkdown(
        md, "Every seed (DiffCloth Tables 5-6)",
        "Final: the run's best loss; %: of that seed's initial loss; conv. steps: as above, for "
        "the single run; wall s: the run's wall-clock seconds.");
    if (!md) throw InputError(out.file("applications.md"), "output", "write failed");
  }
  out.commit();
  std::printf(
      "bench applications: %zu task(s) x %d methods x %d seed(s), %.1f s -> "
      "%s/applications.{csv,md}, "
      "loss_<task>.png\n",
      results.size(), kMethodCount, seeds, benchSeconds, outDir.c_str());
  return 0;
}

}  // namespace weft::cli
