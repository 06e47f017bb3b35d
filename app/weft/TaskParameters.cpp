#include "TaskParameters.h"

#include "SceneOverrideOption.h"
#include "SceneWarnings.h"

#include <weft/core/Error.h>
#include <weft/scene/SceneLoader.h>

namespace weft::cli {

TaskParameters loadTaskParameters(const CommandLine& cl, const std::string& file,
                                  const std::string& verb) {
  Scene scene = loadScene(file, parseOverrides(cl));
  printSceneWarnings(scene);
  if (!scene.task)
    throw InputError(file, "task",
                     "the scene has no task; " + verb + " needs task.loss and parameters");
  const std::vector<std::string> paths = cl.values("--param");
  ParameterSet parameters =
      paths.empty() ? ParameterSet::fromTask(scene) : ParameterSet::fromPaths(scene, paths);
  if (parameters.empty())
    throw InputError(file, "task.parameters",
                     std::string(verb == "gradcheck" ? "no parameters to check" : "no parameters") +
                         ": list them in task.parameters or give --param PATH");
  return {std::move(scene), std::move(parameters)};
}

}  // namespace weft::cli
