#include <weft/diff/TaskLoss.h>

#include <weft/core/Error.h>
#include <weft/diff/FinalFrameLoss.h>
#include <weft/diff/HemlineLoss.h>
#include <weft/diff/KeypointLoss.h>
#include <weft/diff/TrajectoryLoss.h>
#include <weft/io/Npy.h>
#include <weft/scene/JsonReader.h>
#include <weft/scene/SceneLoader.h>

#include <filesystem>

namespace weft {
namespace {

struct TargetFile {
  std::vector<NodeMatrix> states;
};

// Reads a [S, V, 3] or [V, 3] float64/float32 .npy whose V matches the scene's vertex count.
TargetFile readTarget(const Scene& scene, const std::string& where, const std::string& file) {
  const std::string path = resolveScenePath(scene.directory, file);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(scene.file, where, "target file not found: " + path);
  NpyArray npy;
  try {
    npy = readNpy(path);
  } catch (const InputError& e) {
    throw InputError(scene.file, where, "cannot read target " + path + ": " + e.reason());
  }
  const std::size_t vertices = static_cast<std::size_t>(scene.vertexCount());
  std::size_t states = 0;
  if (npy.shape.size() == 3 && npy.shape[1] == vertices && npy.shape[2] == 3)
    states = npy.shape[0];
  else if (npy.shape.size() == 2 && npy.shape[0] == vertices && npy.shape[1] == 3)
    states = 1;
  else {
    std::string shape;
    for (std::size_t d : npy.shape) shape += (shape.empty() ? "" : ", ") + std::to_string(d);
    throw InputError(scene.file, where,
                     "target " + path + " has shape [" + shape + "]; expected [states, " +
                         std::to_string(vertices) + ", 3] or [" + std::to_string(vertices) +
                         ", 3]");
  }
  TargetFile t;
  for (std::size_t s = 0; s < states; ++s) {
    NodeMatrix x(static_cast<int>(vertices), 3);
    for (std::size_t v = 0; v < vertices; ++v)
      for (int c = 0; c < 3; ++c) x(static_cast<int>(v), c) = npy.data[(s * vertices + v) * 3 + c];
    if (!x.allFinite())
      throw InputError(scene.file, where, "target " + path + " has non-finite values");
    t.states.push_back(std::move(x));
  }
  return t;
}

std::vector<int> readVertices(const Scene& scene, const nlohmann::json& term,
                              const std::string& where) {
  std::vector<int> out;
  if (!term.contains("vertices")) return out;
  const nlohmann::json& list = term["vertices"];
  const int count = scene.vertexCount();
  if (!list.is_array() || list.empty())
    throw InputError(scene.file, where + ".vertices", "must be a non-empty list of vertex indices");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& v = list[i];
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() >= count)
      throw InputError(
          scene.file, where + ".vertices." + std::to_string(i),
          "must be a vertex index in [0, " + std::to_string(count) + ") (global, scene order)");
    out.push_back(v.get<int>());
  }
  return out;
}

// task.loss.keypoints (KeypointLoss.h): each entry's vertices with explicit `positions` or with
// the rows of a scene-shaped `target` .npy ([vertices, 3], or [states, vertices, 3] whose state
// `step` is used, as a positions.npy of a run). The loader has checked the structure and ranges;
// they are read through the same checks so that every message names its JSON path.
std::unique_ptr<LossTerm> makeKeypointLoss(const Scene& scene, const JsonReader& term) {
  std::vector<KeypointLoss::Keypoint> keypoints;
  const JsonReader points = term.at("points");
  for (std::size_t e = 0; e < points.size(); ++e) {
    const JsonReader entry = points[e];
    const int step = entry.at("step").integer(0, scene.time.steps);
    const double weight = entry.has("weight") ? entry.at("weight").positive() : 1.0;
    entry.at("vertices").size();  // required here (readVertices defaults to all)
    const std::vector<int> vertices = readVertices(scene, entry.value(), entry.path());
    std::vector<Vec3> targets;
    if (entry.has("positions")) {
      const JsonReader positions = entry.at("positions");
      if (positions.size() != vertices.size())
        positions.fail("needs one [x, y, z] per listed vertex");
      for (std::size_t k = 0; k < vertices.size(); ++k) targets.push_back(positions[k].vec3());
    } else {
      const std::string where = entry.path() + ".target";
      const TargetFile file = readTarget(scene, where, entry.at("target").string());
      if (file.states.size() > 1 && static_cast<int>(file.states.size()) <= step)
        throw InputError(scene.file, where,
                         "target has " + std::to_string(file.states.size()) + " states; step " +
                             std::to_string(step) + " needs at least " + std::to_string(step + 1));
      const NodeMatrix& state = file.states.size() == 1 ? file.states.front() : file.states[step];
      for (int v : vertices) targets.push_back(state.row(v).transpose());
    }
    for (std::size_t k = 0; k < vertices.size(); ++k)
      keypoints.push_back({step, vertices[k], targets[k], weight});
  }
  const double weight = term.has("weight") ? term.at("weight").positive() : 1.0;
  return std::make_unique<KeypointLoss>(std::move(keypoints), weight);
}

// task.loss.hemline (HemlineLoss.h).
std::unique_ptr<LossTerm> makeHemlineLoss(const Scene& scene, const JsonReader& term) {
  term.at("vertices").size();  // required here (readVertices defaults to all)
  std::vector<int> vertices = readVertices(scene, term.value(), term.path());
  const double height = term.has("height")
                            ? term.at("height").number()
                            : targetHemlineHeight(term.at("apex_angle_deg").number(0.0, 180.0),
                                                  term.at("apex_height").number(),
                                                  term.at("slant_length").positive());
  std::vector<int> states;
  if (auto list = term.optional("steps"))
    for (std::size_t i = 0; i < list->size(); ++i)
      states.push_back((*list)[i].integer(0, scene.time.steps));
  else
    states.push_back(scene.time.steps);
  const Vec3 up = term.has("up") ? term.at("up").unitVec3() : Vec3::UnitY();
  const double weight = term.has("weight") ? term.at("weight").positive() : 1.0;
  return std::make_unique<HemlineLoss>(std::move(vertices), std::move(states), up, height, weight);
}

// task.loss.handle_clearance (HandleClearanceLoss.h): needs a handle and an obstacle to keep
// apart, or the term would be zero whatever the parameters.
HandleClearanceLoss makeHandleClearanceLoss(const Scene& scene, const JsonReader& term) {
  const double weight = term.has("weight") ? term.at("weight").positive() : 1.0;
  const double margin = term.has("margin") ? term.at("margin").number(0.0) : 0.0;
  bool handles = false;
  for (const Cloth& cloth : scene.cloths)
    for (const Attachment& a : cloth.attachments) handles |= a.kind == Attachment::Kind::Handle;
  if (!handles || scene.obstacles.empty())
    term.fail(
        "needs a handle attachment and an obstacle (it keeps handle targets out of "
        "obstacles)");
  return HandleClearanceLoss(weight, margin);
}

}  // namespace

TaskLoss::TaskLoss(const Scene& scene) {
  if (!scene.task)
    throw InputError(scene.file, "task",
                     "the scene has no task (a task.loss is needed for gradients)");
  const nlohmann::json& loss = scene.task->loss;
  for (auto it = loss.begin(); it != loss.end(); ++it) {
    const std::string where = "task.loss." + it.key();
    const nlohmann::json& term = it.value();
    if (it.key() == "keypoints") {
      terms_.push_back(makeKeypointLoss(scene, JsonReader(term, scene.file, where)));
      continue;
    }
    if (it.key() == "hemline") {
      terms_.push_back(makeHemlineLoss(scene, JsonReader(term, scene.file, where)));
      continue;
    }
    if (it.key() == "handle_clearance") {
      clearance_ = makeHandleClearanceLoss(scene, JsonReader(term, scene.file, where));
      continue;
    }
    if (it.key() != "trajectory" && it.key() != "final")
      throw InputError(scene.file, where,
                       "unknown loss term '" + it.key() +
                           "' (trajectory, final, keypoints, hemline or handle_clearance)");
    const double weight = term.value("weight", 1.0);
    std::vector<int> vertices = readVertices(scene, term, where);
    TargetFile target = readTarget(scene, where + ".target", term["target"].get<std::string>());
    if (it.key() == "trajectory") {
      const int needed = scene.time.steps + 1;
      if (static_cast<int>(target.states.size()) < needed)
        throw InputError(scene.file, where + ".target",
                         "target has " + std::to_string(target.states.size()) +
                             " states; the scene simulates " + std::to_string(scene.time.steps) +
                             " steps and needs " + std::to_string(needed));
      terms_.push_back(
          std::make_unique<TrajectoryLoss>(std::move(target.states), std::move(vertices), weight));
    } else {
      terms_.push_back(std::make_unique<FinalFrameLoss>(std::move(target.states.back()),
                                                        std::move(vertices), weight));
    }
  }
}

double TaskLoss::value(const Scene& scene, const Trajectory& trajectory) const {
  double sum = 0.0;
  for (const auto& t : terms_) sum += t->value(trajectory);
  if (clearance_) sum += clearance_->value(scene);
  return sum;
}

void TaskLoss::addParameterGradient(const Scene& scene,
                                    const std::vector<SceneParameter>& parameters,
                                    Eigen::VectorXd& gradient) const {
  if (clearance_) clearance_->addParameterGradient(scene, parameters, gradient);
}

std::vector<NodeMatrix> TaskLoss::gradient(const Trajectory& trajectory) const {
  std::vector<NodeMatrix> g(trajectory.positions.size(),
                            NodeMatrix::Zero(trajectory.nodeCount(), 3));
  for (const auto& t : terms_) t->addGradient(trajectory, g);
  return g;
}

}  // namespace weft
