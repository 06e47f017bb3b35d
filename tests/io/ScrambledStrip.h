#pragma once
// The mesh every reader test writes in its format: a 2 x 1 strip whose six vertices are listed
// in a scrambled order, plus a seventh that faces use first. A reader that renumbers vertices by
// first use, welds or splits them changes its indices or count.

#include <weft/mesh/TriangleMesh.h>

#include <gtest/gtest.h>

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

}  // namespace weft::test
