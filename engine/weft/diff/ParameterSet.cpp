#include <weft/diff/ParameterSet.h>

#include <weft/core/Error.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

namespace weft {

ParameterSet ParameterSet::fromPaths(const Scene& scene, const std::vector<std::string>& paths) {
  ParameterSet set;
  for (const std::string& p : paths)
    set.parameters_.push_back(resolveSceneParameter(scene, p, "--param " + p));
  return set;
}

ParameterSet ParameterSet::fromTask(const Scene& scene) {
  ParameterSet set;
  if (!scene.task) return set;
  for (std::size_t i = 0; i < scene.task->parameters.size(); ++i)
    set.parameters_.push_back(resolveSceneParameter(scene, scene.task->parameters[i],
                                                    "task.parameters." + std::to_string(i)));
  return set;
}

Eigen::VectorXd ParameterSet::values(const Scene& scene) const {
  Eigen::VectorXd v(size());
  for (int i = 0; i < size(); ++i) v[i] = parameterValue(scene, parameters_[i]);
  return v;
}

Scene ParameterSet::withValues(const Scene& scene, const Eigen::VectorXd& values) const {
  Scene changed = scene;
  for (int i = 0; i < size(); ++i) setParameterValue(changed, parameters_[i], values[i]);
  return changed;
}

std::shared_ptr<const Model> ParameterSet::compile(const Scene& scene,
                                                   const Eigen::VectorXd& values) const {
  return Model::compile(withValues(scene, values));
}

Scene withDocumentValue(const Scene& scene, const std::string& path, const nlohmann::json& value) {
  nlohmann::json doc = scene.document;
  const std::string err = setJsonPath(doc, path, value);
  if (!err.empty()) throw InputError(scene.file, path, err);
  return parseScene(doc, scene.file, scene.directory);
}

}  // namespace weft
