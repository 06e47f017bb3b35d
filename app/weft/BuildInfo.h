#pragma once
// The sources this build of `weft` was made from (cmake/BuildInfo.cmake writes the values at
// every build). Stored with long comparisons (bench applications' settings.json) and reports
// (optimize's result.json), printed by `weft --version`. Empty strings: unknown (no git).

#include <nlohmann/json.hpp>

#include <string>

namespace weft::cli {

struct BuildInfo {
  const char* commit;        // git commit the build started from
  const char* engineTree;    // git tree hash of engine/ at that commit
  const char* appTree;       // ... of app/weft/ (the CLI and its benchmarks)
  const char* assetsTree;    // ... of assets/ (task scenes, meshes, targets)
  const char* modification;  // SHA-1 of `git diff HEAD` over those folders; empty: unmodified
};

const BuildInfo& buildInfo();

// {"commit", "engine", "app", "assets", "modified"}: nulls for unknown or unmodified.
nlohmann::json buildInfoJson();

// Whether `build` (buildInfoJson's form, as stored) names a commit: false for a missing record
// or a build without git, which cannot be compared.
bool isKnownBuild(const nlohmann::json& build);

// One line: "commit <12 hex>[ with uncommitted changes (diff <12 hex>)]" or "an unknown build
// (no git)".
std::string describeBuild(const nlohmann::json& build);

}  // namespace weft::cli
