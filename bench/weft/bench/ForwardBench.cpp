// `weft bench forward`: what forward accuracy costs in time. For the hanging cloth in wind at
// several resolutions, seconds per step and trajectory error against a tightly converged
// reference, sweeping the PD iteration cap and the PD tolerance; plus PD iterations per step
// with and without Anderson acceleration.

#include "ForwardBench.h"

#include "BenchTable.h"

#include <weft/io/StagedDirectory.h>
#include <weft/physics/Simulator.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace weft::bench {
namespace {

struct RunResult {
  std::vector<NodeMatrix> positions;
  double secondsPerStep = 0.0;
  double iterationsPerStep = 0.0;
  int convergedSteps = 0;
};

RunResult simulateOnce(const std::string& file, std::vector<SceneOverride> overrides) {
  const Scene scene = loadScene(file, overrides);
  Simulator sim(scene);
  Trajectory traj;
  const auto start = std::chrono::steady_clock::now();
  sim.run(scene.time.steps, traj);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RunResult r;
  r.positions = std::move(traj.positions);
  const int steps = std::max(1, scene.time.steps);
  r.secondsPerStep = seconds / steps;
  long long it = 0;
  for (const auto& s : traj.steps) it += s.pdIterations, r.convergedSteps += s.converged;
  r.iterationsPerStep = double(it) / steps;
  return r;
}

// Largest over steps of the RMS node distance to the reference, relative to the cloth's size
// (diagonal of its rest bounding box).
double relativeError(const RunResult& run, const RunResult& ref) {
  const NodeMatrix& rest = ref.positions.front();
  const double size = (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm();
  double worst = 0.0;
  for (std::size_t n = 0; n < run.positions.size(); ++n) {
    const double rms =
        std::sqrt((run.positions[n] - ref.positions[n]).rowwise().squaredNorm().mean());
    worst = std::max(worst, rms);
  }
  return worst / size;
}

std::string defaultScene() {
  if (std::filesystem::exists("assets/scenes/wind.json")) return "assets/scenes/wind.json";
  return std::string(WEFT_ASSET_DIR) + "/scenes/wind.json";
}

}  // namespace

int runForwardBench(const ForwardBenchOptions& options, const std::string& outDir) {
  const bool quick = options.quick;
  const std::string file = options.scene.empty() ? defaultScene() : options.scene;
  const int threads = options.threads;
  omp_set_num_threads(threads);
  StagedDirectory out(outDir);

  // --resolutions: a subset, e.g. 24,48, to remeasure some sizes without the hour-long 96^2.
  const std::vector<int> resolutions = !options.resolutions.empty() ? options.resolutions
                                       : quick                      ? std::vector<int>{12, 24}
                                               : std::vector<int>{12, 24, 48, 96};
  const std::vector<int> caps = {5, 10, 20, 50, 100, 200};
  const std::vector<double> tolerances = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  BenchTable table({"quads", "vertices", "steps", "setting", "pd_iterations", "pd_tolerance",
                    "ms_per_step", "iterations_per_step", "converged_steps", "relative_error"});
  BenchTable accel({"quads", "vertices", "steps", "pd_tolerance", "solves_pd", "solves_pd_anderson",
                    "solves_newton", "ratio_anderson", "ratio_newton", "ms_pd", "ms_pd_anderson",
                    "ms_newton"});
  std::vector<PlotSeries> plot;

  for (int n : resolutions) {
    const int steps = quick ? 40 : (n >= 96 ? 50 : 200);
    const std::vector<SceneOverride> base = {
        {"cloths.0.mesh.grid.resolution", "[" + std::to_string(n) + "," + std::to_string(n) + "]"},
        {"cloths.0.attachments.0.vertices", "[0," + std::to_string(n) + "]"},
        {"time.steps", std::to_string(steps)}};
    const int vertices = (n + 1) * (n + 1);
    auto with = [&](std::vector<SceneOverride> extra) {
      std::vector<SceneOverride> o = base;
      o.insert(o.end(), extra.begin(), extra.end());
      return o;
    };
    std::fprintf(stderr, "forward: %dx%d reference...\n", n, n);
    const RunResult ref = simulateOnce(
        file, with({{"solver.pd_tolerance", "1e-8"}, {"solver.pd_iterations", "20000"}}));
    PlotSeries series{std::to_string(n) + "^2 quads", {}, {}};
    auto record = [&](const std::string& setting, const std::string& cap, const std::string& tol,
                      const RunResult& r) {
      const double err = relativeError(r, ref);
      table.add({std::to_string(n), std::to_string(vertices), std::to_string(steps), setting, cap,
                 tol, formatNumber(1e3 * r.secondsPerStep), formatNumber(r.iterationsPerStep),
                 std::to_string(r.convergedSteps), formatNumber(err, 3)});
      series.x.push_back(1e3 * r.secondsPerStep);
      series.y.push_back(std::max(err, 1e-16));
    };
    record("reference", "20000", "1e-8", ref);
    for (int cap : caps) {
      std::fprintf(stderr, "forward: %dx%d cap %d\n", n, n, cap);
      record("cap", std::to_string(cap), "-",
             simulateOnce(file, with({{"solver.pd_tolerance", "1e-300"},
                                      {"solver.pd_iterations", std::to_string(cap)}})));
    }
    for (double tol : tolerances) {
      std::fprintf(stderr, "forward: %dx%d tolerance %g\n", n, n, tol);
      record("tolerance", "10000", formatNumber(tol, 1),
             simulateOnce(file, with({{"solver.pd_tolerance", formatNumber(tol, 3)},
                                      {"solver.pd_iterations", "10000"}})));
    }
    plot.push_back(series);

    // Plain PD vs PD with Anderson acceleration vs Newton-PCG, at one tolerance, over a short
    // run (plain PD is slow).
    if (n <= 48) {
      const int accelSteps = 20;
      const std::string tol = "1e-3";
      std::fprintf(stderr, "forward: %dx%d solver comparison\n", n, n);
      const auto common = with({{"time.steps", std::to_string(accelSteps)},
                                {"solver.pd_tolerance", tol},
                                {"solver.pd_iterations", "50000"}});
      auto plain = common, anderson = common, newton = common;
      plain.push_back({"solver.method", "\"pd\""});
      plain.push_back({"solver.acceleration", "\"none\""});
      anderson.push_back({"solver.method", "\"pd\""});
      anderson.push_back({"solver.acceleration", "\"anderson\""});
      newton.push_back({"solver.method", "\"newton\""});
      const RunResult a = simulateOnce(file, plain), b = simulateOnce(file, anderson),
                      c = simulateOnce(file, newton);
      accel.add({std::to_string(n), std::to_string(vertices), std::to_string(accelSteps), tol,
                 formatNumber(a.iterationsPerStep), formatNumber(b.iterationsPerStep),
                 formatNumber(c.iterationsPerStep),
                 formatNumber(a.iterationsPerStep / b.iterationsPerStep, 3),
                 formatNumber(a.iterationsPerStep / c.iterationsPerStep, 3),
                 formatNumber(1e3 * a.secondsPerStep), formatNumber(1e3 * b.secondsPerStep),
                 formatNumber(1e3 * c.secondsPerStep)});
    }
  }

  const std::string machine = machineDescription();
  const std::string preamble =
      "Hanging cloth in wind (" + file + "), h = 1/90 s, " + std::to_string(threads) +
      " thread(s). Error: largest over steps of the RMS node distance to a reference run at PD "
      "tolerance 1e-8 m/s^2 (near the round-off floor of the residual), relative to the cloth's "
      "rest bounding-box diagonal. 'cap' rows run "
      "exactly that many PD iterations; 'tolerance' rows stop at the residual (m/s^2). Machine: " +
      machine + ".";
  table.writeCsv(out.file("forward.csv"));
  table.writeMarkdown(out.file("forward.md"), "Forward accuracy vs time (weft bench forward)",
                      preamble);
  accel.writeCsv(out.file("forward_acceleration.csv"));
  {
    std::ofstream md(out.file("forward.md"), std::ios::app);
    md << "\n### Solves with P per step: plain PD, PD + Anderson, Newton-PCG\n\n"
       << "Same scene, 20 steps, tolerance 1e-3 m/s^2 (plain PD needs too many iterations for a "
          "tighter one). "
       << "A PD iteration is one solve with P; a Newton-PCG CG iteration is one too. Ratios: plain "
          "PD solves / "
       << "accelerated solves.\n\n"
       << "| quads | vertices | solves PD | solves PD+Anderson | solves Newton | ratio Anderson | "
          "ratio Newton | "
          "ms/step PD | ms/step PD+Anderson | ms/step Newton |\n"
       << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const auto& r : accel.rows())
      md << "| " << r[0] << " | " << r[1] << " | " << r[4] << " | " << r[5] << " | " << r[6]
         << " | " << r[7] << " | " << r[8] << " | " << r[9] << " | " << r[10] << " | " << r[11]
         << " |\n";
  }
  std::string reason;
  if (!plotSeries(out.file("forward.png"), "Forward: error vs time per step", "ms per step",
                  "relative trajectory error", plot, true, true, reason))
    std::fprintf(stderr, "warning: %s\n", reason.c_str());
  out.commit();
  std::printf("bench forward: %zu runs over %zu resolutions -> %s/forward.{csv,md,png}\n",
              table.rows().size(), resolutions.size(), outDir.c_str());
  return 0;
}

}  // namespace weft::bench
