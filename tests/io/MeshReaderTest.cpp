// Mesh files keep the file's vertex order and count (no welding, splitting or reordering):
// attachments, targets and outputs refer to vertices by index. OBJ goes through tinyobjloader
// (here), PLY and glTF through Weft's own readers (PlyReaderTest.cpp, GltfReaderTest.cpp), the
// rest through assimp (tests/editor/MeshImportTest.cpp); every file here is written by the test.

#include "MeshFileFixtures.h"

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>
#include <weft/io/ObjWriter.h>
#include <weft/mesh/GridMesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

namespace weft {
namespace {

using test::expectScrambledStrip;
using test::kPositions;
using test::kTriangles;
using test::TempDir;

std::string scrambledObj(const std::string& faceStyle) {
  std::ostringstream s;
  s << "# scrambled strip\n";
  for (const auto& p : kPositions) s << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  s << "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 1 0\n";
  for (const auto& t : kTriangles) {
    s << "f";
    for (int k = 0; k < 3; ++k) {
      const int v = t[k] + 1;
      if (faceStyle == "plain") s << " " << v;
      if (faceStyle == "full") s << " " << v << "/" << (k + 1) << "/1";
      if (faceStyle == "normal") s << " " << v << "//1";
      if (faceStyle == "relative") s << " " << (t[k] - 7);  // -1 is the last vertex so far
    }
    s << "\n";
  }
  return s.str();
}

TEST(MeshReader, ObjKeepsVertexOrderCountAndFaceIndices) {
  TempDir dir;
  for (const char* style : {"plain", "full", "normal", "relative"}) {
    SCOPED_TRACE(style);
    expectScrambledStrip(readMesh(dir.write(std::string(style) + ".obj", scrambledObj(style))));
  }
}

TEST(MeshReader, ObjPolygonsAreFanTriangulatedWithoutNewVertices) {
  TempDir dir;
  const std::string path = dir.write("quad.obj",
                                     "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 0 1.5\n"
                                     "f 4 3 5\n"
                                     "f 1 4 3 2\n");
  test::expectTriangleAndQuadFan(readMesh(path));
}

TEST(MeshReader, ObjGroupsShareOneVertexList) {
  TempDir dir;
  const std::string path = dir.write("groups.obj",
                                     "o a\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n"
                                     "o b\nv 1 0 1\nf 2 3 4\n");
  const TriangleMesh mesh = readMesh(path);
  ASSERT_EQ(mesh.vertexCount(), 4);
  ASSERT_EQ(mesh.triangleCount(), 2);
  EXPECT_EQ(mesh.triangles.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.triangles.row(1), Eigen::RowVector3i(1, 2, 3));
}

TEST(MeshReader, ObjWriterOutputReadsBackWithinAnUlp) {
  TempDir dir;
  TriangleMesh grid = makeGrid(1.3, 0.7, 3, 2);
  grid.vertices.col(1).setConstant(1.0 / 3.0);  // not exactly representable in short decimal
  writeObj(dir.file("grid.obj"), grid, {{"first", 0}, {"second", 5}});
  const TriangleMesh back = readMesh(dir.file("grid.obj"));
  // %.17g identifies every double, but tinyobjloader's own number parser is not correctly
  // rounded: allow it one unit in the last place.
  for (int i = 0; i < grid.vertexCount(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(back.vertices(i, c), grid.vertices(i, c), 2.3e-16 * std::abs(grid.vertices(i, c)))
          << "vertex " << i;
  EXPECT_EQ(back.triangles, grid.triangles);
}

TEST(MeshReader, ObjRejectsMalformedCoordinates) {
  // tinyobjloader reads an unparsable number as 0; a silently moved vertex is worse than an error.
  TempDir dir;
  const std::string cases[] = {
      "v 0 0 0\nv 1 0 abc\nv 0 1 0\nf 1 2 3\n",
      "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
      "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
  };
  for (const std::string& text : cases) {
    const std::string path = dir.write("bad.obj", text);
    try {
      const TriangleMesh mesh = readMesh(path);
      ADD_FAILURE() << "accepted:\n" << text << "as vertex 1 = " << mesh.vertices.row(1);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
    }
  }
}

TEST(MeshReader, FailuresAreInputErrors) {
  TempDir dir;
  const std::string noFaces = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string garbage = dir.write("garbage.ply", "this is not a mesh\n");
  const std::string empty = dir.write("empty.obj", "");
  const std::string badIndex = dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  const std::string truncated =
      dir.write("truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  for (const std::string& path :
       {noFaces, garbage, empty, badIndex, truncated, dir.file("missing.obj")}) {
    EXPECT_THROW(readMesh(path), InputError) << path;
  }
  try {
    readMesh(dir.file("missing.obj"));
  } catch (const InputError& e) {
    EXPECT_EQ(e.reason(), "no such file");
  }
  try {
    readMesh(noFaces);
  } catch (const InputError& e) {
    EXPECT_NE(e.reason().find("no faces"), std::string::npos) << e.what();
  }
}

// An FBX file (a fuzzer's mutation of assimp's own export of a square) on which Debian's
// assimp 5.2 dies with a segmentation fault: assimp runs in a child process, so the caller gets
// an InputError naming what happened and carries on (docs/hardening.md).
TEST(MeshReader, AFileThatCrashesAssimpIsRefusedAndTheCallerLives) {
  const std::string path = std::string(WEFT_TEST_DATA_DIR) + "/bad/meshes/assimp_segv.fbx";
  try {
    readMesh(path);
    FAIL() << "read a file assimp cannot read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.path(), "mesh");
    EXPECT_NE(e.reason().find("assimp's reader"), std::string::npos) << e.what();
  }
  // The process still reads meshes through assimp afterwards.
  TempDir dir;
  const TriangleMesh mesh = readMesh(dir.write(
      "triangle.stl",
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid t\n"));
  EXPECT_EQ(mesh.triangleCount(), 1);
}

}  // namespace
}  // namespace weft
