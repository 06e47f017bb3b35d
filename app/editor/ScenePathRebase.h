#pragma once
// Save As into another folder: a scene names its files (mesh files, task targets) relative to
// its own folder, so when the scene moves, each relative reference is rewritten to name the same
// file from the new folder. Pure functions on the JSON document: no window, unit tested.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

// The JSON paths of every file reference in `document` that the engine resolves against the
// scene's folder (SceneLoader's readMeshFile, TaskLoss's targets): cloths.N.mesh.file,
// obstacles.N.mesh.file, task.loss.trajectory.target, task.loss.final.target and
// task.loss.keypoints.points.N.target. Only string values are listed.
std::vector<std::string> sceneFileReferences(const nlohmann::json& document);

// Rewrites every relative reference of `document` so that, read from `toDirectory`, it names the
// file it named from `fromDirectory` (found as the loader finds it, resolveScenePath), as a path
// relative to `toDirectory` (lexically: symbolic links are not followed). Absolute references,
// references to files that do not exist, and the JSON paths in `keep` stay as they are. Nothing
// changes when both name the same folder. Returns the JSON paths that changed.
std::vector<std::string> rebaseSceneFiles(nlohmann::json& document,
                                          const std::string& fromDirectory,
                                          const std::string& toDirectory,
                                          const std::vector<std::string>& keep = {});

}  // namespace weft::editor
