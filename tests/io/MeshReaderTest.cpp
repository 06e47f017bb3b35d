// Mesh files keep the file's vertex order and count (no welding, splitting or reordering):
// attachments, targets and outputs refer to vertices by index. OBJ goes through tinyobjloader,
// the rest through assimp; every file here is written by the test.

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

using test::TempDir;

// Six vertices of a 2 x 1 strip listed in a scrambled order, plus a seventh that faces use
// first: a reader that renumbers vertices by first use, welds or splits them would change
// indices or count.
const double kPositions[7][3] = {{2, 0, 1}, {0, 0, 0}, {1, 0, 1},      {2, 0, 0},
                                 {0, 0, 1}, {1, 0, 0}, {1.5, 0.5, 0.5}};
// Zero-based triangles, deliberately not in vertex order.
const int kTriangles[5][3] = {{6, 3, 0}, {1, 4, 5}, {5, 4, 2}, {5, 2, 3}, {3, 2, 0}};

void expectScrambledStrip(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertexCount(), 7);
  for (int i = 0; i < 7; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.vertices(i, c), kPositions[i][c]) << "vertex " << i;
  ASSERT_EQ(mesh.triangleCount(), 5);
  for (int t = 0; t < 5; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(mesh.triangles(t, k), kTriangles[t][k]) << "triangle " << t;
}

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
  const TriangleMesh mesh = readMesh(path);
  ASSERT_EQ(mesh.vertexCount(), 5);
  ASSERT_EQ(mesh.triangleCount(), 3);
  EXPECT_EQ(mesh.triangles.row(0), Eigen::RowVector3i(3, 2, 4));
  EXPECT_EQ(mesh.triangles.row(1), Eigen::RowVector3i(0, 3, 2));
  EXPECT_EQ(mesh.triangles.row(2), Eigen::RowVector3i(0, 2, 1));
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

TEST(MeshReader, AssimpAsciiPlyKeepsVertexOrderAndCount) {
  TempDir dir;
  std::ostringstream s;
  s << "ply\nformat ascii 1.0\ncomment scrambled strip\nelement vertex 7\n"
       "property float x\nproperty float y\nproperty float z\n"
       "element face 5\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : kPositions) s << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : kTriangles) s << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  expectScrambledStrip(readMesh(dir.write("strip.ply", s.str())));
}

TEST(MeshReader, AssimpBinaryPlyKeepsVertexOrderAndCount) {
  TempDir dir;
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 7\n"
      "property double x\nproperty double y\nproperty double z\n"
      "element face 5\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : kPositions) s.append(reinterpret_cast<const char*>(p), sizeof p);
  for (const auto& t : kTriangles) {
    s += static_cast<char>(3);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = t[k];
      s.append(reinterpret_cast<const char*>(&v), 4);
    }
  }
  expectScrambledStrip(readMesh(dir.write("strip-binary.ply", s)));
}

std::string base64(const std::string& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t chunk = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= static_cast<unsigned char>(bytes[i + 2]);
    out += alphabet[(chunk >> 18) & 63];
    out += alphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[chunk & 63] : '=';
  }
  return out;
}

// glTF 2.0 holding the scrambled strip as mesh 0 (an embedded buffer: float32 positions, uint16
// indices), placed by `nodes` (a JSON array) of which scene 0 lists `roots`.
std::string stripGltf(const std::string& nodes = R"([{"mesh": 0}])",
                      const std::string& roots = "[0]") {
  std::string buffer;
  for (const auto& p : kPositions)
    for (double c : p) {
      const float f = static_cast<float>(c);
      buffer.append(reinterpret_cast<const char*>(&f), 4);
    }
  const std::size_t positionBytes = buffer.size();
  for (const auto& t : kTriangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint16_t i = static_cast<std::uint16_t>(t[k]);
      buffer.append(reinterpret_cast<const char*>(&i), 2);
    }
  std::ostringstream g;
  g << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" << roots << R"(}],
  "nodes": )"
    << nodes << R"(,
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
  "buffers": [{"byteLength": )"
    << buffer.size() << R"(, "uri": "data:application/octet-stream;base64,)" << base64(buffer)
    << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )"
    << positionBytes << R"(},
                  {"buffer": 0, "byteOffset": )"
    << positionBytes << R"(, "byteLength": )" << buffer.size() - positionBytes << R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 7, "type": "VEC3",
                 "min": [0, 0, 0], "max": [2, 0.5, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 15, "type": "SCALAR"}]})";
  return g.str();
}

TEST(MeshReader, AssimpGltfKeepsVertexOrderAndCount) {
  TempDir dir;
  expectScrambledStrip(readMesh(dir.write("strip.gltf", stripGltf())));
}

// An exporter stores an object's placement in its nodes, not in its vertices: the strip is read
// where the node hierarchy puts it (parent then child transform), once per node that references
// it, and a mirroring node lists each triangle's corners the other way round.
TEST(MeshReader, AssimpAppliesNodeTransformsAndInstances) {
  // Node 0 (root): translation (10, 0, 0) and uniform scale 2; its child node 1: a quarter turn
  // about z (quaternion (0, 0, sin 45, cos 45)) holding the mesh. Node 2 (a second root): the same
  // mesh mirrored in x.
  const std::string nodes = R"([
    {"translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1]},
    {"rotation": [0, 0, 0.7071067811865476, 0.7071067811865476], "mesh": 0},
    {"scale": [-1, 1, 1], "mesh": 0}])";
  TempDir dir;
  const TriangleMesh mesh = readMesh(dir.write("placed.gltf", stripGltf(nodes, "[0, 2]")));
  ASSERT_EQ(mesh.vertexCount(), 14);
  ASSERT_EQ(mesh.triangleCount(), 10);
  for (int i = 0; i < 7; ++i) {
    SCOPED_TRACE(i);
    const double x = kPositions[i][0], y = kPositions[i][1], z = kPositions[i][2];
    // First instance: x' = 10 + 2 R_z(90) x = (10 - 2y, 2x, 2z); float precision.
    EXPECT_NEAR(mesh.vertices(i, 0), 10.0 - 2.0 * y, 1e-5);
    EXPECT_NEAR(mesh.vertices(i, 1), 2.0 * x, 1e-5);
    EXPECT_NEAR(mesh.vertices(i, 2), 2.0 * z, 1e-5);
    // Second: mirrored, (-x, y, z).
    EXPECT_EQ(mesh.vertices(7 + i, 0), -x);
    EXPECT_EQ(mesh.vertices(7 + i, 1), y);
    EXPECT_EQ(mesh.vertices(7 + i, 2), z);
  }
  for (int t = 0; t < 5; ++t) {
    SCOPED_TRACE(t);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.triangles(t, k), kTriangles[t][k]);
    // The mirrored copy: the same corners, second and third swapped.
    EXPECT_EQ(mesh.triangles(5 + t, 0), 7 + kTriangles[t][0]);
    EXPECT_EQ(mesh.triangles(5 + t, 1), 7 + kTriangles[t][2]);
    EXPECT_EQ(mesh.triangles(5 + t, 2), 7 + kTriangles[t][1]);
  }
}

TEST(MeshReader, FailuresAreInputErrors) {
  TempDir dir;
  const std::string noFaces = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string garbage = dir.write("garbage.ply", "this is not a mesh\n");
  const std::string empty = dir.write("empty.obj", "");
  const std::string badIndex = dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  // assimp 5.2 never returns on a PLY header without end_header: it must be refused first.
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

}  // namespace
}  // namespace weft
