// _weft.simulate: the forward run of `weft simulate`, into NumPy arrays instead of files. The
// same calls in the same order (loadScene, Simulator, step), so positions are bit for bit those
// of positions.npy for the same scene, steps, overrides and OpenMP threads.

#include "Bindings.h"
#include "NumpyArrays.h"
#include "SceneSource.h"
#include "StepStatsTable.h"
#include "WarningLines.h"

#include <weft/contact/HandleObstacleCheck.h>
#include <weft/core/Error.h>
#include <weft/output/RunWriter.h>
#include <weft/physics/Simulator.h>
#include <weft/record/ConvergenceReport.h>

#include <omp.h>
#include <pybind11/stl.h>

#include <chrono>
#include <memory>
#include <optional>

namespace weft::python {

namespace py = pybind11;

namespace {

py::dict simulate(const SceneSource& source, std::optional<long long> steps) {
  Scene scene;
  std::unique_ptr<Simulator> sim;
  {
    py::gil_scoped_release released;
    scene = source.load();
  }
  const long long count = steps ? *steps : scene.time.steps;
  if (count < 0 || count > 10000000)
    throw InputError(source.name(), "steps",
                     "must be an integer in [0, 10000000], got '" + std::to_string(count) + "'");
  const int n = static_cast<int>(count);
  std::vector<std::string> warnings = scene.warnings;
  {
    py::gil_scoped_release released;
    for (const std::string& w : handlesEnteringObstacles(scene)) warnings.push_back(w);
    sim = std::make_unique<Simulator>(scene);
  }
  const std::size_t nodes = static_cast<std::size_t>(sim->cloth().nodeCount());
  py::array_t<double> positions = stateArray(n + 1, nodes);
  py::array_t<double> velocities = stateArray(n + 1, nodes);
  double* x = positions.mutable_data();
  double* v = velocities.mutable_data();
  std::vector<StepStats> stats;
  ConvergenceReport convergence;
  RunSummary run;
  {
    py::gil_scoped_release released;
    using Clock = std::chrono::steady_clock;
    copyState(x, 0, sim->positions());
    copyState(v, 0, sim->velocities());
    for (int k = 0; k < n; ++k) {
      checkInterrupt();
      const auto start = Clock::now();
      const StepStats& s = sim->step();
      run.seconds += std::chrono::duration<double>(Clock::now() - start).count();
      stats.push_back(s);
      convergence.add(s);
      copyState(x, k + 1, sim->positions());
      copyState(v, k + 1, sim->velocities());
    }
  }
  run.moduleNames = sim->moduleNames();
  run.moduleSeconds = sim->moduleSeconds();
  run.threads = omp_get_max_threads();
  addWarningLines(convergence.warning(scene.solver), warnings);

  py::dict out;
  out["positions"] = positions;
  out["velocities"] = velocities;
  out["stats"] = stepStatsTable(stats);
  out["summary"] = summarize(scene, static_cast<int>(nodes), stats, run).dump();
  out["warnings"] = warnings;
  return out;
}

}  // namespace

void bindSimulate(py::module_& m) {
  m.def(
      "simulate",
      [](std::optional<std::string> file, std::optional<std::string> document,
         std::vector<std::string> overrides, std::optional<long long> steps) {
        return simulate({std::move(file), std::move(document), std::move(overrides)}, steps);
      },
      py::arg("file"), py::arg("document"), py::arg("overrides"), py::arg("steps"),
      "Runs a scene (a file, or a document's JSON text) with overrides (\"PATH=VALUE\"); returns "
      "a dict of positions and velocities [steps+1, vertices, 3], stats (per-step arrays), "
      "summary (summary.json's text) and warnings.");
}

}  // namespace weft::python
