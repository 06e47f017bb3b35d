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
  const char* appTree;       // ... of app/weft/ and bench/ (the CLI and its benchmarks; the SHA-1
                             // of both tree hashes, cmake/BuildInfo.cmake)
  const char* assetsTree;    // ... of assets/ (task scenes, meshes, targets)
  const char* modification;  // SHA-1 of `git diff HEAD` over those folders; empty: unmodified
};

const BuildInfo& buildInfo();

// {"commit", "engine", "app", "assets", "modified"}: nulls for unknown or unmodified (compared
// and described by bench/weft/bench/BuildRecord.h).
nlohmann::json buildInfoJson();

}  // namespace weft::cli
