#include <weft/output/RunWriter.h>

#include <weft/collision/MeshCrossingCheck.h>
#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/io/ObjWriter.h>
#include <weft/record/ConvergenceReport.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <memory>
#include <utility>

namespace weft {

double peakMemoryMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

RunWriter::RunWriter(std::string folder, const Scene& scene, const ClothModel& model, int steps,
                     bool contactArrays)
    : folder_(std::move(folder)),
      scene_(scene),
      model_(model),
      nodes_(static_cast<std::size_t>(model.nodeCount())),
      restArea_(model.rest.totalArea()),
      positions_(folder_ + "/positions.npy", {static_cast<std::size_t>(steps) + 1,
                                              static_cast<std::size_t>(model.nodeCount()), 3}),
      row_(nodes_ * 3) {
  const std::size_t states = static_cast<std::size_t>(steps) + 1;
  if (contactArrays) {
    branches_.emplace(folder_ + "/contact_branches.npy", std::vector<std::size_t>{states, nodes_});
    forces_.emplace(folder_ + "/contact_forces.npy", std::vector<std::size_t>{states, nodes_, 3});
    branchRow_.resize(nodes_);
    forceRow_.resize(nodes_ * 3);
    strength_.resize(nodes_);
  }
  areaRatio_.reserve(states);
  steps_.reserve(static_cast<std::size_t>(steps));
  bool selfColliding = false;
  for (const Cloth& c : scene.cloths) selfColliding = selfColliding || c.selfCollision.has_value();
  if (selfColliding) {
    crossingCheck_ = std::make_unique<collision::MeshCrossingCheck>(
        collision::CollisionMesh::of(scene, model, false));
    crossings_.reserve(states);
  }
}

RunWriter::~RunWriter() = default;

void RunWriter::addPositions(const NodeMatrix& x) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < nodes_; ++i)
    for (int c = 0; c < 3; ++c) row_[k++] = x(static_cast<Eigen::Index>(i), c);
  positions_.append(row_.data(), row_.size());
  // Area of the cloths over their rest area (DiffCloth Fig. 5's area ratio: a contact model
  // that moves nodes without regard to friction makes it jump).
  areaRatio_.push_back(restArea_ > 0.0 ? model_.rest.areaAt(x) / restArea_ : 1.0);
  if (crossingCheck_) crossings_.push_back(crossingCheck_->count(x));
}

void RunWriter::addInitialState(const NodeMatrix& x) {
  addPositions(x);
  if (branches_) {  // state 0 has no contacts
    std::fill(branchRow_.begin(), branchRow_.end(), 0.0);
    std::fill(forceRow_.begin(), forceRow_.end(), 0.0);
    branches_->append(branchRow_.data(), branchRow_.size());
    forces_->append(forceRow_.data(), forceRow_.size());
  }
}

void RunWriter::addStep(const NodeMatrix& x, const StepStats& stats, const StepContacts* contacts) {
  addPositions(x);
  steps_.push_back(stats);
  if (!branches_) return;
  // Per node, for the renderer and the editor: the branch (0 none, 1 take-off, 2 stick, 3 slip)
  // and the total contact force (N, impulse / h). A node with several contacts shows its
  // obstacle contact if it has one, else its strongest pair.
  std::fill(branchRow_.begin(), branchRow_.end(), 0.0);
  std::fill(forceRow_.begin(), forceRow_.end(), 0.0);
  std::fill(strength_.begin(), strength_.end(), -1.0);
  if (contacts)
    for (const ContactPoint& p : contacts->points) {
      for (int end = 0; end < (p.partner >= 0 ? 2 : 1); ++end) {
        const std::size_t node = static_cast<std::size_t>(end == 0 ? p.node : p.partner);
        const Vec3 force = (end == 0 ? 1.0 : -1.0) * p.impulse / scene_.time.dt;
        for (int c = 0; c < 3; ++c) forceRow_[node * 3 + c] += force[c];
        // Obstacle contacts rank above every pair (strength offset by 1e9 N s; impulses of a
        // simulation that has not blown up are far below).
        const double rank = p.impulse.norm() + (p.obstacle >= 0 ? 1e9 : 0.0);
        if (rank > strength_[node]) {
          strength_[node] = rank;
          branchRow_[node] = static_cast<double>(p.branch);
        }
      }
    }
  branches_->append(branchRow_.data(), branchRow_.size());
  forces_->append(forceRow_.data(), forceRow_.size());
}

nlohmann::json summarize(const Scene& scene, int vertices, const std::vector<StepStats>& stepStats,
                         const RunSummary& run) {
  nlohmann::json modules = nlohmann::json::object();
  for (std::size_t i = 0; i < run.moduleNames.size(); ++i)
    modules[run.moduleNames[i]] = run.moduleSeconds[i];
  long long takeoff = 0, stick = 0, slip = 0, iterations = 0;
  int maxIterations = 0, splitSteps = 0, deepestHalvings = 0;
  double maxResidual = 0.0;
  long long impactRounds = 0, impactZones = 0, impactConstraints = 0, impactIterations = 0;
  long long rigidZones = 0;
  int rigidSteps = 0;
  double impactMove = 0.0;
  ConvergenceReport convergence;
  for (const StepStats& s : stepStats) {
    convergence.add(s);
    takeoff += s.takeoff, stick += s.stick, slip += s.slip;
    iterations += s.pdIterations;
    maxIterations = std::max(maxIterations, s.pdIterations);
    maxResidual = std::max(maxResidual, s.residual);
    splitSteps += s.substeps > 1;
    deepestHalvings = std::max(deepestHalvings, s.halvings);
    impactRounds += s.impactRounds, impactZones += s.impactZones;
    impactConstraints += s.impactConstraints, impactIterations += s.impactQpIterations;
    impactMove = std::max(impactMove, s.impactMove);
    rigidZones += s.impactRigidZones;
    rigidSteps += s.impactRigidZones > 0;
  }
  const int steps = static_cast<int>(stepStats.size());
  nlohmann::json j;
  j["scene"] = scene.name;
  j["scene_file"] = scene.file;
  j["scene_directory"] = scene.directory;  // resolves relative paths in scene.json
  j["steps"] = steps;
  j["vertices"] = vertices;
  j["dt"] = scene.time.dt;
  j["seconds"] = run.seconds;
  j["seconds_per_step"] = steps > 0 ? run.seconds / steps : 0.0;
  j["threads"] = run.threads;
  j["peak_memory_mb"] = peakMemoryMegabytes();
  j["modules"] = modules;
  j["contacts"] = {{"takeoff", takeoff},
                   {"stick", stick},
                   {"slip", slip},
                   {"max_depth", convergence.maxDepth},
                   {"max_depth_step", convergence.maxDepthStep}};
  j["pd"] = {
      {"iterations_total", iterations},
      {"iterations_mean", steps > 0 ? double(iterations) / steps : 0.0},
      {"iterations_max", maxIterations},
      {"converged_steps", convergence.steps - convergence.unconverged},
      {"unconverged_steps", convergence.unconverged},
      {"max_residual", maxResidual},
      {"worst_unconverged_residual", convergence.worstResidual},
      {"worst_unconverged_step", convergence.worstResidualStep},
      {"iteration_limit", scene.solver.pdIterations},
      {"tolerance", scene.solver.pdTolerance},
      {"split_steps", splitSteps},
      {"deepest_halvings", deepestHalvings},
      {"max_halvings", scene.solver.maxHalvings},
      {"remember_halvings", scene.solver.rememberHalvings},
      {"acceleration", scene.solver.acceleration == Acceleration::Anderson ? "anderson" : "none"}};
  if (scene.hasImpactZones())
    j["impact_zones"] = {{"rounds_total", impactRounds},
                         {"zones_total", impactZones},
                         {"constraints_total", impactConstraints},
                         {"qp_iterations_total", impactIterations},
                         {"rigid_zones_total", rigidZones},
                         {"rigid_steps", rigidSteps},
                         {"unresolved_steps", convergence.unresolvedImpactSteps},
                         {"first_unresolved_step", convergence.firstUnresolvedImpactStep},
                         {"max_move", impactMove}};
  return j;
}

void RunWriter::finish(const RunSummary& run) {
  positions_.close();
  if (branches_) {
    branches_->close();
    forces_->close();
  }
  const std::string& folder = folder_;
  {
    const std::string path = folder + "/stats.csv";
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw InputError(path, "output", "cannot open for writing");
    std::fprintf(
        f.get(),
        "step,time,contacts_takeoff,contacts_stick,contacts_slip,pd_iterations,residual,converged,"
        "contact_sweeps,contact_sweep_change,late_contacts,area_ratio,depth,substeps");
    const bool impacts = scene_.hasImpactZones();
    if (impacts)
      std::fprintf(f.get(),
                   ",impact_rounds,impact_zones,impact_constraints,impact_qp_iterations,"
                   "impact_rigid_zones,impacts_resolved,impact_move");
    if (crossingCheck_) std::fprintf(f.get(), ",crossings");
    for (const std::string& name : run.moduleNames)
      std::fprintf(f.get(), ",seconds_%s", name.c_str());
    std::fprintf(f.get(), "\n");
    for (const StepStats& s : steps_) {
      std::fprintf(f.get(), "%d,%.9g,%d,%d,%d,%d,%.6e,%d,%d,%.6e,%d,%.9f,%.6e,%d", s.step, s.time,
                   s.takeoff, s.stick, s.slip, s.pdIterations, s.residual, s.converged ? 1 : 0,
                   s.contactSweeps, s.contactSweepChange, s.lateContacts, areaRatio_.at(s.step),
                   s.depth, s.substeps);
      if (impacts)
        std::fprintf(f.get(), ",%d,%d,%d,%d,%d,%d,%.6e", s.impactRounds, s.impactZones,
                     s.impactConstraints, s.impactQpIterations, s.impactRigidZones,
                     s.impactsResolved ? 1 : 0, s.impactMove);
      if (crossingCheck_) std::fprintf(f.get(), ",%d", crossings_.at(s.step));
      for (double sec : s.moduleSeconds) std::fprintf(f.get(), ",%.6e", sec);
      std::fprintf(f.get(), "\n");
    }
    if (std::ferror(f.get())) throw InputError(path, "output", "write failed");
  }

  std::vector<std::pair<std::string, int>> groups;
  for (std::size_t c = 0; c + 1 < model_.triangleOffset.size(); ++c)
    groups.emplace_back("cloth" + std::to_string(c), model_.triangleOffset[c]);
  writeObj(folder + "/rest.obj", model_.rest, groups);

  // The scene as simulated (overrides applied), so a run folder can be rendered or replayed alone.
  std::ofstream sceneCopy(folder + "/scene.json");
  sceneCopy << scene_.document.dump(2) << "\n";
  if (!sceneCopy) throw InputError(folder + "/scene.json", "output", "write failed");

  std::ofstream summary(folder + "/summary.json");
  nlohmann::json summaryJson = summarize(scene_, static_cast<int>(nodes_), steps_, run);
  summaryJson["area_ratio"] = {{"min", *std::min_element(areaRatio_.begin(), areaRatio_.end())},
                               {"max", *std::max_element(areaRatio_.begin(), areaRatio_.end())},
                               {"final", areaRatio_.back()}};
  if (crossingCheck_) {
    // Edge-triangle crossings of the self-colliding cloths, over every state (0 = the start).
    const auto worst = std::max_element(crossings_.begin(), crossings_.end());
    summaryJson["crossings"] = {
        {"final", crossings_.back()},
        {"max", *worst},
        {"max_state", worst - crossings_.begin()},
        {"states_with_crossings",
         std::count_if(crossings_.begin(), crossings_.end(), [](int n) { return n > 0; })}};
  }
  summary << summaryJson.dump(2) << "\n";
  if (!summary) throw InputError(folder + "/summary.json", "output", "write failed");
}

}  // namespace weft
