#pragma once
// Final-frame targets as the editor edits them: chosen vertices and where each should end up,
// for the task's `final` loss term (weight * sum |x_N,i - target_i|^2, FinalFrameLoss).
//
// The scene format keeps target positions in a .npy file (task.loss.final {target, vertices}),
// not inline. So the editor keeps the positions in the document's sidecar, edits them together
// with task.loss.final in one undo step, and writes the .npy next to the scene when it is saved:
//
//   sidecar: {"final_targets": {"file": "<scene>-final-target.npy",
//                               "positions": {"<global vertex>": [x, y, z], ...}}}
//   scene:   "task": {"loss": {"final": {"target": "<scene>-final-target.npy",
//                                         "vertices": [sorted global vertices], "weight": w}}}
//
// The editor always writes its own file (never one the scene already pointed at, which may be a
// recorded run that a trajectory term also reads). Pure functions: no window, unit tested.

#include <weft/core/Types.h>
#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

struct FinalTarget {
  int node = -1;                 // global vertex (scene order)
  Vec3 position = Vec3::Zero();  // m
};

// The targets held by `sidecar`, sorted by node (empty when there are none).
std::vector<FinalTarget> finalTargets(const nlohmann::json& sidecar);
// The target file name the editor writes for a scene file: "<stem>-final-target.npy"
// ("untitled-final-target.npy" for a document without a file).
std::string finalTargetFileName(const std::string& sceneFile);

// Save As from `oldScene` to `newScene`: the name the editor's own target file takes. It follows
// the scene ("<stem>-final-target.npy"), so that a copy saved beside the original does not share,
// and overwrite, the original's file; a name the user chose (any other) is kept.
std::string finalTargetFileAfterSaveAs(const std::string& name, const std::string& oldScene,
                                       const std::string& newScene);
// Renames the sidecar's target file, and the final term naming it, by that rule.
void renameFinalTargetFile(nlohmann::json& document, nlohmann::json& sidecar,
                           const std::string& oldScene, const std::string& newScene);

// The target file the editor writes when `document` is saved: the sidecar holds targets and the
// final term names the sidecar's own file. "" otherwise (no targets, or targets read from a file
// the scene still names: that file is the scene's, not the editor's). The name is relative to the
// scene's folder wherever the scene is saved, since the file is written next to the scene.
std::string ownedFinalTargetFile(const nlohmann::json& document, const nlohmann::json& sidecar);

// Replaces the target set in `document` (task.loss.final, creating the task when needed) and in
// `sidecar`. An empty set removes the final term (and the task when nothing else is left in it).
// `fileName` is used when the sidecar does not name its file yet. A weight already in the scene
// is kept.
void setFinalTargets(nlohmann::json& document, nlohmann::json& sidecar,
                     std::vector<FinalTarget> targets, const std::string& fileName);

// For a scene just opened: the sidecar holding the targets of its final term when that term lists
// vertices and its file reads ([V, 3], or [S, V, 3] whose last state is used). Returns an empty
// object otherwise (the term is then shown from the file only, as before).
nlohmann::json readFinalTargets(const Scene& scene);

// The [V, 3] target array the loss reads: the target rows for listed vertices, `rest` elsewhere
// (the loss never looks at those; rest positions keep the file a plausible shape).
NodeMatrix finalTargetMatrix(const std::vector<FinalTarget>& targets, const NodeMatrix& rest);

// Writes that array as float64 .npy to `path`, atomically (a temporary sibling, then a rename).
// Throws InputError naming the path.
void writeTargetNpy(const std::string& path, const NodeMatrix& target);

}  // namespace weft::editor
