#include "BuildRecord.h"

namespace weft::bench {

bool isKnownBuild(const nlohmann::json& build) {
  return build.is_object() && build.value("commit", nlohmann::json()).is_string();
}

std::string describeBuild(const nlohmann::json& build) {
  if (!isKnownBuild(build)) return "an unknown build (no git)";
  std::string s = "commit " + build["commit"].get<std::string>().substr(0, 12);
  const nlohmann::json modified = build.value("modified", nlohmann::json());
  if (modified.is_string())
    s += " with uncommitted changes (diff " + modified.get<std::string>().substr(0, 12) + ")";
  return s;
}

}  // namespace weft::bench
