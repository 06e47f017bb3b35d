#pragma once
// Unsaved work kept on disk while the editor runs, so that a crash, a killed process or a power
// cut loses at most a few seconds of edits: the document of a dirty session is written
// atomically to a recovery file (one per scene file, named after it and a hash of its absolute
// path; "untitled" for a new document) at most every `interval` seconds while it changes, and
// the file goes once the document is clean again (saved, or undone to its saved state), belongs
// to another file, or its changes are discarded. A later run lists what an earlier one left
// (recoveries()) and offers to restore it. The sidecar (final-target positions) is not kept.
// No window: unit tested.

#include "EditorDocument.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

struct Recovery {
  std::string path;       // the recovery file
  std::string sceneFile;  // the scene it belongs to, "" for an untitled document
  std::string savedAt;    // UTC, ISO 8601
  nlohmann::json document;
};

class Autosave {
 public:
  // `folder` "" turns autosaving off (scripted runs unless told otherwise).
  explicit Autosave(std::string folder = "", double interval = 5.0);
  // $XDG_STATE_HOME/weft/recovery, or ~/.local/state/weft/recovery.
  static std::string defaultFolder();
  bool enabled() const { return !folder_.empty(); }
  const std::string& folder() const { return folder_; }

  // Every frame, `seconds` after the last call: writes the document when it is dirty, changed
  // since the last write and `interval` seconds have passed since that write; removes this
  // run's recovery file when the document is clean or belongs to another file. Failing to write
  // is not an error (a convenience must not disturb editing); lastError() says why.
  void tick(const EditorDocument& document, double seconds);
  // True while a change waits for its write (the window keeps drawing until it is done).
  bool pending(const EditorDocument& document) const;
  // The user dropped the unsaved changes (Discard): the recovery file goes.
  void discardCurrent();

  // What the folder holds, newest first; unreadable files are left out.
  std::vector<Recovery> recoveries() const;
  static void remove(const Recovery& recovery);

  const std::string& lastError() const { return error_; }

 private:
  std::string fileFor(const std::string& sceneFile) const;

  std::string folder_;
  double interval_;
  double sinceWrite_ = 1e300;  // seconds since the last write (none yet: long ago)
  long writtenRevision_ = -1;
  std::string written_;  // this run's recovery file, "" when none is on disk
  std::string error_;
};

}  // namespace weft::editor
