#pragma once
// Importing a mesh file into the scene document: a garment as a new cloth
// (cloths[].mesh {file, scale, transform, repair}) or a mesh obstacle (obstacles[].mesh {file,
// scale, transform, smooth_normals}). The file is read with the engine's MeshReader (OBJ through
// tinyobjloader; PLY and glTF by Weft itself; FBX and the rest through assimp) and the new entry
// is validated by
// the same strict loader as a scene, on its own, before it touches the document: an unreadable
// file, an empty mesh, degenerate triangles or vertices in no triangle give a message naming
// the file and the problem, and the document is left as it was. No window: unit tested.

#include <weft/core/Types.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

struct MeshImportOptions {
  std::string file;    // absolute, or relative to the working directory
  double scale = 1.0;  // file units to metres, applied first
  // Instead of `scale`: scale the mesh so that its largest extent is `fitSize` metres, and move
  // its bounding-box centre to `translate` (garment files come in any unit: cm, inches, ...).
  bool fit = false;
  double fitSize = 1.0;
  Vec3 rotateDeg = Vec3::Zero();  // about X, then Y, then Z (the scene's transform)
  Vec3 translate = Vec3::Zero();
  bool repair = false;  // cloth: drop degenerate triangles (with a warning) instead of failing
  bool smoothNormals = true;  // obstacle: contact normals interpolated across triangles
};

// A length unit a mesh file may be written in.
struct LengthUnit {
  std::string name;  // "metres", "centimetres", "millimetres", "inches", "feet"
  double metres;     // one unit in metres: the import's scale
};

// The units under which a file whose largest extent is `fileExtent` (in its own units) spans
// [lo, hi] metres, the one whose size lies nearest the span's geometric middle first.
std::vector<LengthUnit> plausibleUnits(double fileExtent, double lo, double hi);

struct MeshImport {
  std::string error;                  // empty when the entry can be added
  std::vector<std::string> warnings;  // the loader's, a unit check, and loose triangles (garments)
  // When the placed size is implausible for what is imported (a garment outside 0.05-5 m, an
  // obstacle outside 0.01-20 m) and no fit was asked for: the units that would make it
  // plausible, for the dialog to offer (plausibleUnits).
  std::vector<LengthUnit> units;
  int vertices = 0, triangles = 0;
  Vec3 fileLower = Vec3::Zero(), fileUpper = Vec3::Zero();  // bounding box in file units
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();          // after scale and transform (m)
  nlohmann::json entry;                                     // the cloths[] or obstacles[] entry
  bool ok() const { return error.empty(); }
};

// `documentFile` is the scene's file ("" for a new document) and `documentDirectory` the folder
// its relative paths resolve against. The entry names the mesh relative to that folder when the
// mesh lies inside it, else by its absolute path (so saving the scene elsewhere keeps it found).
MeshImport prepareGarment(const MeshImportOptions& options, const std::string& documentFile,
                          const std::string& documentDirectory);
MeshImport prepareMeshObstacle(const MeshImportOptions& options, const std::string& documentFile,
                               const std::string& documentDirectory);

// How a scene names `file`: relative to `documentDirectory` when the file lies inside it and the
// document has a file, else by its absolute path (so saving the scene elsewhere keeps it found).
std::string documentRelativePath(const std::string& file, const std::string& documentFile,
                                 const std::string& documentDirectory);

// The material a newly imported garment starts with (the default scene's cloth).
nlohmann::json defaultGarmentMaterial();

}  // namespace weft::editor
