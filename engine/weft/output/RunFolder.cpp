#include <weft/output/RunFolder.h>

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

nlohmann::json readJson(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "RUNDIR", "missing: not a folder written by weft simulate");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "json", e.what());
  }
}

// An array [states, nodes, 3] (positions, velocities, contact forces) as one matrix per state;
// `states` 0 takes any count of at least one.
std::vector<NodeMatrix> readStates(const std::string& file, std::size_t nodes, std::size_t states) {
  const NpyArray a = readNpy(file);
  if (a.shape.size() != 3 || (states > 0 && a.shape[0] != states) || a.shape[1] != nodes ||
      a.shape[2] != 3 || a.shape[0] < 1)
    throw InputError(file, "shape",
                     "expected [" + (states > 0 ? std::to_string(states) : std::string("states")) +
                         ", " + std::to_string(nodes) + ", 3] for the scene's " +
                         std::to_string(nodes) + " vertices");
  std::vector<NodeMatrix> out(a.shape[0], NodeMatrix(Eigen::Index(nodes), 3));
  for (std::size_t s = 0; s < a.shape[0]; ++s)
    for (std::size_t i = 0; i < nodes; ++i)
      for (int c = 0; c < 3; ++c)
        out[s](Eigen::Index(i), c) = a.data[(s * nodes + i) * 3 + std::size_t(c)];
  return out;
}

// stats.csv as RunWriter writes it: a header of column names, then one row per step.
std::vector<StepStats> readStats(const std::string& file, std::size_t states) {
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) throw InputError(file, "header", "empty file");
  std::map<std::string, std::size_t> column;
  {
    std::istringstream names(line);
    std::string name;
    for (std::size_t k = 0; std::getline(names, name, ','); ++k) column[name] = k;
  }
  for (const char* required : {"step", "time", "pd_iterations", "residual", "converged"})
    if (!column.count(required))
      throw InputError(file, "header", std::string("no column '") + required + "'");
  std::vector<StepStats> steps;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    std::vector<double> values;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(field.c_str(), &end);
      if (end == field.c_str() || *end != '\0' || errno == ERANGE)
        throw InputError(file, "row " + std::to_string(row), "'" + field + "' is not a number");
      values.push_back(v);
    }
    if (values.size() != column.size())
      throw InputError(file, "row " + std::to_string(row),
                       std::to_string(values.size()) + " values for " +
                           std::to_string(column.size()) + " columns");
    const auto get = [&](const char* name, double fallback) {
      const auto it = column.find(name);
      return it == column.end() ? fallback : values[it->second];
    };
    StepStats s;
    s.step = int(get("step", 0));
    s.time = get("time", 0);
    s.takeoff = int(get("contacts_takeoff", 0));
    s.stick = int(get("contacts_stick", 0));
    s.slip = int(get("contacts_slip", 0));
    s.pdIterations = int(get("pd_iterations", 0));
    s.residual = get("residual", 0);
    s.converged = get("converged", 0) != 0.0;
    s.contactSweeps = int(get("contact_sweeps", 0));
    s.contactSweepChange = get("contact_sweep_change", 0);
    s.lateContacts = int(get("late_contacts", 0));
    s.depth = get("depth", 0);
    s.substeps = int(get("substeps", 1));
    s.impactRounds = int(get("impact_rounds", 0));
    s.impactZones = int(get("impact_zones", 0));
    s.impactConstraints = int(get("impact_constraints", 0));
    s.impactQpIterations = int(get("impact_qp_iterations", 0));
    s.impactRigidZones = int(get("impact_rigid_zones", 0));
    s.impactsResolved = get("impacts_resolved", 1) != 0.0;
    s.impactMove = get("impact_move", 0);
    if (s.step != static_cast<int>(steps.size()) + 1)
      throw InputError(file, "row " + std::to_string(row),
                       "step " + std::to_string(s.step) + " where step " +
                           std::to_string(steps.size() + 1) + " belongs");
    steps.push_back(s);
  }
  if (steps.size() + 1 != states)
    throw InputError(file, "rows",
                     std::to_string(steps.size()) + " steps for " + std::to_string(states) +
                         " states in positions.npy");
  return steps;
}

}  // namespace

bool isRunFolder(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

RunFolder loadRunFolder(const std::string& path) {
  RunFolder run;
  run.path = path;
  const std::string summaryFile = path + "/summary.json", sceneFile = path + "/scene.json",
                    positionsFile = path + "/positions.npy";
  const nlohmann::json summary = readJson(summaryFile);
  // Relative mesh and target paths in scene.json are relative to the original scene's folder.
  std::string directory = path;
  if (summary.contains("scene_directory") && summary["scene_directory"].is_string())
    directory = summary["scene_directory"].get<std::string>();
  run.scene = parseScene(readJson(sceneFile), sceneFile, directory);

  if (!fs::exists(positionsFile))
    throw InputError(positionsFile, "RUNDIR", "missing: not a folder written by weft simulate");
  const std::size_t nodes = static_cast<std::size_t>(run.scene.vertexCount());
  run.states = readStates(positionsFile, nodes, 0);
  const std::size_t states = run.states.size();
  const std::string velocitiesFile = path + "/velocities.npy", statsFile = path + "/stats.csv";
  if (fs::exists(velocitiesFile)) run.velocities = readStates(velocitiesFile, nodes, states);
  if (fs::exists(statsFile)) run.steps = readStats(statsFile, states);

  const std::string branchesFile = path + "/contact_branches.npy",
                    forcesFile = path + "/contact_forces.npy";
  if (fs::exists(branchesFile)) {
    const NpyArray b = readNpy(branchesFile);
    if (b.shape.size() != 2 || b.shape[0] != states || b.shape[1] != nodes)
      throw InputError(branchesFile, "shape",
                       "expected [" + std::to_string(states) + ", " + std::to_string(nodes) + "]");
    run.contacts.branches.assign(states, std::vector<std::uint8_t>(nodes, 0));
    for (std::size_t s = 0; s < states; ++s)
      for (std::size_t i = 0; i < nodes; ++i) {
        const double v = b.data[s * nodes + i];
        if (!(v >= 0.0 && v <= 3.0 && v == double(int(v))))
          throw InputError(branchesFile, "value",
                           "branch ids are 0 (none), 1 (take-off), 2 (stick) or 3 (slip)");
        run.contacts.branches[s][i] = static_cast<std::uint8_t>(v);
      }
    if (fs::exists(forcesFile)) run.contacts.forces = readStates(forcesFile, nodes, states);
  }
  return run;
}

}  // namespace weft
