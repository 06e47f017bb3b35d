// `weft bench backward`: DiffCloth Table 1. For the hanging napkin in wind ("Wind", no contact)
// and the ribbon sliding down a slope ("Slope", every node in contact, self-collision on) at
// several resolutions, one tightly converged forward run is recorded, then the backward pass of
// a trajectory loss is timed with each adjoint solver: direct sparse LU, fixed point (DiffCloth
// Eq. 30) and GMRES at relative tolerances 1e-4 and 1e-6, each with the fallback to the direct
// LU counted. Reports seconds (total, per step, linear solve vs rest), the fallback rate, the
// speedup over direct and the gradient's relative error against the direct solve's gradient.

#include "BackwardBench.h"

#include "BenchAssets.h"
#include "BenchTable.h"

#include <weft/core/ProcessCpuTime.h>
#include <weft/diff/AdjointSystem.h>
#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientErrorControl.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/Npy.h>
#include <weft/io/StagedDirectory.h>
#include <weft/scene/SceneLoader.h>

#include <Eigen/Core>

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <vector>

namespace weft::bench {
namespace {

// One of Table 1's scenes: its file, its steps (the paper's: Wind 200 at h = 1/90, Slope 300 at
// h = 1/100), the overrides that set an n x n resolution, the change that makes the target run
// differ, and the parameters differentiated.
struct BackwardCase {
  std::string name, file;
  int steps;
  std::function<std::vector<SceneOverride>(int)> resolution;
  std::function<SceneOverride(int)> targetChange;  // at n x n
  std::vector<std::string> parameters;
  // pd_tolerance (m/s^2) of the recorded forward run at n x n. Slope's is looser: the ribbon
  // slides over a metre, and the residual's round-off floor (about 1e-16 |P| |x| / (m h^2)) grows
  // with it and with the resolution: it passes 1e-8 at 24^2 (1.4e-8 from step 151 on) and 1e-7
  // at 48^2 (from step 164; 3.0e-7 at step 300: `weft simulate assets/scenes/slope.json --set
  // cloths.0.mesh.grid.resolution=[48,48] --set solver.method=newton --set
  // solver.pd_tolerance=1e-7`, stats.csv).
  std::function<double(int)> forwardTolerance;
};

// wind_reference.json's wind strength (N/m^2), set for 24^2 quads.
constexpr double kReferenceWindAt24 = 0.0905;

std::vector<BackwardCase> backwardCases(const std::vector<std::string>& names) {
  auto grid = [](int n) { return "[" + std::to_string(n) + "," + std::to_string(n) + "]"; };
  // The hanging napkin (its two top corners held at every resolution); the target run blows
  // harder.
  // `wind(n)`: the wind strength at n x n quads; the target blows 1.5 times as hard.
  auto hangingNapkin = [grid](const std::string& title, const std::string& scene,
                              std::function<double(int)> wind) {
    return BackwardCase{title,
                        assetFile(scene),
                        200,
                        [grid, wind](int n) {
                          return std::vector<SceneOverride>{
                              {"cloths.0.mesh.grid.resolution", grid(n)},
                              {"cloths.0.attachments.0.vertices", "[0," + std::to_string(n) + "]"},
                              {"wind.strength", formatNumber(wind(n), 8)}};
                        },
                        [wind](int n) {
                          return SceneOverride{"wind.strength", formatNumber(1.5 * wind(n), 8)};
                        },
                        {"wind.strength", "wind.direction.0", "cloths.0.material.stretch",
                         "cloths.0.material.density"},
                        [](int) { return 1e-8; }};
  };
  std::vector<BackwardCase> cases;
  for (const std::string& name : names) {
    if (name == "wind")
      cases.push_back(hangingNapkin("Wind", "scenes/wind.json", [](int) { return 1.0; }));
    else if (name == "wind_reference")
      // The same napkin with the DiffCloth authors' own parameters (a 6-unit cloth, stretch 100,
      // density 0.054): the scene their published backward timings come from. Their windScene
      // pushes every vertex with the same force, (0, 0.004, 0.004) N, at any resolution;
      // wind_reference.json spreads it as a pressure over an interior vertex's area at 24^2
      // quads, 0.0905 N/m^2 over (6/24 m)^2. At n^2 quads a vertex covers (6/n m)^2, so the same
      // force per vertex is 0.0905 (n/24)^2 N/m^2: 0.362 at 48^2 (49 x 49 vertices; at
      // DiffCloth's 48 x 48 vertices, 47^2 quads, it would be 0.347).
      cases.push_back(
          hangingNapkin("Wind (reference parameters)", "scenes/wind_reference.json",
                        [](int n) { return kReferenceWindAt24 * (n / 24.0) * (n / 24.0); }));
    else if (name == "slope")
      cases.push_back(
          {"Slope",
           assetFile("scenes/slope.json"),
           300,
           [grid](int n) {
             return std::vector<SceneOverride>{{"cloths.0.mesh.grid.resolution", grid(n)}};
           },
           [](int) {
             return SceneOverride{"obstacles.0.friction", "0.25"};
           },
           {"obstacles.0.friction", "cloths.0.material.stretch", "cloths.0.material.density"},
           [](int n) { return n >= 48 ? 5e-7 : 1e-7; }});
  }
  return cases;
}

double peakRssMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux: kilobytes
}

// `--calibrate`: what AdjointSystem::hessianFactorCost estimates from operation counts (the
// automatic preconditioner's exchange rate between a factorisation of the clamped Hessian H and
// iterations with P) against timings. For each scene and resolution, at the state of the middle
// step of a forward run: one factorClampedHessian with its symbolic analysis, the median of five
// more on the kept analysis, and the median of 30 GMRES iterations' work with P (a product with K
// and a solve with P). Contact (Delta R) is left out: it adds to both sides alike.
int calibrateFactorCost(const std::vector<BackwardCase>& cases, const std::vector<int>& resolutions,
                        int threads, StagedDirectory& out, const std::string& outDir) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  BenchTable table({"scene", "quads", "vertices", "first_factor_ms", "factor_ms", "iteration_ms",
                    "measured_iterations", "flop_ratio", "estimated_iterations",
                    "estimate_over_measured", "hessian_iteration_ms",
                    "measured_hessian_iteration_cost", "estimated_hessian_iteration_cost"});
  for (const BackwardCase& c : cases)
    for (int n : resolutions) {
      std::vector<SceneOverride> overrides = c.resolution(n);
      overrides.push_back({"time.steps", std::to_string(c.steps / 2 + 1)});
      const Scene scene = loadScene(c.file, overrides);
      std::fprintf(stderr, "calibrate: %s %dx%d forward run...\n", c.name.c_str(), n, n);
      const ForwardPass forward = runForwardPass(scene);
      AdjointSystem system(forward.trajectory.model);
      system.prepare(forward.trajectory.positions.back());
      if (!system.hasDeltaP()) continue;
      auto start = Clock::now();
      if (!system.factorClampedHessian()) {
        std::fprintf(stderr, "calibrate: %s %dx%d: the clamped Hessian did not factorise\n",
                     c.name.c_str(), n, n);
        continue;
      }
      const double first = since(start);
      std::vector<double> factor, iteration;
      for (int k = 0; k < 5; ++k) {
        start = Clock::now();
        system.factorClampedHessian();
        factor.push_back(since(start));
      }
      const int m = system.nodeCount();
      std::mt19937 random(1);
      std::normal_distribution<double> normal;
      NodeMatrix in(m, 3), product(m, 3);
      for (Eigen::Index i = 0; i < in.size(); ++i) in.data()[i] = normal(random);
      for (int k = 0; k < 30; ++k) {
        start = Clock::now();
        system.multiplyK(in, product);
        system.solveP(product);
        iteration.push_back(since(start));
      }
      std::vector<double> hessianIteration;
      for (int k = 0; k < 30; ++k) {
        start = Clock::now();
        system.multiplyK(in, product);
        system.solveClampedHessian(product);
        hessianIteration.push_back(since(start));
      }
      const double f = median(factor), it = median(iteration), hit = median(hessianIteration);
      const double measured = f / it, ratio = system.hessianFlopRatio();
      table.add({c.name, std::to_string(n), std::to_string(m), formatNumber(1e3 * first),
                 formatNumber(1e3 * f), formatNumber(1e3 * it, 3), formatNumber(measured, 3),
                 formatNumber(ratio, 3), formatNumber(system.hessianFactorCost(), 3),
                 formatNumber(system.hessianFactorCost() / measured, 3), formatNumber(1e3 * hit, 3),
                 formatNumber(hit / it, 3), formatNumber(system.hessianIterationCost(), 3)});
    }
  const std::string preamble =
      "AdjointSystem::hessianFactorCost against timings, " + std::to_string(threads) +
      " thread(s). Machine: " + machineDescription() +
      ". At the middle step of each scene's forward run: first_factor = the first "
      "factorClampedHessian "
      "(assembly, symbolic analysis, numeric factorisation), factor = the median of five more "
      "(analysis kept), "
      "iteration = the median of 30 products with K plus solves with P (one GMRES iteration's work "
      "with P). "
      "measured_iterations = factor / iteration; flop_ratio = the factorisation's flops over an "
      "iteration's; estimated_iterations = hessianFactorCost() = kFactorCostScale (" +
      formatNumber(AdjointSystem::kFactorCostScale, 3) +
      ") x sqrt(flop_ratio). hessian_iteration = the median of 30 products with K plus solves with "
      "the "
      "clamped Hessian's factor (one iteration's work with H); measured_hessian_iteration_cost = "
      "hessian_iteration / iteration, estimated_hessian_iteration_cost = hessianIterationCost() "
      "(operation "
      "counts), what the automatic preconditioner charges a run of Hessian steps per iteration.";
  table.writeCsv(out.file("calibrate.csv"));
  table.writeMarkdown(out.file("calibrate.md"),
                      "Factorisation cost of the clamped Hessian (weft bench backward --calibrate)",
                      preamble);
  out.commit();
  std::printf("bench backward --calibrate: %zu rows -> %s/calibrate.{csv,md}\n",
              table.rows().size(), outDir.c_str());
  return 0;
}

struct Method {
  std::string label, method;
  double tolerance;
  std::string preconditioner = "p";  // GMRES's (solver.backward.preconditioner)
  // solver.backward.accuracy: 0, one pass at `tolerance`; else the error-controlled passes
  // (diff/GradientErrorControl.h) starting from it, what every command's gradient does.
  double accuracy = 0.0;
};

}  // namespace

double factorCostScale() {
  return AdjointSystem::kFactorCostScale;
}

int runBackwardBench(const BackwardBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  const std::vector<BackwardCase> cases = backwardCases(
      options.scenes.empty() ? std::vector<std::string>{"wind", "slope"} : options.scenes);
  const int threads = options.threads;
  omp_set_num_threads(threads);
  StagedDirectory out(outDir);
  const std::vector<int> resolutions = !options.resolutions.empty() ? options.resolutions
                                       : quick                      ? std::vector<int>{12, 24}
                                                                    : std::vector<int>{12, 24, 48};
  if (options.calibrate) return calibrateFactorCost(cases, resolutions, threads, out, outDir);
  const std::vector<Method> methods = {
      {"direct", "direct", 1e-4},
      {"fixed_point 1e-4", "fixed_point", 1e-4},
      {"fixed_point 1e-6", "fixed_point", 1e-6},
      {"gmres 1e-4", "gmres", 1e-4},
      {"gmres 1e-6", "gmres", 1e-6},
      {"gmres+hessian 1e-4", "gmres", 1e-4, "hessian"},
      {"gmres+hessian 1e-6", "gmres", 1e-6, "hessian"},
      {"gmres+auto 1e-4", "gmres", 1e-4, "auto"},
      {"gmres+auto 1e-6", "gmres", 1e-6, "auto"},
      {"gmres+auto accuracy 1e-3 (default)", "gmres", 1e-4, "auto", 1e-3}};
  BenchTable table({"scene",
                    "quads",
                    "vertices",
                    "steps",
                    "method",
                    "tolerance",
                    "backward_s",
                    "ms_per_step",
                    "solve_ms_per_step",
                    "rest_ms_per_step",
                    "iterations_per_step",
                    "max_iterations",
                    "not_converged",
                    "fallbacks",
                    "fail_percent",
                    "speedup_vs_direct",
                    "gradient_rel_error",
                    "forward_ms_per_step",
                    "forward_unconverged",
                    "peak_rss_mb",
                    "delta_p_ms_per_step",
                    "delta_r_ms_per_step",
                    "fallback_ms_per_step",
                    "cpu_ms_per_step",
                    "cpu_speedup_vs_direct",
                    "adjoint_growth",
                    "hessian_iterations_per_step",
                    "hessian_factorizations",
                    "passes",
                    "error_estimate"});
  std::vector<PlotSeries> plot;

  const std::filesystem::path scratch = std::filesystem::temp_directory_path() /
                                        ("weft-bench-backward-" + std::to_string(::getpid()));
  std::filesystem::create_directories(scratch);

  for (const BackwardCase& c : cases) {
    const std::size_t firstSeries = plot.size();
    for (const Method& method : methods)
      plot.push_back(PlotSeries{c.name + " " + method.label, {}, {}});
    const int steps = quick ? 30 : c.steps;
    for (int n : resolutions) {
      std::vector<SceneOverride> base = c.resolution(n);
      base.push_back({"time.steps", std::to_string(steps)});

      // Target: the same scene with one parameter changed; the loss is the trajectory distance to
      // it.
      std::fprintf(stderr, "backward: %s %dx%d target run...\n", c.name.c_str(), n, n);
      std::vector<SceneOverride> perturbed = base;
      perturbed.push_back(c.targetChange(n));
      // The target is data only (the loss's reference), so it is simulated with the scene's own
      // solver settings: at 48^2 the tight solve would take minutes and change nothing measured.
      const ForwardPass target = runForwardPass(loadScene(c.file, perturbed));
      const std::string targetPath =
          (scratch / (c.name + "_target_" + std::to_string(n) + ".npy")).string();
      const int vertices = target.trajectory.nodeCount();
      {
        const std::vector<double> data = target.trajectory.flattenedPositions();
        writeNpy(targetPath,
                 {target.trajectory.positions.size(), static_cast<std::size_t>(vertices), 3},
                 data.data());
      }

      // A step whose residual cannot reach the tolerance (at the floor) stops after 1000 solves,
      // not the default 20000: past the floor the iterates only jitter, and at 48^2 the 20000
      // took hours. forward_unconverged counts those steps.
      const double forwardTolerance = c.forwardTolerance(n);
      Scene scene = withTightForwardSolver(loadScene(c.file, base), forwardTolerance, 1000);
      Task task;
      task.loss = nlohmann::json{{"trajectory", {{"target", targetPath}}}};
      scene.task = task;
      const TaskLoss loss(scene);
      const ParameterSet parameters = ParameterSet::fromPaths(scene, c.parameters);

      std::fprintf(stderr, "backward: %s %dx%d forward run...\n", c.name.c_str(), n, n);
      const auto fwdStart = std::chrono::steady_clock::now();
      const ForwardPass forward = runForwardPass(scene);
      const double forwardSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - fwdStart).count();
      if (forward.unconvergedSteps > 0)
        std::fprintf(stderr, "warning: %d forward steps did not reach %g\n",
                     forward.unconvergedSteps, forwardTolerance);

      Eigen::VectorXd directGradient;
      double directSeconds = 0.0, directCpuSeconds = 0.0;
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const Method& method = methods[m];
        std::fprintf(stderr, "backward: %s %dx%d %s\n", c.name.c_str(), n, n, method.label.c_str());
        BackwardSettings settings = scene.solver.backward;
        settings.method = method.method;
        settings.tolerance = method.tolerance;
        settings.preconditioner = method.preconditioner;
        settings.fallback = "direct";
        settings.accuracy = method.accuracy;
        const auto start = std::chrono::steady_clock::now();
        const double cpuStart = processCpuSeconds();
        const GradientResult g =
            backpropagateToAccuracy(forward.trajectory, loss, parameters, settings);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpuSeconds = processCpuSeconds() - cpuStart;
        if (m == 0)
          directGradient = g.gradient, directSeconds = seconds, directCpuSeconds = cpuSeconds;
        const double relError =
            (g.gradient - directGradient).norm() / std::max(directGradient.norm(), 1e-300);
        const AdjointSolverStats& s = g.solver;
        const double perStep = 1e3 * seconds / steps;
        const double solvePerStep = 1e3 * s.seconds / steps;
        const bool iterative = method.method != "direct";
        const std::string methodName =
            (method.preconditioner == "p" ? method.method
                                          : method.method + "+" + method.preconditioner) +
            (method.accuracy > 0.0 ? " accuracy " + formatNumber(method.accuracy, 1) : "");
        table.add(
            {c.name,
             std::to_string(n),
             std::to_string(vertices),
             std::to_string(steps),
             methodName,
             iterative ? formatNumber(method.tolerance, 1) : "-",
             formatNumber(seconds),
             formatNumber(perStep),
             formatNumber(solvePerStep),
             formatNumber(perStep - solvePerStep),
             iterative ? formatNumber(double(s.iterations) / std::max(1, s.solves)) : "-",
             std::to_string(s.maxIterations),
             std::to_string(s.notConverged),
             std::to_string(s.fallbacks),
             formatNumber(100.0 * s.fallbacks / std::max(1, s.solves), 3),
             formatNumber(directSeconds / seconds, 3),
             formatNumber(relError, 3),
             formatNumber(1e3 * forwardSeconds / steps),
             std::to_string(forward.unconvergedSteps),
             formatNumber(peakRssMegabytes()),
             formatNumber(1e3 * g.deltaPSeconds / steps),
             formatNumber(1e3 * g.deltaRSeconds / steps),
             formatNumber(1e3 * s.fallbackSeconds / steps),
             formatNumber(1e3 * cpuSeconds / steps),
             formatNumber(directCpuSeconds / cpuSeconds, 3),
             formatNumber(s.adjointGrowth, 3),
             iterative ? formatNumber(double(s.hessianIterations) / std::max(1, s.solves)) : "-",
             std::to_string(s.hessianFactorizations),
             std::to_string(g.error.passes),
             formatNumber(g.error.relative, 3)});
        plot[firstSeries + m].x.push_back(n);
        plot[firstSeries + m].y.push_back(perStep);
      }
    }
  }
  std::error_code ignored;
  std::filesystem::remove_all(scratch, ignored);

  const std::string machine = machineDescription();
  std::string names;
  for (const BackwardCase& c : cases)
    names += (names.empty() ? "" : ", ") + c.name + " (" + c.file + ")";
  const std::string preamble =
      "DiffCloth Table 1: " + names + ", " + std::to_string(threads) +
      " thread(s) (omp_get_max_threads = " + std::to_string(omp_get_max_threads()) +
      "). Machine: " + machine +
      ". Wind: the hanging napkin in wind, h = 1/90 s, no contact; loss = trajectory distance to "
      "the same scene "
      "at wind.strength 1.5; parameters wind.strength, wind.direction.0, stretch, density. Wind "
      "(reference "
      "parameters): the same with the DiffCloth authors' public scene parameters (6-unit cloth, "
      "stretch 100, "
      "density 0.054, constant wind; their force per vertex at every resolution, i.e. "
      "wind.strength 0.0905 (n/24)^2 N/m^2 at n x n quads: 0.0226 at 12^2, 0.0905 at 24^2, 0.362 "
      "at 48^2), target at 1.5 times its wind strength. Slope: the ribbon on "
      "the 20 degree plane, h = 1/100 s, every node in contact (slip), self-collision on; loss = "
      "trajectory "
      "distance to the same scene at friction 0.25; parameters obstacles.0.friction, stretch, "
      "density. One "
      "forward run per scene and resolution (Wind: Newton-PCG to 1e-8 m/s^2; Slope: the scene's "
      "Newton contact "
      "solve to 1e-7, 5e-7 from 48^2 on, above the round-off floor of the sliding ribbon's "
      "residual; at most "
      "1000 solves per step) is recorded once; forward_unconverged counts its steps that stopped "
      "at that cap. solve = "
      "time in the per-step adjoint linear solve (AdjointSolver, including any fallback), rest = "
      "the other "
      "backward work (Delta P, the contact Jacobians, parameter partials). Split of those: delta_p "
      "= preparing "
      "Delta P (the projections' derivatives at x_{n+1}; its products are inside the solve, which "
      "is "
      "matrix-free), delta_r = preparing the contact part Delta R (law Jacobians, frames, coupling "
      "LU), both "
      "part of rest; fallback = the direct LU after a failed iterative solve, part of solve. All "
      "these are "
      "wall-clock; cpu_ms_per_step is the process's CPU time for the same backward pass (one "
      "thread: the "
      "time it actually computed, without waiting for a shared core) and cpu_speedup_vs_direct its "
      "ratio "
      "to the direct row's. The target run (data only) uses the scene's own solver settings. fail "
      "% = steps where the iterative "
      "method did not converge within its cap (200 iterations) and fell back to the direct LU. "
      "gradient_rel_error = |g - g_direct| / |g_direct|. peak_rss_mb = the process's peak resident "
      "set "
      "(getrusage maxrss) after that row: cumulative over all rows so far. adjoint_growth = max "
      "|z_n| over "
      "the first nonzero |z_n| of the pass (diff/AdjointGrowth.h): an iterative solve's gradient "
      "error "
      "is of the order of tolerance x sqrt(adjoint_growth) / 100. hessian_iterations_per_step = of "
      "iterations_per_step, those preconditioned by the clamped Hessian; hessian_factorizations = "
      "its "
      "factorisations over the pass (gmres+hessian: one per step; gmres+auto: where it chose to). "
      "The accuracy row is what every command's gradient does (solver.backward.accuracy, "
      "diff/GradientErrorControl.h): passes from its tolerance down by 100 until two agree to "
      "1e-3; its times cover all its passes. passes = backward passes made; error_estimate = "
      "the gradient's estimated relative error (the accuracy row: its difference to the looser "
      "pass; one-pass rows: tolerance x sqrt(growth) / 100, or epsilon x growth for direct).";
  table.writeCsv(out.file("backward.csv"));
  table.writeMarkdown(out.file("backward.md"),
                      "Backward pass: adjoint solvers (weft bench backward)", preamble);
  std::string reason;
  if (!plotSeries(out.file("backward.png"), "Backward (Table 1): time per step vs resolution",
                  "quads per side", "backward ms per step", plot, true, true, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  std::printf("bench backward: %zu rows over %zu resolutions -> %s/backward.{csv,md,png}\n",
              table.rows().size(), resolutions.size(), outDir.c_str());
  return 0;
}

}  // namespace weft::bench
