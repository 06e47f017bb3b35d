#include "EditorDocument.h"

#include "FinalTargets.h"
#include "ScenePathRebase.h"

#include <weft/contact/HandleObstacleCheck.h>
#include <weft/core/Error.h>
#include <weft/io/AtomicFile.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace weft::editor {

namespace fs = std::filesystem;

EditorDocument::EditorDocument(nlohmann::json document) : document_(std::move(document)) {
  revalidate();
}

nlohmann::json EditorDocument::defaultSceneDocument() {
  return nlohmann::json::parse(R"({
    "name": "untitled",
    "time": { "dt": 0.01, "steps": 100 },
    "gravity": [0, -9.8, 0],
    "solver": { "pd_iterations": 100, "pd_tolerance": 1e-4 },
    "cloths": [ {
      "mesh": { "grid": { "size": [1.0, 1.0], "resolution": [16, 16] },
                "transform": { "rotate_deg": [90, 0, 0], "translate": [0, 1.0, 0] } },
      "material": { "density": 0.2, "stretch": 1000.0, "bend": 0.0001 },
      "attachments": [ { "vertices": [0, 16], "kind": "fixed" } ]
    } ]
  })");
}

void EditorDocument::open(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file, "-", "cannot open the file: " + std::string(std::strerror(errno)));
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range (1e400).
    throw InputError(file, "-", std::string("not valid JSON: ") + e.what());
  }
  if (!parsed.is_object()) throw InputError(file, "-", "a scene must be a JSON object");
  document_ = std::move(parsed);
  sidecar_ = nlohmann::json::object();
  file_ = file;
  undo_.clear();
  redo_.clear();
  state_ = savedState_ = nextState_++;
  ++revision_;
  revalidate();
}

void EditorDocument::save() {
  if (file_.empty()) throw InputError("untitled", "-", "the document has no file yet: use Save As");
  writeFileAtomically(file_, document_.dump(2) + "\n");
  savedState_ = state_;
}

void EditorDocument::saveAs(const std::string& file) {
  if (file.empty()) throw InputError("-", "-", "no file name given");
  const std::string from = directory();
  const std::string to = fs::absolute(file).parent_path().string();
  // Relative file references resolve against the scene's folder, so in another folder they are
  // rewritten to name the same files (ScenePathRebase.h). This is part of saving, not an undoable
  // edit: the document must equal the file just written (clean, and Save writes the same), and
  // undoing it could only bring back references that name nothing from the new folder. So the
  // whole history is rebased with it: every undo and redo state keeps naming the files it named.
  // The editor's own target file is not moved: it is written next to the scene, wherever that is,
  // under the new scene's name (FinalTargets.h, finalTargetFileAfterSaveAs).
  auto rebase = [&](nlohmann::json& document, nlohmann::json& sidecar) {
    renameFinalTargetFile(document, sidecar, file_, file);
    std::vector<std::string> keep;
    if (!ownedFinalTargetFile(document, sidecar).empty()) keep.push_back("task.loss.final.target");
    rebaseSceneFiles(document, from, to, keep);
  };
  nlohmann::json saved = document_, savedSidecar = sidecar_;
  rebase(saved, savedSidecar);
  writeFileAtomically(file, saved.dump(2) + "\n");  // throws: nothing has changed yet
  document_ = std::move(saved);
  sidecar_ = std::move(savedSidecar);
  for (std::vector<Step>* stack : {&undo_, &redo_})
    for (Step& step : *stack) rebase(step.before, step.sidecarBefore);
  const bool directoryChanged =
      fs::path(to).lexically_normal() != fs::path(from).lexically_normal();
  file_ = file;
  savedState_ = state_;
  // Relative references now resolve against the new folder (to the same files).
  if (directoryChanged) {
    ++revision_;
    revalidate();
  }
}

std::string EditorDocument::directory() const {
  if (file_.empty()) return fs::current_path().string();
  return fs::absolute(file_).parent_path().string();
}

std::string EditorDocument::displayName() const {
  return file_.empty() ? "untitled" : fs::path(file_).filename().string();
}

const nlohmann::json* EditorDocument::find(const std::string& path) const {
  return findJsonPath(document_, path);
}

std::string EditorDocument::setValue(const std::string& path, const nlohmann::json& value,
                                     bool coalesce, bool createParents) {
  nlohmann::json after = document_;
  if (createParents) {
    // Create missing objects along the way (never array elements).
    const auto parts = splitJsonPath(path);
    nlohmann::json* node = &after;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (node->is_object()) {
        if (!node->contains(parts[i])) (*node)[parts[i]] = nlohmann::json::object();
        node = &(*node)[parts[i]];
      } else if (node->is_array()) {
        char* end = nullptr;
        const unsigned long index = std::strtoul(parts[i].c_str(), &end, 10);
        if (parts[i].empty() || *end != '\0' || index >= node->size()) break;
        node = &(*node)[index];
      } else {
        break;
      }
    }
  }
  const std::string error = setJsonPath(after, path, value);
  if (!error.empty()) return path + ": " + error;
  if (after == document_) return "";
  commit("Set " + path, path, std::move(after), sidecar_, coalesce);
  return "";
}

std::string EditorDocument::removeValue(const std::string& path) {
  const auto parts = splitJsonPath(path);
  if (parts.empty()) return path + ": empty path";
  nlohmann::json after = document_;
  nlohmann::json* parent = &after;
  if (parts.size() > 1) {
    std::string parentPath = parts[0];
    for (std::size_t i = 1; i + 1 < parts.size(); ++i) parentPath += "." + parts[i];
    parent = findJsonPath(after, parentPath);
  }
  if (!parent) return path + ": unknown path";
  if (parent->is_object()) {
    if (parent->erase(parts.back()) == 0) return path + ": unknown path";
  } else if (parent->is_array()) {
    char* end = nullptr;
    const unsigned long index = std::strtoul(parts.back().c_str(), &end, 10);
    if (*end != '\0' || index >= parent->size()) return path + ": index out of range";
    parent->erase(index);
  } else {
    return path + ": unknown path";
  }
  commit("Remove " + path, "", std::move(after), sidecar_, false);
  return "";
}

std::string EditorDocument::edit(const std::string& label,
                                 const std::function<void(nlohmann::json&)>& change) {
  nlohmann::json after = document_;
  try {
    change(after);
  } catch (const std::exception& e) {
    return label + ": " + e.what();
  }
  if (after == document_) return "";
  commit(label, "", std::move(after), sidecar_, false);
  return "";
}

std::string EditorDocument::editWithSidecar(
    const std::string& label, const std::function<void(nlohmann::json&, nlohmann::json&)>& change,
    const std::string& coalesceKey) {
  nlohmann::json after = document_, sidecarAfter = sidecar_;
  try {
    change(after, sidecarAfter);
  } catch (const std::exception& e) {
    return label + ": " + e.what();
  }
  if (after == document_ && sidecarAfter == sidecar_) return "";
  commit(label, coalesceKey, std::move(after), std::move(sidecarAfter), !coalesceKey.empty());
  return "";
}

void EditorDocument::commit(std::string label, std::string coalesceKey, nlohmann::json after,
                            nlohmann::json sidecarAfter, bool coalesce) {
  const bool merge = coalesce && !coalesceKey.empty() && !undo_.empty() &&
                     undo_.back().coalesceKey == coalesceKey && state_ != savedState_;
  if (!merge) {
    undo_.push_back(Step{std::move(label), std::move(coalesceKey), document_, sidecar_, state_});
    if (undo_.size() > kMaxUndo) undo_.erase(undo_.begin());
  }
  redo_.clear();
  sidecar_ = std::move(sidecarAfter);
  document_ = std::move(after);
  state_ = nextState_++;
  ++revision_;
  revalidate();
}

bool EditorDocument::undo() {
  return restore(undo_, redo_);
}

bool EditorDocument::redo() {
  return restore(redo_, undo_);
}

bool EditorDocument::restore(std::vector<Step>& from, std::vector<Step>& to) {
  // Undo and redo are one move: the newest step of one stack is restored, and the current state
  // becomes the newest step of the other.
  if (from.empty()) return false;
  Step step = std::move(from.back());
  from.pop_back();
  to.push_back(Step{step.label, "", document_, sidecar_, state_});
  document_ = std::move(step.before);
  sidecar_ = std::move(step.sidecarBefore);
  state_ = step.beforeState;
  ++revision_;
  revalidate();
  return true;
}

void EditorDocument::revalidate() {
  try {
    Scene scene = parseScene(document_, file_.empty() ? displayName() : file_, directory());
    // The engine's checks of a valid scene (a handle driven into an obstacle), shown with the
    // loader's warnings as the command line prints them.
    for (std::string& w : handlesEnteringObstacles(scene)) scene.warnings.push_back(std::move(w));
    cloth_ = std::make_shared<const ClothModel>(buildClothModel(scene));
    scene_ = std::make_shared<const Scene>(std::move(scene));
    error_.clear();
  } catch (const std::exception& e) {
    // InputError carries "<file>: <path>: <what>"; anything else is still a message, never a crash.
    scene_.reset();
    cloth_.reset();
    error_ = e.what();
  }
}

RecentFiles::RecentFiles(std::string storeFile, std::size_t limit)
    : storeFile_(std::move(storeFile)), limit_(limit) {
  load();
}

std::string RecentFiles::defaultStoreFile() {
  const char* config = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  fs::path base = config && *config ? fs::path(config) : fs::path(home ? home : ".") / ".config";
  return (base / "weft" / "recent-files.json").string();
}

void RecentFiles::add(const std::string& file) {
  std::error_code ec;
  const std::string absolute = fs::absolute(file, ec).lexically_normal().string();
  files_.erase(std::remove(files_.begin(), files_.end(), absolute), files_.end());
  files_.insert(files_.begin(), absolute);
  if (files_.size() > limit_) files_.resize(limit_);
  store();
}

void RecentFiles::remove(const std::string& file) {
  files_.erase(std::remove(files_.begin(), files_.end(), file), files_.end());
  store();
}

void RecentFiles::load() {
  files_.clear();
  std::ifstream in(storeFile_);
  if (!in) return;
  try {
    const nlohmann::json list = nlohmann::json::parse(in);
    for (const auto& item : list)
      if (item.is_string() && files_.size() < limit_) files_.push_back(item.get<std::string>());
  } catch (const std::exception&) {
    files_.clear();  // a damaged list is not worth an error: it is rebuilt as files are opened
  }
}

void RecentFiles::store() const {
  if (storeFile_.empty()) return;
  std::error_code ec;
  fs::create_directories(fs::path(storeFile_).parent_path(), ec);
  try {
    writeFileAtomically(storeFile_, nlohmann::json(files_).dump(2) + "\n");
  } catch (const std::exception&) {
    // The recent list is a convenience; failing to store it must not disturb editing.
  }
}

}  // namespace weft::editor
