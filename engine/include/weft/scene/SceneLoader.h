#pragma once
#include <weft/scene/Scene.h>

#include <string>
#include <vector>

namespace weft {

struct SceneOverride {
  std::string path;   // JSON path, e.g. "obstacles.0.friction"
  std::string value;  // as typed: "0.2", "[0,-9.8,0]", "0,-9.8,0"
};

// One `--set` argument, "PATH=VALUE", split at its first '='. Text without '=' or with an empty
// path is an InputError `<file>: --set: expects PATH=VALUE, got '<text>'`.
SceneOverride parseSceneOverride(const std::string& text, const std::string& file);

// Reads, overrides and validates a scene file. Every problem is an InputError naming the file,
// the JSON path (or "--set <path>") and what is wrong. Builds the cloth meshes and checks them.
Scene loadScene(const std::string& file, const std::vector<SceneOverride>& overrides = {});

// The same for a document already parsed (what loadScene does after reading the file): applies
// the overrides, then validates. `file` names the document in error messages and `directory`
// resolves its relative mesh and target paths. The Python module loads scenes given as dicts
// with it.
Scene loadSceneDocument(nlohmann::json document, const std::string& file,
                        const std::string& directory,
                        const std::vector<SceneOverride>& overrides = {});

// Validates an already-parsed document (e.g. built by the editor or a test).
// `directory` resolves relative mesh and target paths.
Scene parseScene(const nlohmann::json& document, const std::string& file,
                 const std::string& directory);

// Resolves a path written in a scene: relative to the scene's folder first, then to the
// working directory. Returns the first that exists, or the scene-relative one.
std::string resolveScenePath(const std::string& directory, const std::string& path);

}  // namespace weft
