#pragma once
// The modal dialog behind File > Import garment... and Add > Mesh obstacle...: the file path,
// its scale or a fit-to-size, rotation and translation (and, for a garment, dropping degenerate
// triangles), a Check button that reads the file and shows what would be added (vertex and
// triangle counts, size in metres, warnings) or why it cannot be, and Import. The file is typed
// or picked in a file browser listing the mesh formats Weft reads (FileBrowserView.h).

#include "FileBrowser.h"
#include "MeshImport.h"

namespace weft::editor {

class EditorApp;
class EditorSession;

class MeshImportDialog {
 public:
  enum class Kind { Garment, Obstacle };
  void open(Kind kind);
  void draw(EditorSession& session, EditorApp& app);
  // The dialog's file browser while the dialog is open (as last drawn), else null.
  const FileBrowser* browser() const { return visible_ ? &browser_ : nullptr; }

 private:
  Kind kind_ = Kind::Garment;
  bool requested_ = false;
  char path_[1024] = {};
  MeshImportOptions options_;
  MeshImport preview_;
  bool previewed_ = false;
  bool visible_ = false;
  FileBrowser browser_{{".obj", ".ply", ".gltf", ".glb", ".fbx", ".dae", ".stl", ".off", ".3ds"}};
};

}  // namespace weft::editor
