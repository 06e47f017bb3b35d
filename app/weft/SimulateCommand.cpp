#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>
#include <weft/output/RunWriter.h>
#include <weft/physics/Simulator.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/scene/SceneLoader.h>

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace weft::cli {

int applyThreads(const CommandLine& cl) {
  const int threads = cl.integer("--threads", 0, 0, 1024);
  if (threads > 0) omp_set_num_threads(threads);
  return omp_get_max_threads();
}

int simulateCommand(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--steps", "--out", "--set", "--threads"}, {"--quiet", "--strict"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "simulate takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  const int threads = applyThreads(cl);
  Scene scene = loadScene(file, parseOverrides(cl));
  const int steps = cl.integer("--steps", scene.time.steps, 0, 10000000);
  printSceneWarnings(scene);
  const std::string outDir = cl.value("--out", "out/" + scene.name);
  StagedDirectory out(outDir);  // fails early on an unusable --out, before simulating

  // The run goes to its files state by state as it is simulated (RunWriter.h): memory stays
  // that of the simulator, whatever the steps and contacts.
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  Simulator sim(scene);
  RunWriter writer(out.path(), scene, sim.cloth(), steps, sim.contact() != nullptr && steps > 0);
  double writing = 0.0;  // seconds spent writing, left out of the simulation's wall time
  auto timed = [&writing](auto&& write) {
    const auto t = Clock::now();
    write();
    writing += std::chrono::duration<double>(Clock::now() - t).count();
  };
  timed([&] { writer.addInitialState(sim.positions()); });
  const bool quiet = cl.has("--quiet");
  const int every = std::max(1, steps / 10);
  long long iterations = 0;
  ConvergenceReport convergence;
  for (int k = 0; k < steps; ++k) {
    const StepStats& s = sim.step();
    timed([&] { writer.addStep(sim.positions(), s, &sim.lastContacts()); });
    iterations += s.pdIterations;
    convergence.add(s);
    if (!quiet && (s.step % every == 0))
      std::fprintf(stderr, "\rstep %d/%d  pd %d  residual %.2e", s.step, steps, s.pdIterations,
                   s.residual);
  }
  if (!quiet && steps > 0) std::fprintf(stderr, "\n");
  RunSummary run;
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count() - writing;
  run.moduleNames = sim.moduleNames();
  run.moduleSeconds = sim.moduleSeconds();
  run.threads = threads;
  writer.finish(run);
  out.commit();

  std::printf(
      "simulate: %s: %d steps, %d vertices, %.3f s (%.2f ms/step, %.1f PD iterations/step) -> %s\n",
      scene.name.c_str(), steps, sim.cloth().nodeCount(), run.seconds,
      steps ? 1e3 * run.seconds / steps : 0.0, steps ? double(iterations) / steps : 0.0,
      outDir.c_str());
  std::fprintf(stderr, "%s", convergence.warning(scene.solver).c_str());
  if (cl.has("--strict") && convergence.unconverged > 0) {
    char what[256];
    std::snprintf(what, sizeof what,
                  "residual %.3g m/s^2 above solver.pd_tolerance after solver.pd_iterations (%d "
                  "of %d steps unconverged; --strict)",
                  convergence.worstResidual, convergence.unconverged, steps);
    throw NumericalError(convergence.worstResidualStep, "solver", what);
  }
  return 0;
}

}  // namespace weft::cli
