#include "ParameterOptimisation.h"

#include <weft/core/Error.h>
#include <weft/diff/SceneParameter.h>
#include <weft/scene/JsonPath.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace weft::editor {

ParameterOptimisation::ParameterOptimisation(EditorDocument& document, TaskTargets& targets)
    : document_(document), targets_(targets) {}

std::string ParameterOptimisation::start(const OptimizerRun::Setup& setup, bool paused) {
  return targets_.withHeldTargets(
      [&](const Scene& scene) { return optimizer_.start(scene, setup, paused); });
}

std::string ParameterOptimisation::setParameterValues(const std::string& label,
                                                      const std::vector<double>& values) {
  const std::vector<std::string>& paths = optimizer_.parameters();
  if (paths.empty() || values.size() != paths.size())
    return "there is no optimisation result to use";
  for (const std::string& path : paths) {
    const nlohmann::json* v = document_.find(path);
    if (!v || !v->is_number())
      return path + " is no longer a number in the scene: cannot write the result";
  }
  return document_.edit(label, [&](nlohmann::json& doc) {
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const std::string error = setJsonPath(doc, paths[i], values[i]);
      if (!error.empty()) throw std::runtime_error(paths[i] + ": " + error);
    }
  });
}

std::string ParameterOptimisation::applyResult() {
  const auto best = optimizer_.best();
  if (!best) return "the optimiser has no evaluation yet";
  return setParameterValues(
      "Apply optimised parameters (loss " +
          [&] {
            char text[32];
            std::snprintf(text, sizeof text, "%.3g", best->loss);
            return std::string(text);
          }() +
          ")",
      best->values);
}

std::string ParameterOptimisation::revertToStart() {
  return setParameterValues("Revert to the optimiser's start values", optimizer_.initialValues());
}

std::string ParameterOptimisation::addParameter(const std::string& path) {
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  if (!scene->task)
    return "the task has no loss yet: set targets or load a target motion first (Targets tab)";
  const std::vector<std::string>& chosen = scene->task->parameters;
  if (std::find(chosen.begin(), chosen.end(), path) != chosen.end())
    return path + " is already a parameter";
  const std::vector<std::string> offered = differentiableParameterPaths(*scene);
  if (std::find(offered.begin(), offered.end(), path) == offered.end()) {
    try {  // the engine's own reason (no such value, not differentiable)
      resolveSceneParameter(*scene, path, "task.parameters");
    } catch (const InputError& e) {
      return e.reason();
    }
    return path + " is not a parameter of this scene";
  }
  return document_.edit("Add parameter " + path, [&](nlohmann::json& doc) {
    nlohmann::json& list = doc["task"]["parameters"];
    if (!list.is_array()) list = nlohmann::json::array();
    list.push_back(path);
  });
}

std::string ParameterOptimisation::removeParameter(const std::string& path) {
  const nlohmann::json* list = document_.find("task.parameters");
  if (!list || !list->is_array() || std::find(list->begin(), list->end(), path) == list->end())
    return path + " is not a parameter of the task";
  return document_.edit("Remove parameter " + path, [&](nlohmann::json& doc) {
    nlohmann::json& task = doc["task"];
    nlohmann::json kept = nlohmann::json::array();
    for (const nlohmann::json& p : task["parameters"])
      if (p != path) kept.push_back(p);
    if (kept.empty())
      task.erase("parameters");
    else
      task["parameters"] = kept;
    if (task.contains("bounds") && task["bounds"].is_object()) {
      task["bounds"].erase(path);
      if (task["bounds"].empty()) task.erase("bounds");
    }
  });
}

}  // namespace weft::editor
