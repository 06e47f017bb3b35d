// The static intersection checker (independent of CCD): a flat cloth has no crossings, a second
// grid pushed through it has the number derived by hand, single segment-triangle cases show the
// tie rule, its grid broad phase agrees with all pairs, and it agrees with CCD: a step that starts
// with no crossings and ends with some has CCD impacts (a vertex through a face at the analytic
// time in the configured case), while steps without impacts keep the state free of crossings.

#include "CollisionTestMeshes.h"

#include <weft/collision/EdgeTriangleCrossings.h>
#include <weft/collision/SweptBroadPhase.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace weft::collision {
namespace {

// Grid 1: the unit square in z = 0, 4 x 4 cells. Grid 2: the vertical rectangle y = 0.3,
// x in [0.13, 0.88] (3 cells), z in [zLow, zLow + 0.3] (1 cell).
TriangleMesh twoGrids(double zLow) {
  TriangleMesh mesh = test::gridMesh(Vec3(0, 0, 0), Vec3(0.25, 0, 0), Vec3(0, 0.25, 0), 4, 4);
  mesh.append(test::gridMesh(Vec3(0.13, 0.3, zLow), Vec3(0.25, 0, 0), Vec3(0, 0, 0.3), 3, 1));
  return mesh;
}

TEST(CollisionCrossings, SegmentTriangleAndTies) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), a, b, c));
  EXPECT_TRUE(segmentCrossesTriangle(Vec3(0.2, 0.2, 1), Vec3(0.3, 0.1, -1), a, b, c));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.6, 0.6, -1), Vec3(0.6, 0.6, 1), a, b, c));   // beside
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.2, 0.2, 0.5), Vec3(0.2, 0.2, 1), a, b, c));  // above
  // Ties are not crossings: an endpoint in the plane, through an edge or a corner, coplanar.
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.2, 0.2, 0), Vec3(0.2, 0.2, 1), a, b, c));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0.5, 0, -1), Vec3(0.5, 0, 1), a, b, c));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(0, 0, -1), Vec3(0, 0, 1), a, b, c));
  EXPECT_FALSE(segmentCrossesTriangle(Vec3(-1, 0.2, 0), Vec3(2, 0.2, 0), a, b, c));
}

TEST(CollisionCrossings, FlatGridHasNone) {
  const TriangleMesh cloth =
      test::gridMesh(Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 10, 10);
  EXPECT_EQ(findEdgeTriangleCrossings(cloth, cloth.vertices).count(), 0);
  // Crumpled (heights vary, no fold): still none.
  NodeMatrix wavy = cloth.vertices;
  for (int i = 0; i < wavy.rows(); ++i)
    wavy(i, 2) = 0.05 * std::sin(7 * wavy(i, 0) + 3 * wavy(i, 1));
  EXPECT_EQ(findEdgeTriangleCrossings(cloth, wavy).count(), 0);
}

TEST(CollisionCrossings, FlatGridTurnedAnyWayHasNone) {
  // A flat sheet turned by an arbitrary rotation is coplanar only up to rounding: every edge and
  // every triangle lie in one plane within about 1e-17 m, and the orientation determinants are
  // rounding noise. Read as signs they made a crossing between neighbouring cells of a falling
  // 64 x 64 cloth (issue 38's pyramid); within rounding of a tie is a tie.
  const TriangleMesh cloth =
      test::gridMesh(Vec3(0, 0, 0), Vec3(0.7 / 32, 0, 0), Vec3(0, 0.7 / 32, 0), 32, 32);
  std::mt19937 rng(38);
  std::uniform_real_distribution<double> angle(-3.14159, 3.14159), offset(-1.0, 1.0);
  int total = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(angle(rng), Vec3::UnitZ()) *
                               Eigen::AngleAxisd(angle(rng), Vec3::UnitY()) *
                               Eigen::AngleAxisd(angle(rng), Vec3::UnitX()))
                                  .toRotationMatrix();
    const Vec3 t(offset(rng), offset(rng), offset(rng));
    NodeMatrix x(cloth.vertices.rows(), 3);
    for (int i = 0; i < x.rows(); ++i)
      x.row(i) = (r * cloth.vertices.row(i).transpose() + t).transpose();
    total += findEdgeTriangleCrossings(cloth, x).count();
  }
  EXPECT_EQ(total, 0);
}

TEST(CollisionCrossings, GridPushedThroughAGridHasTheAnalyticCount) {
  // Grid 2 spanning z in [-0.1, 0.2]. Its edges crossing z = 0 inside grid 1: the 4 vertical
  // edges (x = 0.13, 0.38, 0.63, 0.88) and the 3 diagonals (at x = 0.13 + 0.25 i + 0.25 / 3):
  // 7, each through one triangle (none on a grid-1 edge: x, y not multiples of 0.25, x - y
  // not one). Grid 1's edges crossing y = 0.3 inside grid 2 (x in (0.13, 0.88), z = 0): in the row
  // y in [0.25, 0.5], the edges x = 0.25, 0.5, 0.75 and the diagonals at x = 0.3, 0.55, 0.8: 6.
  const TriangleMesh crossing = twoGrids(-0.1);
  const EdgeTriangleCrossings found = findEdgeTriangleCrossings(crossing, crossing.vertices);
  EXPECT_EQ(found.count(), 13);
  const int grid1Triangles = 32;
  int grid2EdgesThroughGrid1 = 0;
  for (const auto& [e, t] : found.pairs) grid2EdgesThroughGrid1 += t < grid1Triangles;
  EXPECT_EQ(grid2EdgesThroughGrid1, 7);
  // Above grid 1 (z in [0.05, 0.35]) or beside it: none.
  const TriangleMesh above = twoGrids(0.05);
  EXPECT_EQ(findEdgeTriangleCrossings(above, above.vertices).count(), 0);
}

TEST(CollisionCrossings, GridBroadPhaseAgreesWithAllPairs) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> noise(-0.15, 0.15);
  int total = 0;
  for (int trial = 0; trial < 10; ++trial) {
    TriangleMesh mesh = test::gridMesh(Vec3(0, 0, 0), Vec3(0.2, 0, 0), Vec3(0, 0.2, 0), 5, 5);
    // And one large triangle through the cloth (its edges cover many grid cells).
    TriangleMesh large;
    large.vertices.resize(3, 3);
    large.vertices << -2, -2, -0.3, 3, -1, 0.2, 0, 3, 0.1;
    large.triangles.resize(1, 3);
    large.triangles << 0, 1, 2;
    mesh.append(large);
    NodeMatrix x = mesh.vertices;
    for (int i = 0; i < x.rows(); ++i)
      for (int c = 0; c < 3; ++c) x(i, c) += noise(rng);
    std::vector<std::pair<int, int>> all;
    const std::vector<MeshEdge> edges = buildEdges(mesh);
    for (int e = 0; e < static_cast<int>(edges.size()); ++e)
      for (int t = 0; t < mesh.triangleCount(); ++t) {
        const auto f = mesh.triangles.row(t);
        const int a = edges[e].a, b = edges[e].b;
        if (a == f[0] || a == f[1] || a == f[2] || b == f[0] || b == f[1] || b == f[2]) continue;
        if (segmentCrossesTriangle(x.row(a).transpose(), x.row(b).transpose(),
                                   x.row(f[0]).transpose(), x.row(f[1]).transpose(),
                                   x.row(f[2]).transpose()))
          all.emplace_back(e, t);
      }
    EXPECT_EQ(findEdgeTriangleCrossings(mesh, x).pairs, all);
    total += static_cast<int>(all.size());
  }
  std::printf("crumpled grids: %d crossings over 10 states\n", total);
  EXPECT_GT(total, 10);
}

TEST(CollisionCrossings, AgreeWithCcdOnAGridPushedThrough) {
  // Grid 2 moves down by 0.15, from z in [0.05, 0.35] (no crossing) to [-0.1, 0.2] (13). Its
  // bottom vertices (z = 0.05 - 0.15 t) pass through grid 1 at t = 1/3: CCD reports each of them
  // against the grid-1 face below it at that time.
  const TriangleMesh mesh = twoGrids(0.05);
  const NodeMatrix start = mesh.vertices, end = twoGrids(-0.1).vertices;
  EXPECT_EQ(findEdgeTriangleCrossings(mesh, start).count(), 0);
  EXPECT_EQ(findEdgeTriangleCrossings(mesh, end).count(), 13);
  SweptBroadPhase broad(mesh);
  const std::vector<Impact> impacts = broad.findImpacts(start, end, 1e-3);
  ASSERT_FALSE(impacts.empty());
  const int grid1Vertices = 25;
  for (int v = grid1Vertices; v < grid1Vertices + 4; ++v) {  // grid 2's bottom row
    const auto hit = std::find_if(impacts.begin(), impacts.end(), [&](const Impact& i) {
      return i.kind == ImpactKind::VertexFace && i.nodes[0] == v;
    });
    ASSERT_NE(hit, impacts.end()) << "vertex " << v;
    EXPECT_NEAR(hit->time, 1.0 / 3.0, 1e-12);
    EXPECT_NEAR((hit->normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);  // it comes from above
    EXPECT_LT(hit->nodes[1], grid1Vertices);
    // The face's barycentric weights reproduce the vertex's (x, y).
    Vec3 q = Vec3::Zero();
    for (int k = 1; k < 4; ++k) q -= hit->weights[k] * start.row(hit->nodes[k]).transpose();
    EXPECT_NEAR(q.x(), start(v, 0), 1e-12);
    EXPECT_NEAR(q.y(), start(v, 1), 1e-12);
  }
}

TEST(CollisionCrossings, StepsWithoutImpactsCreateNoCrossings) {
  // Two grids 0.05 apart, each vertex moved randomly (by up to 0.01 to 0.07): whenever the end
  // state has crossings that the start did not, CCD found impacts; when CCD finds none, no crossing
  // appears.
  std::mt19937 rng(32);
  int crossedSteps = 0, quietSteps = 0;
  for (int trial = 0; trial < 60; ++trial) {
    TriangleMesh mesh = test::gridMesh(Vec3(0, 0, 0), Vec3(0.2, 0, 0), Vec3(0, 0.2, 0), 5, 5);
    mesh.append(test::gridMesh(Vec3(0.07, 0.03, 0.05), Vec3(0.2, 0, 0), Vec3(0, 0.2, 0), 5, 5));
    const double amplitude = 0.01 + 0.06 * trial / 60.0;
    std::uniform_real_distribution<double> move(-amplitude, amplitude);
    NodeMatrix end = mesh.vertices;
    for (int i = 0; i < end.rows(); ++i)
      for (int c = 0; c < 3; ++c) end(i, c) += move(rng);
    ASSERT_EQ(findEdgeTriangleCrossings(mesh, mesh.vertices).count(), 0);
    const int crossings = findEdgeTriangleCrossings(mesh, end).count();
    SweptBroadPhase broad(mesh);
    const std::vector<Impact> impacts = broad.findImpacts(mesh.vertices, end, 1e-4);
    if (crossings > 0) {
      ++crossedSteps;
      EXPECT_FALSE(impacts.empty()) << "trial " << trial;
    }
    if (impacts.empty()) {
      ++quietSteps;
      EXPECT_EQ(crossings, 0) << "trial " << trial;
    }
  }
  std::printf("random steps: %d with crossings at the end, %d without impacts\n", crossedSteps,
              quietSteps);
  EXPECT_GT(crossedSteps, 5);
  EXPECT_GT(quietSteps, 5);
}

}  // namespace
}  // namespace weft::collision
