#include "SceneOverrideOption.h"

namespace weft::cli {

std::vector<SceneOverride> parseOverrides(const CommandLine& cl) {
  std::vector<SceneOverride> overrides;
  for (const std::string& s : cl.values("--set")) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) cl.fail("--set", "expects PATH=VALUE, got '" + s + "'");
    overrides.push_back({s.substr(0, eq), s.substr(eq + 1)});
  }
  return overrides;
}

}  // namespace weft::cli
