#pragma once
// The `--set PATH=VALUE` option shared by the verbs that load a scene (simulate, render).

#include "CommandLine.h"

#include <weft/scene/SceneLoader.h>

#include <vector>

namespace weft::cli {

// Every --set of the command line as a scene override (parseSceneOverride: a value without '='
// is a usage error).
std::vector<SceneOverride> parseOverrides(const CommandLine& cl);

}  // namespace weft::cli
