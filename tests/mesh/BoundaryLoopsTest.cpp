// Boundary loops: the border of a grid walked in order, the two rims of a tube, none on a closed
// surface, and a border that touches itself at a vertex listed sorted.

#include <weft/mesh/BoundaryLoops.h>
#include <weft/mesh/GridMesh.h>

#include <gtest/gtest.h>

#include <array>

namespace weft {
namespace {

TriangleMesh meshOf(int vertices, const std::vector<std::array<int, 3>>& triangles) {
  TriangleMesh m;
  m.vertices = NodeMatrix::Zero(vertices, 3);
  m.triangles.resize(Eigen::Index(triangles.size()), 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) m.triangles(Eigen::Index(t), k) = triangles[t][std::size_t(k)];
  return m;
}

TEST(BoundaryLoops, AGridHasOneLoopWalkedInOrder) {
  // 3 x 2 quads: vertex (i, j) = 4 j + i. From 0 towards its smaller neighbour 1, round the border.
  const std::vector<std::vector<int>> loops = boundaryLoops(makeGrid(3.0, 2.0, 3, 2));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0], (std::vector<int>{0, 1, 2, 3, 7, 11, 10, 9, 8, 4}));
}

TEST(BoundaryLoops, ATubeHasTwoRims) {
  // Four quads round a tube: bottom ring 0..3, top ring 4..7.
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    triangles.push_back({i, j, 4 + j});
    triangles.push_back({i, 4 + j, 4 + i});
  }
  const std::vector<std::vector<int>> loops = boundaryLoops(meshOf(8, triangles));
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0], (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(loops[1], (std::vector<int>{4, 5, 6, 7}));
}

TEST(BoundaryLoops, AClosedSurfaceHasNone) {
  const TriangleMesh tetrahedron = meshOf(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
  EXPECT_TRUE(boundaryLoops(tetrahedron).empty());
}

TEST(BoundaryLoops, BordersTouchingAtAVertexAreListedSorted) {
  // Two triangles sharing only vertex 2 (a bow tie): one run of boundary edges through a vertex
  // with four of them, which no walk can follow unambiguously.
  const std::vector<std::vector<int>> loops = boundaryLoops(meshOf(5, {{0, 1, 2}, {2, 3, 4}}));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0], (std::vector<int>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace weft
