#pragma once
// What the Add menu and the import dialog add to the scene: a garment from a mesh file, an
// analytic obstacle (plane, sphere, capsule, box, cylinder), an obstacle from a mesh file. Each
// returns an error text ("" on success) and is one undo step; nothing is added when the mesh or
// shape is rejected.

#include "EditorDocument.h"
#include "MeshImport.h"

#include <string>
#include <vector>

namespace weft::editor {

class SceneAdditions {
 public:
  explicit SceneAdditions(EditorDocument& document) : document_(document) {}

  MeshImport previewGarment(const MeshImportOptions& options) const;  // what importGarment adds
  std::string importGarment(const MeshImportOptions& options);
  // Placed by newObstaclePlace: centred on the `selected` cloth nodes (global numbers), or
  // below the cloths when none are.
  std::string addObstacle(const std::string& shape, const std::vector<int>& selected = {});
  std::string importMeshObstacle(const MeshImportOptions& options);

 private:
  EditorDocument& document_;
};

}  // namespace weft::editor
