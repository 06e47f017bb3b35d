#include <weft/output/RunWriter.h>

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/io/ObjWriter.h>

#include <cstdio>
#include <fstream>
#include <memory>

namespace weft {

nlohmann::json summarize(const Scene& scene, const Trajectory& trajectory, const RunSummary& run) {
  nlohmann::json modules = nlohmann::json::object();
  for (std::size_t i = 0; i < run.moduleNames.size(); ++i) modules[run.moduleNames[i]] = run.moduleSeconds[i];
  long long takeoff = 0, stick = 0, slip = 0, iterations = 0;
  int converged = 0, maxIterations = 0;
  double maxResidual = 0.0;
  for (const StepStats& s : trajectory.steps) {
    takeoff += s.takeoff, stick += s.stick, slip += s.slip;
    iterations += s.pdIterations;
    maxIterations = std::max(maxIterations, s.pdIterations);
    converged += s.converged ? 1 : 0;
    maxResidual = std::max(maxResidual, s.residual);
  }
  const int steps = trajectory.stepCount();
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_file"] = scene.file;
  j["scene_directory"] = scene.directory;  // resolves relative paths in scene.json
  j["steps"] = steps;
  j["vertices"] = trajectory.nodeCount();
  j["dt"] = scene.time.dt;
  j["seconds"] = run.seconds;
  j["seconds_per_step"] = steps > 0 ? run.seconds / steps : 0.0;
  j["threads"] = run.threads;
  j["modules"] = modules;
  j["contacts"] = {{"takeoff", takeoff}, {"stick", stick}, {"slip", slip}};
  j["pd"] = {{"iterations_total", iterations},
             {"iterations_mean", steps > 0 ? double(iterations) / steps : 0.0},
             {"iterations_max", maxIterations},
             {"converged_steps", converged},
             {"max_residual", maxResidual},
             {"tolerance", scene.solver.pdTolerance},
             {"acceleration", scene.solver.acceleration == Acceleration::Anderson ? "anderson" : "none"}};
  return j;
}

void writeRun(const std::string& folder, const Scene& scene, const ClothModel& model,
              const Trajectory& trajectory, const RunSummary& run) {
  const std::vector<double> flat = trajectory.flattenedPositions();
  writeNpy(folder + "/positions.npy",
           {trajectory.positions.size(), static_cast<std::size_t>(trajectory.nodeCount()), 3}, flat.data());

  {
    const std::string path = folder + "/stats.csv";
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw InputError(path, "output", "cannot open for writing");
    std::fprintf(f.get(), "step,time,contacts_takeoff,contacts_stick,contacts_slip,pd_iterations,residual,converged");
    for (const std::string& name : run.moduleNames) std::fprintf(f.get(), ",seconds_%s", name.c_str());
    std::fprintf(f.get(), "\n");
    for (const StepStats& s : trajectory.steps) {
      std::fprintf(f.get(), "%d,%.9g,%d,%d,%d,%d,%.6e,%d", s.step, s.time, s.takeoff, s.stick, s.slip,
                   s.pdIterations, s.residual, s.converged ? 1 : 0);
      for (double sec : s.moduleSeconds) std::fprintf(f.get(), ",%.6e", sec);
      std::fprintf(f.get(), "\n");
    }
    if (std::ferror(f.get())) throw InputError(path, "output", "write failed");
  }

  std::vector<std::pair<std::string, int>> groups;
  for (std::size_t c = 0; c + 1 < model.triangleOffset.size(); ++c)
    groups.emplace_back("cloth" + std::to_string(c), model.triangleOffset[c]);
  writeObj(folder + "/rest.obj", model.rest, groups);

  // The scene as simulated (overrides applied), so a run folder can be rendered or replayed alone.
  std::ofstream sceneCopy(folder + "/scene.json");
  sceneCopy << scene.document.dump(2) << "\n";
  if (!sceneCopy) throw InputError(folder + "/scene.json", "output", "write failed");

  std::ofstream summary(folder + "/summary.json");
  summary << summarize(scene, trajectory, run).dump(2) << "\n";
  if (!summary) throw InputError(folder + "/summary.json", "output", "write failed");
}

}  // namespace weft
