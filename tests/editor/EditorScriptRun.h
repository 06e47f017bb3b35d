#pragma once
// Running the real weft-editor binary on a script, as the editor's scripted tests do, and reading
// back the JSON files a script writes (states, saved scenes).

#include "support/Process.h"
#include "support/TempDir.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::test {

// Writes {"actions": actions} to dir/script.json and runs the editor headless on it at `size`
// (window pixels), with `dir` as the working directory and any further command-line `options`.
ProcessResult runEditor(const TempDir& dir, const nlohmann::json& actions,
                        const std::string& size = "960x600",
                        const std::vector<std::string>& options = {});

// The script point {"item": NAME}: where the last frame drew the named item (EditorApp.h).
inline nlohmann::json item(const std::string& name) {
  return {{"item", name}};
}

// The JSON file at `path`; fails the current test (and returns null) when it cannot be read.
nlohmann::json readJson(const std::string& path);

}  // namespace weft::test
