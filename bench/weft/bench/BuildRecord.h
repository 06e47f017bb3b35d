#pragma once
// A build's record as stored with results (the `weft` tool makes it: app/weft/BuildInfo.h):
// {"commit", "engine", "app", "assets", "modified"}, nulls for unknown or unmodified. What the
// run store of `weft bench applications` compares on resume and names in its report.

#include <nlohmann/json.hpp>

#include <string>

namespace weft::bench {

// Whether `build` names a commit: false for a missing record or a build without git, which
// cannot be compared.
bool isKnownBuild(const nlohmann::json& build);

// One line: "commit <12 hex>[ with uncommitted changes (diff <12 hex>)]" or "an unknown build
// (no git)".
std::string describeBuild(const nlohmann::json& build);

}  // namespace weft::bench
