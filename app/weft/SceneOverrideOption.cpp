#include "SceneOverrideOption.h"

namespace weft::cli {

std::vector<SceneOverride> parseOverrides(const CommandLine& cl) {
  std::vector<SceneOverride> overrides;
  for (const std::string& s : cl.values("--set"))
    overrides.push_back(parseSceneOverride(s, cl.context()));
  return overrides;
}

}  // namespace weft::cli
