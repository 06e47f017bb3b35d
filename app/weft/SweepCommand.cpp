// `weft sweep SCENE --set-grid PATH=a,b,c [--set-grid ...] [--set PATH=VALUE ...] [--steps N]
//                   [--out DIR] [--threads N] [--quiet]`
// One simulation per combination of the listed values (output/SceneSweep.h), serially or over
// MPI's ranks under mpirun/srun; DIR/sweep.csv (default out/sweep-<scene name>) has one row per
// combination. Exit 0 when every run succeeded; otherwise the worst run's exit code (2 or 3),
// after the file is written with every row.

#include "CommandLine.h"
#include "Commands.h"
#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/core/Error.h>
#include <weft/distributed/WorkDistributor.h>
#include <weft/output/SceneSweep.h>
#include <weft/scene/SceneLoader.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace weft::cli {

int applyThreads(const CommandLine& cl);  // SimulateCommand.cpp

int sweepCommand(const std::vector<std::string>& args) {
  CommandLine cl(args, {"--set-grid", "--set", "--steps", "--out", "--threads"}, {"--quiet"});
  if (cl.positional().size() != 1) cl.fail("SCENE", "sweep takes exactly one scene file");
  const std::string file = cl.positional()[0];
  cl.setContext(file);
  applyThreads(cl);
  SweepSettings settings;
  settings.sceneFile = file;
  settings.overrides = parseOverrides(cl);
  for (const std::string& g : cl.values("--set-grid"))
    settings.axes.push_back(parseSweepAxis(g, file));
  if (settings.axes.empty()) cl.fail("--set-grid", "give at least one PATH=VALUE,VALUE,...");
  settings.steps = cl.integer("--steps", -1, 0, 10000000);
  const Scene scene = loadScene(file, settings.overrides);
  const std::string outDir = cl.value("--out", "out/sweep-" + scene.name);
  checkSweepCombinations(settings);

  WorkDistributor& workers = processWorkers();
  if (workers.isRoot()) {
    printSceneWarnings(scene);
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec || !std::filesystem::is_directory(outDir))
      throw InputError(outDir, "--out", "cannot create the folder");
  }
  const std::size_t total = sweepCombinations(settings).size();
  if (workers.isRoot() && !cl.has("--quiet"))
    std::fprintf(stderr, "sweep: %s: %zu combination(s), %s\n", scene.name.c_str(), total,
                 workers.description().c_str());
  const auto start = std::chrono::steady_clock::now();
  const SweepOutcome outcome = runSweep(settings, workers, outDir + "/sweep.csv");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!workers.isRoot()) return outcome.worstExitCode;
  for (const std::string& f : outcome.failures) std::fprintf(stderr, "error: %s\n", f.c_str());
  if (outcome.unconvergedRuns > 0)
    std::fprintf(stderr,
                 "warning: %d of %zu runs have steps that stopped above solver.pd_tolerance "
                 "(column pd.unconverged_steps)\n",
                 outcome.unconvergedRuns, outcome.combinations);
  std::printf("sweep: %s: %zu runs, %d failed, %.2f s, %s -> %s/sweep.csv\n", scene.name.c_str(),
              outcome.combinations, outcome.failed, seconds, workers.description().c_str(),
              outDir.c_str());
  return outcome.worstExitCode;
}

}  // namespace weft::cli
