// Importing garments and mesh obstacles: the entry added to the document names the file, keeps
// the file's vertex count and order (through the engine's reader), carries scale and placement,
// and every unusable file is a clear message rather than a broken document. FBX and glTF files
// are written here by assimp's own exporter and imported as the editor's Import garment does.

#include <EditorSession.h>
#include <MeshImport.h>

#include "support/TempDir.h"

#include <weft/scene/SceneLoader.h>

#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Exporter.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace weft::editor {
namespace {

using test::TempDir;

// A 2 x 1 m strip in the XZ plane, six vertices listed out of order, four triangles.
std::string stripObj() {
  return "v 2 0 1\nv 0 0 0\nv 1 0 1\nv 2 0 0\nv 0 0 1\nv 1 0 0\n"
         "f 2 5 6\nf 6 5 3\nf 6 3 4\nf 4 3 1\n";
}

std::string stripPly() {
  return "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty "
         "float z\n"
         "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
         "2 0 1\n0 0 0\n1 0 1\n2 0 0\n0 0 1\n1 0 0\n3 1 4 5\n3 5 4 2\n3 5 2 3\n3 3 2 0\n";
}

// The same strip as glTF 2.0 with its buffer in a sibling .bin file.
std::string writeStripGltf(const TempDir& dir) {
  const float positions[6][3] = {{2, 0, 1}, {0, 0, 0}, {1, 0, 1}, {2, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  const std::uint16_t indices[12] = {1, 4, 5, 5, 4, 2, 5, 2, 3, 3, 2, 0};
  std::ofstream bin(dir.file("strip.bin"), std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
  bin.close();
  return dir.write("strip.gltf",
                   R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
    "buffers": [{"byteLength": 96, "uri": "strip.bin"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3",
                   "min": [0, 0, 0], "max": [2, 0, 1]},
                  {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]})");
}

TEST(MeshImport, GarmentEntryKeepsTheFileAndItsPlacement) {
  TempDir dir;
  const std::string scene = dir.file("scene.json");
  for (const std::string& file : {dir.write("strip.obj", stripObj()),
                                  dir.write("strip.ply", stripPly()), writeStripGltf(dir)}) {
    SCOPED_TRACE(file);
    MeshImportOptions o;
    o.file = file;
    o.scale = 0.5;
    o.rotateDeg = Vec3(90, 0, 0);
    o.translate = Vec3(0, 1, 0);
    const MeshImport r = prepareGarment(o, scene, dir.path());
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(r.vertices, 6);
    EXPECT_EQ(r.triangles, 4);
    EXPECT_EQ(r.fileUpper, Vec3(2, 0, 1));
    // Inside the scene's folder the file is named relative to it.
    const nlohmann::json& mesh = r.entry.at("mesh");
    EXPECT_EQ(mesh.at("file"), std::filesystem::path(file).filename().string());
    EXPECT_EQ(mesh.at("scale"), 0.5);
    EXPECT_EQ(mesh.at("transform").at("rotate_deg"), nlohmann::json::array({90.0, 0.0, 0.0}));
    EXPECT_EQ(mesh.at("transform").at("translate"), nlohmann::json::array({0.0, 1.0, 0.0}));
    EXPECT_TRUE(r.entry.contains("material"));
    // The entry is a cloth the loader accepts as it is, with the file's vertices in order.
    const Scene s = parseScene({{"time", {{"dt", 0.01}, {"steps", 1}}}, {"cloths", {r.entry}}},
                               scene, dir.path());
    ASSERT_EQ(s.cloths[0].mesh.vertexCount(), 6);
    // Vertex 0 of the file, (2, 0, 1): scaled by 0.5 to (1, 0, 0.5), turned 90 degrees about X
    // (z to -y) to (1, -0.5, 0), lifted by 1.
    EXPECT_NEAR(s.cloths[0].mesh.vertices(0, 0), 1.0, 1e-12);
    EXPECT_NEAR(s.cloths[0].mesh.vertices(0, 1), 1.0 - 0.5, 1e-12);
    EXPECT_NEAR(s.cloths[0].mesh.vertices(0, 2), 0.0, 1e-12);
  }
}

TEST(MeshImport, FitScalesToTheSizeAndCentresTheMesh) {
  TempDir dir;
  // The strip in centimetres: 200 x 100.
  const std::string file =
      dir.write("strip-cm.obj",
                "v 200 0 100\nv 0 0 0\nv 100 0 100\nv 200 0 0\nv 0 0 100\nv 100 0 0\n"
                "f 2 5 6\nf 6 5 3\nf 6 3 4\nf 4 3 1\n");
  MeshImportOptions o;
  o.file = file;
  o.fit = true;
  o.fitSize = 0.8;
  o.translate = Vec3(0, 0.5, 0);
  const MeshImport r = prepareGarment(o, "", dir.path());
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_DOUBLE_EQ(r.entry["mesh"]["scale"].get<double>(), 0.8 / 200.0);
  EXPECT_NEAR((r.upper - r.lower).maxCoeff(), 0.8, 1e-12);
  EXPECT_TRUE((0.5 * (r.lower + r.upper)).isApprox(Vec3(0, 0.5, 0), 1e-12));
  EXPECT_TRUE(r.warnings.empty());
  // A new document has no folder of its own: the file is named by its absolute path.
  EXPECT_TRUE(std::filesystem::path(r.entry["mesh"]["file"].get<std::string>()).is_absolute());

  // Without the fit, 2 m of centimetres is flagged as not metres (a warning, not an error).
  o.fit = false;
  const MeshImport unscaled = prepareGarment(o, "", dir.path());
  ASSERT_TRUE(unscaled.ok()) << unscaled.error;
  ASSERT_EQ(unscaled.warnings.size(), 1u);
  EXPECT_NE(unscaled.warnings[0].find("not in metres"), std::string::npos) << unscaled.warnings[0];
  // The units that make 200 file units a garment's size (0.05-5 m), nearest 0.5 m first:
  // millimetres (0.2 m), centimetres (2 m); not inches (5.08 m) or feet.
  ASSERT_EQ(unscaled.units.size(), 2u);
  EXPECT_EQ(unscaled.units[0].name, "millimetres");
  EXPECT_EQ(unscaled.units[1].name, "centimetres");
  EXPECT_TRUE(r.units.empty()) << "a fit is the user's choice of size";
  o.scale = 0.01;
  EXPECT_TRUE(prepareGarment(o, "", dir.path()).units.empty()) << "2 m is a garment's size";
}

TEST(MeshImport, PlausibleUnitsSpanTheSizeAskedNearestItsMiddleFirst) {
  // A T-shirt of 70 file units: centimetres (0.7 m) first, then inches (1.78 m), millimetres
  // (0.07 m); feet (21 m) and metres (70 m) left out.
  const std::vector<LengthUnit> shirt = plausibleUnits(70.0, 0.05, 5.0);
  ASSERT_EQ(shirt.size(), 3u);
  EXPECT_EQ(shirt[0].name, "centimetres");
  EXPECT_EQ(shirt[1].name, "inches");
  EXPECT_EQ(shirt[2].name, "millimetres");
  EXPECT_DOUBLE_EQ(shirt[1].metres, 0.0254);
  EXPECT_EQ(plausibleUnits(0.5, 0.05, 5.0)[0].name, "metres");
  EXPECT_TRUE(plausibleUnits(1e9, 0.05, 5.0).empty());
  EXPECT_TRUE(plausibleUnits(0.0, 0.05, 5.0).empty());
  EXPECT_TRUE(plausibleUnits(std::nan(""), 0.05, 5.0).empty());
}

TEST(MeshImport, UnusableFilesAreMessagesNamingTheFile) {
  TempDir dir;
  MeshImportOptions o;
  o.file = dir.file("missing.obj");
  MeshImport r = prepareGarment(o, "", dir.path());
  EXPECT_NE(r.error.find("missing.obj: file not found"), std::string::npos) << r.error;

  o.file = dir.write("garbage.ply", "this is not a mesh\n");
  r = prepareGarment(o, "", dir.path());
  EXPECT_NE(r.error.find("garbage.ply: cannot read the mesh"), std::string::npos) << r.error;

  o.file = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  r = prepareGarment(o, "", dir.path());
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.error.find("points.obj"), std::string::npos) << r.error;

  // A degenerate triangle: the loader's message, which names the way out (repair) ...
  // (vertices 2, 6 and 4 lie on one line).
  o.file = dir.write("degenerate.obj", stripObj() + "f 2 6 4\n");
  r = prepareGarment(o, "", dir.path());
  EXPECT_NE(r.error.find("degenerate"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("repair"), std::string::npos) << r.error;
  // ... and with repair the triangle is dropped, with a warning saying so.
  o.repair = true;
  r = prepareGarment(o, "", dir.path());
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.entry["mesh"]["repair"], true);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("dropped degenerate triangles"), std::string::npos) << r.warnings[0];

  o = MeshImportOptions();
  o.file = dir.write("strip.obj", stripObj());
  o.scale = -1.0;
  r = prepareGarment(o, "", dir.path());
  EXPECT_NE(r.error.find("scale"), std::string::npos) << r.error;
}

TEST(MeshImport, MeshObstacleEntry) {
  TempDir dir;
  MeshImportOptions o;
  o.file = dir.write("strip.obj", stripObj());
  o.smoothNormals = false;
  o.translate = Vec3(0, -0.2, 0);
  const MeshImport r = prepareMeshObstacle(o, dir.file("scene.json"), dir.path());
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.entry["mesh"]["file"], "strip.obj");
  EXPECT_EQ(r.entry["mesh"]["smooth_normals"], false);
  EXPECT_EQ(r.entry["mesh"]["transform"]["translate"], nlohmann::json::array({0.0, -0.2, 0.0}));
  EXPECT_EQ(r.entry["friction"], 0.3);
  EXPECT_FALSE(r.entry.contains("material"));

  o.file = dir.file("nothing.ply");
  EXPECT_FALSE(prepareMeshObstacle(o, "", dir.path()).ok());
}

TEST(MeshImport, PathsOutsideTheSceneFolderStayAbsolute) {
  TempDir dir, other;
  const std::string mesh = other.write("strip.obj", stripObj());
  EXPECT_EQ(documentRelativePath(mesh, dir.file("scene.json"), dir.path()),
            std::filesystem::weakly_canonical(mesh).generic_string());
  std::filesystem::create_directories(dir.file("meshes"));
  const std::string inside = dir.write("meshes/strip.obj", stripObj());
  EXPECT_EQ(documentRelativePath(inside, dir.file("scene.json"), dir.path()), "meshes/strip.obj");
}

// The position of vertex (i, j) of the 3 x 3 quad grid below, in file units.
Vec3 gridPoint(int i, int j) {
  return Vec3(0.25 + 0.5 * i, 0.1, 0.5 * j);
}

// A 3 x 3 quad grid in the XZ plane (16 vertices, vertex (i, j) = 4 j + i; 18 triangles), written
// by assimp's exporter as `format` (an Assimp::Exporter id) to `file`. Its coordinates are not
// round numbers in any unit, so a unit conversion on the way back would show.
void exportGrid(const std::string& format, const std::string& file) {
  aiScene scene;
  scene.mRootNode = new aiNode("grid");
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned[1]{0};
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial* [1] { new aiMaterial };
  aiMesh* mesh = new aiMesh;
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh* [1] { mesh };
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = 16;
  mesh->mVertices = new aiVector3D[16];
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const Vec3 p = gridPoint(i, j);
      mesh->mVertices[4 * j + i] = aiVector3D(float(p.x()), float(p.y()), float(p.z()));
    }
  mesh->mNumFaces = 18;
  mesh->mFaces = new aiFace[18];
  int f = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const unsigned a = unsigned(4 * j + i), b = a + 1, c = a + 5, d = a + 4;
      for (const auto& corners :
           {std::array<unsigned, 3>{a, d, c}, std::array<unsigned, 3>{a, c, b}}) {
        aiFace& face = mesh->mFaces[f++];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3]{corners[0], corners[1], corners[2]};
      }
    }
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(&scene, format, file), aiReturn_SUCCESS) << exporter.GetErrorString();
}

bool canExport(const std::string& format) {
  Assimp::Exporter exporter;
  for (std::size_t i = 0; i < exporter.GetExportFormatCount(); ++i)
    if (format == exporter.GetExportFormatDescription(i)->id) return true;
  return false;
}

// The grid written by assimp's exporter as `format` to `name` in `dir`, named as the import
// dialog's options name it; nullopt (after a test failure) when that could not be done.
std::optional<MeshImportOptions> exportedGrid(const TempDir& dir, const std::string& format,
                                              const std::string& name) {
  if (!canExport(format)) {
    ADD_FAILURE() << "this assimp cannot write " << format;
    return std::nullopt;
  }
  MeshImportOptions o;
  o.file = dir.file(name);
  exportGrid(format, o.file);
  if (::testing::Test::HasFatalFailure()) return std::nullopt;
  return o;
}

// Imports `o.file` as a new garment the way the dialog does; the new cloth's mesh (what the
// engine reads from the file), or nullptr after a test failure.
const TriangleMesh* importGarmentMesh(EditorSession& session, const MeshImportOptions& o) {
  const std::string error = session.additions().importGarment(o);
  const Scene* scene = session.document().scene();
  if (!error.empty() || !scene) {
    ADD_FAILURE() << "import: " << error << " " << session.document().validationError();
    return nullptr;
  }
  return &scene->cloths.back().mesh;
}

// FBX as the editor's Import garment reads it (assimp 5.2 here). Written as ASCII FBX ("fbxa"):
// the binary FBX assimp 5.2.5 writes is refused by its own reader ("FBX-Tokenize ... block offset
// is out of range"). assimp's reader gives a vertex per triangle corner (it unrolls the
// polygon-vertex list); the engine's reader joins corners at one position again, so the grid
// comes back connected: its 16 vertices (numbered in order of first use), its 18 triangles in
// order, at the file's coordinates (no unit scale: the exporter writes UnitScaleFactor 1).
TEST(MeshImport, FbxGarmentComesBackConnected) {
  TempDir dir;
  const std::optional<MeshImportOptions> exported = exportedGrid(dir, "fbxa", "grid.fbx");
  ASSERT_TRUE(exported);
  const MeshImportOptions& o = *exported;
  EditorSession session("");
  const MeshImport preview = session.additions().previewGarment(o);
  ASSERT_TRUE(preview.ok()) << preview.error;
  EXPECT_EQ(preview.triangles, 18);
  EXPECT_EQ(preview.vertices, 16);
  // The file's coordinates as written (in single precision): no unit scale applied.
  EXPECT_LT((preview.fileLower - gridPoint(0, 0)).norm(), 1e-6) << preview.fileLower.transpose();
  EXPECT_LT((preview.fileUpper - gridPoint(3, 3)).norm(), 1e-6) << preview.fileUpper.transpose();
  EXPECT_TRUE(preview.warnings.empty()) << preview.warnings.front();

  const TriangleMesh* imported = importGarmentMesh(session, o);
  ASSERT_NE(imported, nullptr);
  const TriangleMesh& cloth = *imported;
  EXPECT_EQ(cloth.vertexCount(), 16);
  ASSERT_EQ(cloth.triangleCount(), 18);
  // Triangle t of the file, corner by corner, at the exported positions (float precision).
  for (int t = 0; t < 18; ++t) {
    const int i = (t / 2) % 3, j = (t / 2) / 3;
    const Vec3 a = gridPoint(i, j), b = gridPoint(i + 1, j), c = gridPoint(i + 1, j + 1),
               d = gridPoint(i, j + 1);
    const Vec3 corners[2][3] = {{a, d, c}, {a, c, b}};
    for (int k = 0; k < 3; ++k)
      EXPECT_LT((cloth.vertices.row(cloth.triangles(t, k)).transpose() - corners[t % 2][k]).norm(),
                1e-6)
          << "triangle " << t << " corner " << k;
  }
  // Connected as the grid is: each interior edge is shared by two triangles.
  std::map<std::pair<int, int>, int> edges;
  for (int t = 0; t < 18; ++t)
    for (int k = 0; k < 3; ++k) {
      const int u = cloth.triangles(t, k), v = cloth.triangles(t, (k + 1) % 3);
      ++edges[{std::min(u, v), std::max(u, v)}];
    }
  int shared = 0;
  for (const auto& [edge, count] : edges) shared += count == 2;
  EXPECT_EQ(edges.size(), 33u);  // 24 grid edges + 9 diagonals
  EXPECT_EQ(shared, 21);         // 12 interior grid edges + 9 diagonals
}

// The same grid as glTF 2.0 from the same exporter: the file's vertices, in the file's order.
TEST(MeshImport, GltfGarmentFromAssimpsExporterKeepsItsVertices) {
  TempDir dir;
  const std::optional<MeshImportOptions> exported = exportedGrid(dir, "gltf2", "grid.gltf");
  ASSERT_TRUE(exported);
  EditorSession session("");
  const TriangleMesh* imported = importGarmentMesh(session, *exported);
  ASSERT_NE(imported, nullptr);
  const TriangleMesh& cloth = *imported;
  EXPECT_EQ(cloth.vertexCount(), 16);
  EXPECT_EQ(cloth.triangleCount(), 18);
  for (int v = 0; v < 16; ++v)
    EXPECT_LT((cloth.vertices.row(v).transpose() - gridPoint(v % 4, v / 4)).norm(), 1e-6)
        << "vertex " << v;
  EXPECT_TRUE(session.additions().previewGarment(*exported).warnings.empty());
}

}  // namespace
}  // namespace weft::editor
