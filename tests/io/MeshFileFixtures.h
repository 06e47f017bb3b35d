#pragma once
// What every mesh reader's tests check, whatever the format: the scrambled strip (a 2 x 1 strip
// whose six vertices are listed in a scrambled order, plus a seventh that faces use first: a
// reader that renumbers vertices by first use, welds or splits them changes its indices or
// count), the fan triangulation of a triangle and a quad, and malformed files refused with a
// reason.

#include <support/TempDir.h>
#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>
#include <weft/mesh/TriangleMesh.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace weft::test {

inline constexpr double kPositions[7][3] = {{2, 0, 1}, {0, 0, 0}, {1, 0, 1},      {2, 0, 0},
                                            {0, 0, 1}, {1, 0, 0}, {1.5, 0.5, 0.5}};
// Zero-based triangles, deliberately not in vertex order.
inline constexpr int kTriangles[5][3] = {{6, 3, 0}, {1, 4, 5}, {5, 4, 2}, {5, 2, 3}, {3, 2, 0}};

inline void expectScrambledStrip(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertexCount(), 7);
  for (int i = 0; i < 7; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.vertices(i, c), kPositions[i][c]) << "vertex " << i;
  ASSERT_EQ(mesh.triangleCount(), 5);
  for (int t = 0; t < 5; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(mesh.triangles(t, k), kTriangles[t][k]) << "triangle " << t;
}

// The five vertices (0 0 0, 1 0 0, 1 0 1, 0 0 1, 0.5 0 1.5) of a triangle (3 2 4) and a quad
// (0 3 2 1) written in the file, read back: the quad fanned from its first corner, no vertex
// added.
inline void expectTriangleAndQuadFan(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertexCount(), 5);
  ASSERT_EQ(mesh.triangleCount(), 3);
  EXPECT_EQ(mesh.triangles.row(0), Eigen::RowVector3i(3, 2, 4));
  EXPECT_EQ(mesh.triangles.row(1), Eigen::RowVector3i(0, 3, 2));
  EXPECT_EQ(mesh.triangles.row(2), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.vertices(4, 0), 0.5);
  EXPECT_EQ(mesh.vertices(4, 2), 1.5);
}

// A malformed file and the words its InputError's reason must contain.
struct MalformedFile {
  const char* name;
  std::string text;
  const char* reason;
};

// Each file, written to `dir`, is refused by readMesh with an InputError on the path "mesh" whose
// reason starts with `prefix` (the reader's: "PLY: ", "glTF: ") and names the fault.
inline void expectRefused(const TempDir& dir, const std::vector<MalformedFile>& files,
                          const std::string& prefix) {
  for (const MalformedFile& f : files) {
    SCOPED_TRACE(f.name);
    try {
      readMesh(dir.write(f.name, f.text));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.path(), "mesh");
      EXPECT_NE(e.reason().find(f.reason), std::string::npos) << e.what();
      EXPECT_EQ(e.reason().rfind(prefix, 0), 0u) << e.what();
    }
  }
}

}  // namespace weft::test
