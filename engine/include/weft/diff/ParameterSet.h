#pragma once
// The parameters a gradient is taken with respect to, in a fixed order: from `--param` options
// or from the scene's task.parameters. Each path is resolved once; setting values writes them into
// a copy of the typed scene (setParameterValue), checked as the loader checks a file, so a value
// out of range (a negative density, a zero wind direction) is the same InputError a scene file
// would give, and no file is read again.

#include <weft/diff/SceneParameter.h>
#include <weft/physics/Model.h>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace weft {

class ParameterSet {
 public:
  ParameterSet() = default;
  // Resolves explicit paths (reported as "--param <path>" on error).
  static ParameterSet fromPaths(const Scene& scene, const std::vector<std::string>& paths);
  // Resolves the scene's task.parameters (reported as "task.parameters.<i>").
  static ParameterSet fromTask(const Scene& scene);

  int size() const { return static_cast<int>(parameters_.size()); }
  bool empty() const { return parameters_.empty(); }
  const SceneParameter& operator[](int i) const { return parameters_[i]; }
  const std::vector<SceneParameter>& parameters() const { return parameters_; }

  Eigen::VectorXd values(const Scene& scene) const;
  // A copy of `scene` with the parameters set to `values` (typed setters; reads no file).
  Scene withValues(const Scene& scene, const Eigen::VectorXd& values) const;
  // That copy compiled: the model one objective evaluation simulates and differentiates.
  std::shared_ptr<const Model> compile(const Scene& scene, const Eigen::VectorXd& values) const;

 private:
  std::vector<SceneParameter> parameters_;
};

// A new validated scene with any JSON path set to a value, through the strict loader (parseScene,
// which reads the scene's mesh files again): for edits that are not task parameters, such as a
// grid resolution.
Scene withDocumentValue(const Scene& scene, const std::string& path, const nlohmann::json& value);

}  // namespace weft
