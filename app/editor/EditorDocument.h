#pragma once
// The editor's model of one scene file: the JSON document being edited, the Scene it validates
// to (or the loader's error), a dirty flag, undo/redo of document edits, atomic saving and the
// recent-files list. Pure C++: no window, no GL, unit tested on its own.
//
// Every edit goes through the document (never through the Scene), is validated by the same
// loader as `weft simulate`, and is kept even when the loader rejects it: the UI shows the
// loader's message and disables simulation until the document is valid again. Nothing is
// clamped or dropped silently.

#include <weft/model/ClothModel.h>
#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

class EditorDocument {
 public:
  // A new, unsaved document holding `document` (validated against the working directory).
  explicit EditorDocument(nlohmann::json document = defaultSceneDocument());

  // A small valid scene: a 1 m cloth of 16x16 quads hanging from two corners under gravity.
  static nlohmann::json defaultSceneDocument();

  // Replaces the document by the file's contents. Throws InputError when the file cannot be
  // read or is not JSON (the current document is then unchanged). A file that parses but does
  // not validate is opened, with its error shown (validationError()).
  void open(const std::string& file);

  // Saves to the current file (which must be set) or to `file` (save as: the document then
  // belongs to that file). Atomic: writes a temporary sibling, then renames it over the
  // target, so a crash never leaves a truncated scene. Throws InputError on failure. Save As into
  // another folder rewrites relative file references (meshes, targets) to name the same files
  // from there, in the document and its whole undo history (ScenePathRebase.h).
  void save();
  void saveAs(const std::string& file);

  const nlohmann::json& document() const { return document_; }
  const std::string& file() const { return file_; }  // empty for a new document
  std::string directory() const;                     // resolves relative paths in the scene
  std::string displayName() const;                   // file name, or "untitled"
  bool dirty() const { return state_ != savedState_; }
  // Increases with every change of the document (edit, undo, redo, open): caches compare it.
  long revision() const { return revision_; }

  // The validated scene, or null when the document does not validate.
  const Scene* scene() const { return scene_.get(); }
  std::shared_ptr<const Scene> sharedScene() const { return scene_; }
  // The validated scene's cloths as one nodal system (built once per validation), or null.
  const ClothModel* cloth() const { return cloth_.get(); }
  bool valid() const { return scene_ != nullptr; }
  const std::string& validationError() const { return error_; }

  // Sets the value at a dotted JSON path (as `--set` does). Missing intermediate objects are
  // created when `createParents` is true (e.g. "solver.pd_iterations" in a file without
  // "solver"). Returns an error text ("" on success); on error the document is unchanged.
  // `coalesce`: merge into the previous undo step when that one set the same path (one undo
  // step for a whole slider drag or typed number).
  std::string setValue(const std::string& path, const nlohmann::json& value, bool coalesce = false,
                       bool createParents = true);
  // Removes the key at `path` (e.g. "wind" to remove the wind module). Returns an error text.
  std::string removeValue(const std::string& path);
  // Any other edit: `change` mutates a copy of the document; one undo step named `label`.
  // Returns an error text when `change` throws (the document is then unchanged).
  std::string edit(const std::string& label, const std::function<void(nlohmann::json&)>& change);
  // The same, for an edit of the document and its sidecar together (one undo step; consecutive
  // edits with the same non-empty `coalesceKey` merge into one, as for a drag).
  std::string editWithSidecar(
      const std::string& label,
      const std::function<void(nlohmann::json& document, nlohmann::json& sidecar)>& change,
      const std::string& coalesceKey = "");

  // Editor data that belongs to the document but is not scene JSON (the scene format has no
  // place for it): the positions of final-frame targets, which the session writes as a .npy next
  // to the scene on save. Undo and redo restore it together with the document. open() empties
  // it; resetSidecar() sets it without an undo step (what was read alongside an opened file).
  const nlohmann::json& sidecar() const { return sidecar_; }
  void resetSidecar(nlohmann::json sidecar) { sidecar_ = std::move(sidecar); }

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  std::string undoLabel() const { return undo_.empty() ? "" : undo_.back().label; }
  std::string redoLabel() const { return redo_.empty() ? "" : redo_.back().label; }
  bool undo();
  bool redo();

  // Value at a path, or null when absent.
  const nlohmann::json* find(const std::string& path) const;

 private:
  struct Step {
    std::string label;
    std::string coalesceKey;  // the path of a setValue, "" otherwise
    nlohmann::json before;
    nlohmann::json sidecarBefore;
    long beforeState = 0;  // identity of the document state `before`
  };
  void commit(std::string label, std::string coalesceKey, nlohmann::json after,
              nlohmann::json sidecarAfter, bool coalesce);
  void revalidate();
  bool restore(std::vector<Step>& from, std::vector<Step>& to);  // undo or redo

  nlohmann::json document_;
  nlohmann::json sidecar_ = nlohmann::json::object();
  std::string file_;
  std::shared_ptr<const Scene> scene_;
  std::shared_ptr<const ClothModel> cloth_;
  std::string error_;
  long revision_ = 0;
  // Identity of the current document state: undo/redo restore earlier identities, so the
  // document is clean again when it is back at the saved state.
  long state_ = 0, savedState_ = 0, nextState_ = 1;
  std::vector<Step> undo_, redo_;
  static constexpr std::size_t kMaxUndo = 200;
};

// The most recently used scene files, most recent first, without duplicates, at most `limit`,
// persisted as a JSON list in `storeFile` (an unreadable store starts empty).
class RecentFiles {
 public:
  explicit RecentFiles(std::string storeFile, std::size_t limit = 8);
  // $XDG_CONFIG_HOME/weft/recent-files.json, or ~/.config/weft/recent-files.json.
  static std::string defaultStoreFile();

  const std::vector<std::string>& files() const { return files_; }
  void add(const std::string& file);  // made absolute, moved to the front, saved
  void remove(const std::string& file);

 private:
  void load();
  void store() const;
  std::string storeFile_;
  std::size_t limit_;
  std::vector<std::string> files_;
};

}  // namespace weft::editor
