#pragma once
// The scene and parameters of the gradient verbs (gradient, gradcheck): the scene loaded with
// the --set overrides and its warnings printed, then the --param paths, or else the task's.
// Throws InputError for a scene without a task or with no parameters to differentiate.

#include "CommandLine.h"

#include <weft/diff/ParameterSet.h>
#include <weft/scene/Scene.h>

#include <string>

namespace weft::cli {

struct TaskParameters {
  Scene scene;
  ParameterSet parameters;
};

// `verb` names the command in the messages.
TaskParameters loadTaskParameters(const CommandLine& cl, const std::string& file,
                                  const std::string& verb);

}  // namespace weft::cli
