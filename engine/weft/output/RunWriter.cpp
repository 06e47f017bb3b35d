#include <weft/output/RunWriter.h>

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/io/ObjWriter.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>

namespace weft {

double peakMemoryMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

namespace {

void writeContactArrays(const std::string& folder, const Trajectory& trajectory, double dt) {
  // Per state and node, for the renderer and the editor: the branch (0 none, 1 take-off,
  // 2 stick, 3 slip) and the total contact force (N, impulse / h). A node with several contacts
  // shows its obstacle contact if it has one, else its strongest pair; state 0 has no contacts.
  const std::size_t states = trajectory.positions.size(),
                    nodes = static_cast<std::size_t>(trajectory.nodeCount());
  std::vector<double> branches(states * nodes, 0.0), forces(states * nodes * 3, 0.0),
      strength(nodes);
  for (std::size_t s = 1; s < states && s - 1 < trajectory.contacts.size(); ++s) {
    std::fill(strength.begin(), strength.end(), -1.0);
    for (const ContactPoint& p : trajectory.contacts[s - 1].points) {
      for (int end = 0; end < (p.partner >= 0 ? 2 : 1); ++end) {
        const std::size_t node = static_cast<std::size_t>(end == 0 ? p.node : p.partner);
        const Vec3 force = (end == 0 ? 1.0 : -1.0) * p.impulse / dt;
        for (int c = 0; c < 3; ++c) forces[(s * nodes + node) * 3 + c] += force[c];
        // Obstacle contacts rank above every pair (strength offset by 1e9 N s; impulses of a
        // simulation that has not blown up are far below).
        const double rank = p.impulse.norm() + (p.obstacle >= 0 ? 1e9 : 0.0);
        if (rank > strength[node]) {
          strength[node] = rank;
          branches[s * nodes + node] = static_cast<double>(p.branch);
        }
      }
    }
  }
  writeNpy(folder + "/contact_branches.npy", {states, nodes}, branches.data());
  writeNpy(folder + "/contact_forces.npy", {states, nodes, 3}, forces.data());
}

}  // namespace

nlohmann::json summarize(const Scene& scene, const Trajectory& trajectory, const RunSummary& run) {
  nlohmann::json modules = nlohmann::json::object();
  for (std::size_t i = 0; i < run.moduleNames.size(); ++i)
    modules[run.moduleNames[i]] = run.moduleSeconds[i];
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
  j["peak_memory_mb"] = peakMemoryMegabytes();
  j["modules"] = modules;
  j["contacts"] = {{"takeoff", takeoff}, {"stick", stick}, {"slip", slip}};
  j["pd"] = {
      {"iterations_total", iterations},
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
           {trajectory.positions.size(), static_cast<std::size_t>(trajectory.nodeCount()), 3},
           flat.data());

  // Area of the cloths over their rest area per state (DiffCloth Fig. 5's area ratio: a contact
  // model that moves nodes without regard to friction makes it jump).
  const double restArea = model.rest.totalArea();
  std::vector<double> areaRatio(trajectory.positions.size(), 1.0);
  for (std::size_t n = 0; n < trajectory.positions.size(); ++n)
    if (restArea > 0.0) areaRatio[n] = model.rest.areaAt(trajectory.positions[n]) / restArea;

  {
    const std::string path = folder + "/stats.csv";
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw InputError(path, "output", "cannot open for writing");
    std::fprintf(
        f.get(),
        "step,time,contacts_takeoff,contacts_stick,contacts_slip,pd_iterations,residual,converged,"
        "contact_sweeps,contact_sweep_change,late_contacts,area_ratio");
    for (const std::string& name : run.moduleNames)
      std::fprintf(f.get(), ",seconds_%s", name.c_str());
    std::fprintf(f.get(), "\n");
    for (const StepStats& s : trajectory.steps) {
      std::fprintf(f.get(), "%d,%.9g,%d,%d,%d,%d,%.6e,%d,%d,%.6e,%d,%.9f", s.step, s.time,
                   s.takeoff, s.stick, s.slip, s.pdIterations, s.residual, s.converged ? 1 : 0,
                   s.contactSweeps, s.contactSweepChange, s.lateContacts, areaRatio.at(s.step));
      for (double sec : s.moduleSeconds) std::fprintf(f.get(), ",%.6e", sec);
      std::fprintf(f.get(), "\n");
    }
    if (std::ferror(f.get())) throw InputError(path, "output", "write failed");
  }

  if (!trajectory.contacts.empty()) writeContactArrays(folder, trajectory, scene.time.dt);

  std::vector<std::pair<std::string, int>> groups;
  for (std::size_t c = 0; c + 1 < model.triangleOffset.size(); ++c)
    groups.emplace_back("cloth" + std::to_string(c), model.triangleOffset[c]);
  writeObj(folder + "/rest.obj", model.rest, groups);

  // The scene as simulated (overrides applied), so a run folder can be rendered or replayed alone.
  std::ofstream sceneCopy(folder + "/scene.json");
  sceneCopy << scene.document.dump(2) << "\n";
  if (!sceneCopy) throw InputError(folder + "/scene.json", "output", "write failed");

  std::ofstream summary(folder + "/summary.json");
  nlohmann::json summaryJson = summarize(scene, trajectory, run);
  summaryJson["area_ratio"] = {{"min", *std::min_element(areaRatio.begin(), areaRatio.end())},
                               {"max", *std::max_element(areaRatio.begin(), areaRatio.end())},
                               {"final", areaRatio.back()}};
  summary << summaryJson.dump(2) << "\n";
  if (!summary) throw InputError(folder + "/summary.json", "output", "write failed");
}

}  // namespace weft
