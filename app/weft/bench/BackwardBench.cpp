// `weft bench backward`: DiffCloth Table 1 for the Wind scene. For the hanging napkin in wind at
// several resolutions, one tightly converged forward run is recorded, then the backward pass of a
// trajectory loss is timed with each adjoint solver: direct sparse LU, fixed point (DiffCloth
// Eq. 30) and GMRES at relative tolerances 1e-4 and 1e-6, each with the fallback to the direct
// LU counted. Reports seconds (total, per step, linear solve vs rest), the fallback rate, the
// speedup over direct and the gradient's relative error against the direct solve's gradient.

#include "BenchTable.h"
#include "../CommandLine.h"
#include "../Commands.h"

#include <weft/diff/Backpropagation.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/ParameterSet.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/Npy.h>
#include <weft/io/StagedDirectory.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace weft::cli {
namespace {

std::string defaultScene() {
  if (std::filesystem::exists("assets/scenes/wind.json")) return "assets/scenes/wind.json";
  return std::string(WEFT_ASSET_DIR) + "/scenes/wind.json";
}

double peakRssMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux: kilobytes
}

struct Method {
  std::string label, method;
  double tolerance;
};

}  // namespace

int backwardBenchmark(const CommandLine& cl, const std::string& outDir) {
  const bool quick = cl.has("--quick");
  const std::string file = cl.value("--scene", defaultScene());
  const int threads = cl.integer("--threads", 1, 1, 1024);
  omp_set_num_threads(threads);
  StagedDirectory out(outDir);
  const std::vector<int> resolutions = benchResolutions(cl, quick ? std::vector<int>{12, 24} : std::vector<int>{12, 24, 48});
  const int steps = quick ? 30 : 200;
  const double forwardTolerance = 1e-8;  // m/s^2, Newton-PCG
  const std::vector<Method> methods = {{"direct", "direct", 1e-4},
                                       {"fixed_point 1e-4", "fixed_point", 1e-4},
                                       {"fixed_point 1e-6", "fixed_point", 1e-6},
                                       {"gmres 1e-4", "gmres", 1e-4},
                                       {"gmres 1e-6", "gmres", 1e-6}};
  const std::vector<std::string> paramPaths = {"wind.strength", "wind.direction.0", "cloths.0.material.stretch",
                                               "cloths.0.material.density"};
  BenchTable table({"quads", "vertices", "steps", "method", "tolerance", "backward_s", "ms_per_step",
                    "solve_ms_per_step", "rest_ms_per_step", "iterations_per_step", "max_iterations",
                    "not_converged", "fallbacks", "fail_percent", "speedup_vs_direct", "gradient_rel_error",
                    "forward_ms_per_step", "peak_rss_mb"});
  std::vector<PlotSeries> plot(methods.size());
  for (std::size_t m = 0; m < methods.size(); ++m) plot[m].title = methods[m].label;

  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("weft-bench-backward-" + std::to_string(::getpid()));
  std::filesystem::create_directories(scratch);

  for (int n : resolutions) {
    const std::vector<SceneOverride> base = {
        {"cloths.0.mesh.grid.resolution", "[" + std::to_string(n) + "," + std::to_string(n) + "]"},
        {"cloths.0.attachments.0.vertices", "[0," + std::to_string(n) + "]"},
        {"time.steps", std::to_string(steps)}};
    const int vertices = (n + 1) * (n + 1);

    // Target: the same scene in a stronger wind; the loss is the trajectory distance to it.
    std::fprintf(stderr, "backward: %dx%d target run...\n", n, n);
    std::vector<SceneOverride> perturbed = base;
    perturbed.push_back({"wind.strength", "1.5"});
    const ForwardPass target = runForwardPass(withTightForwardSolver(loadScene(file, perturbed), forwardTolerance));
    const std::string targetPath = (scratch / ("target_" + std::to_string(n) + ".npy")).string();
    {
      const auto& states = target.trajectory.positions;
      std::vector<double> data;
      data.reserve(states.size() * vertices * 3);
      for (const NodeMatrix& x : states)
        for (int v = 0; v < x.rows(); ++v)
          for (int c = 0; c < 3; ++c) data.push_back(x(v, c));
      writeNpy(targetPath, {states.size(), static_cast<std::size_t>(vertices), 3}, data.data());
    }

    Scene scene = withTightForwardSolver(loadScene(file, base), forwardTolerance);
    Task task;
    task.loss = nlohmann::json{{"trajectory", {{"target", targetPath}}}};
    scene.task = task;
    const TaskLoss loss(scene);
    const ParameterSet parameters = ParameterSet::fromPaths(scene, paramPaths);

    std::fprintf(stderr, "backward: %dx%d forward run...\n", n, n);
    const auto fwdStart = std::chrono::steady_clock::now();
    const ForwardPass forward = runForwardPass(scene);
    const double forwardSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - fwdStart).count();
    if (forward.unconvergedSteps > 0)
      std::fprintf(stderr, "warning: %d forward steps did not reach %g\n", forward.unconvergedSteps, forwardTolerance);

    Eigen::VectorXd directGradient;
    double directSeconds = 0.0;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const Method& method = methods[m];
      std::fprintf(stderr, "backward: %dx%d %s\n", n, n, method.label.c_str());
      BackwardSettings settings = scene.solver.backward;
      settings.method = method.method;
      settings.tolerance = method.tolerance;
      settings.fallback = "direct";
      const auto start = std::chrono::steady_clock::now();
      const GradientResult g = backpropagate(scene, forward.trajectory, loss, parameters, settings);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (m == 0) directGradient = g.gradient, directSeconds = seconds;
      const double relError = (g.gradient - directGradient).norm() / std::max(directGradient.norm(), 1e-300);
      const AdjointSolverStats& s = g.solver;
      const double perStep = 1e3 * seconds / steps;
      const double solvePerStep = 1e3 * s.seconds / steps;
      const bool iterative = method.method != "direct";
      table.add({std::to_string(n), std::to_string(vertices), std::to_string(steps), method.method,
                 iterative ? formatNumber(method.tolerance, 1) : "-", formatNumber(seconds), formatNumber(perStep),
                 formatNumber(solvePerStep), formatNumber(perStep - solvePerStep),
                 iterative ? formatNumber(double(s.iterations) / std::max(1, s.solves)) : "-",
                 std::to_string(s.maxIterations), std::to_string(s.notConverged), std::to_string(s.fallbacks),
                 formatNumber(100.0 * s.fallbacks / std::max(1, s.solves), 3), formatNumber(directSeconds / seconds, 3),
                 formatNumber(relError, 3), formatNumber(1e3 * forwardSeconds / steps),
                 formatNumber(peakRssMegabytes())});
      plot[m].x.push_back(n);
      plot[m].y.push_back(perStep);
    }
  }
  std::error_code ignored;
  std::filesystem::remove_all(scratch, ignored);

  const std::string machine = machineDescription();
  const std::string preamble =
      "DiffCloth Table 1, Wind scene only: the hanging napkin in wind (" + file + "), h = 1/90 s, " +
      std::to_string(steps) + " steps, " + std::to_string(threads) + " thread(s) (omp_get_max_threads = " +
      std::to_string(omp_get_max_threads()) + "). Machine: " + machine +
      ". One forward run per resolution (Newton-PCG, tolerance 1e-8 m/s^2) is recorded once; each row is "
      "the backward pass of a trajectory loss (distance to the same scene run at wind.strength 1.5) with "
      "respect to wind.strength, wind.direction.0, cloths.0.material.stretch and cloths.0.material.density. "
      "solve = time in the per-step adjoint linear solve (AdjointSolver, including any fallback), rest = "
      "the other backward work (Delta P assembly, parameter partials). fail % = steps where the iterative "
      "method did not converge within its cap (200 iterations) and fell back to the direct LU. "
      "gradient_rel_error = |g - g_direct| / |g_direct|. peak_rss_mb = the process's peak resident set "
      "(getrusage maxrss) after that row: cumulative, so the last resolution's rows are the peak of all "
      "forward + backward runs so far. The Slope row of Table 1 is not reproduced: it needs gradients "
      "through contact, which Weft does not have yet (backpropagate rejects contact scenes).";
  table.writeCsv(out.file("backward.csv"));
  table.writeMarkdown(out.file("backward.md"), "Backward pass: adjoint solvers (weft bench backward)", preamble);
  std::string reason;
  if (!plotSeries(out.file("backward.png"), "Backward (Wind): time per step vs resolution", "quads per side",
                  "backward ms per step", plot, true, true, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  std::printf("bench backward: %zu rows over %zu resolutions -> %s/backward.{csv,md,png}\n", table.rows().size(),
              resolutions.size(), outDir.c_str());
  return 0;
}

}  // namespace weft::cli
