#pragma once
// Draws a FileBrowser inside a file dialog: an Up button and the folder shown, which opens the
// list of places to start from, then the folder's entries. A click on a folder opens it, a click
// on a file picks it (the dialog puts its path into the path field), a double click on a file
// picks it and confirms the dialog. Scripts click the items noted with the app: "browser:up",
// "browser:places", "browser:place:K" (the K-th place, while the list is open) and
// "browser:entry:NAME" (each entry drawn, ".." included).

#include "FileBrowser.h"

#include <string>
#include <vector>

namespace weft::editor {

class EditorApp;

struct FileBrowserEvent {
  enum class Kind { None, Moved, Picked, Confirmed };
  Kind kind = Kind::None;
  std::string path;  // the file picked or confirmed, or the folder moved to
};

// `picked`: the file the dialog's path field names, highlighted in the list when it is shown.
FileBrowserEvent drawFileBrowser(FileBrowser& browser, const std::vector<std::string>& places,
                                 const std::string& picked, EditorApp& app, float width,
                                 float height);

}  // namespace weft::editor
