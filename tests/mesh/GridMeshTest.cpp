// The grid convention of the scene contract: vertex (i, j) at index j * (nx + 1) + i, centred
// at the origin in the XZ plane, X fastest, normal +Y, two triangles per quad.

#include <support/SceneBuilder.h>
#include <weft/mesh/GridMesh.h>

#include <gtest/gtest.h>

#include <set>

namespace weft {
namespace {

Vec3 triangleNormal(const TriangleMesh& mesh, int t) {
  const Vec3 a = mesh.vertices.row(mesh.triangles(t, 0));
  const Vec3 b = mesh.vertices.row(mesh.triangles(t, 1));
  const Vec3 c = mesh.vertices.row(mesh.triangles(t, 2));
  return (b - a).cross(c - a);
}

TEST(GridMesh, VertexIndexIsRowMajorWithXFastest) {
  const double sx = 2.0, sz = 1.0;
  const int qx = 4, qz = 2;
  const TriangleMesh grid = makeGrid(sx, sz, qx, qz);
  ASSERT_EQ(grid.vertexCount(), (qx + 1) * (qz + 1));
  ASSERT_EQ(grid.triangleCount(), 2 * qx * qz);
  for (int j = 0; j <= qz; ++j) {
    for (int i = 0; i <= qx; ++i) {
      const Vec3 p = grid.vertices.row(j * (qx + 1) + i);
      EXPECT_NEAR(p.x(), -0.5 * sx + sx * i / qx, 1e-15) << "vertex (" << i << ", " << j << ")";
      EXPECT_EQ(p.y(), 0.0);
      EXPECT_NEAR(p.z(), -0.5 * sz + sz * j / qz, 1e-15) << "vertex (" << i << ", " << j << ")";
    }
  }
}

TEST(GridMesh, IsCentredAtTheOriginWithTheRequestedExtent) {
  const TriangleMesh grid = makeGrid(3.0, 0.5, 6, 3);
  const Vec3 mean = grid.vertices.colwise().mean();
  EXPECT_NEAR(mean.norm(), 0.0, 1e-14);
  EXPECT_NEAR(grid.vertices.col(0).maxCoeff() - grid.vertices.col(0).minCoeff(), 3.0, 1e-14);
  EXPECT_NEAR(grid.vertices.col(2).maxCoeff() - grid.vertices.col(2).minCoeff(), 0.5, 1e-14);
  EXPECT_NEAR(grid.totalArea(), 3.0 * 0.5, 1e-13);
}

TEST(GridMesh, EveryTriangleFacesPlusYAndHalvesAQuad) {
  const int qx = 3, qz = 5;
  const TriangleMesh grid = makeGrid(1.5, 2.5, qx, qz);
  const double quadArea = (1.5 / qx) * (2.5 / qz);
  for (int t = 0; t < grid.triangleCount(); ++t) {
    const Vec3 n = triangleNormal(grid, t);
    EXPECT_GT(n.y(), 0.0) << "triangle " << t << " faces -Y";
    EXPECT_NEAR(n.x(), 0.0, 1e-15);
    EXPECT_NEAR(n.z(), 0.0, 1e-15);
    EXPECT_NEAR(0.5 * n.norm(), 0.5 * quadArea, 1e-14) << "triangle " << t;
    // The three corners lie in one quad: grid coordinates differ by at most one.
    std::set<int> is, js;
    for (int k = 0; k < 3; ++k)
      is.insert(grid.triangles(t, k) % (qx + 1)), js.insert(grid.triangles(t, k) / (qx + 1));
    EXPECT_EQ(is.size(), 2u);
    EXPECT_EQ(js.size(), 2u);
    EXPECT_EQ(*is.rbegin() - *is.begin(), 1);
    EXPECT_EQ(*js.rbegin() - *js.begin(), 1);
  }
}

TEST(GridMesh, LumpedAreasSumToTheTotalAndEqualAQuadInside) {
  const int qx = 4, qz = 4;
  const TriangleMesh grid = makeGrid(1.0, 1.0, qx, qz);
  const Eigen::VectorXd areas = grid.lumpedAreas();
  EXPECT_NEAR(areas.sum(), 1.0, 1e-13);
  // An interior vertex touches six half-quads, each contributing a third.
  EXPECT_NEAR(areas[2 * (qx + 1) + 2], 1.0 / (qx * qz), 1e-15);
}

TEST(GridMesh, AreaAtOtherPositionsFollowsTheMap) {
  const TriangleMesh grid = makeGrid(1.0, 1.0, 4, 4);  // XZ plane, area 1
  EXPECT_NEAR(grid.areaAt(grid.vertices), grid.totalArea(), 1e-15);
  // x doubled: area doubled; a rigid motion: unchanged; folded along x = 0 onto itself: unchanged.
  NodeMatrix stretched = grid.vertices;
  stretched.col(0) *= 2.0;
  EXPECT_NEAR(grid.areaAt(stretched), 2.0, 1e-13);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const NodeMatrix moved =
      (grid.vertices * rotation.transpose()).rowwise() + Vec3(0.3, -2.0, 5.0).transpose();
  EXPECT_NEAR(grid.areaAt(moved), 1.0, 1e-13);
  NodeMatrix folded = grid.vertices;
  folded.col(0) = folded.col(0).cwiseAbs();
  EXPECT_NEAR(grid.areaAt(folded), 1.0, 1e-13);
}

TEST(GridMesh, EdgesAreUniqueWithBoundaryAndInteriorCounts) {
  const int qx = 3, qz = 2;
  const TriangleMesh grid = makeGrid(1.0, 1.0, qx, qz);
  const auto edges = buildEdges(grid);
  // Along X, along Z, one diagonal per quad.
  EXPECT_EQ(edges.size(), std::size_t(qx * (qz + 1) + (qx + 1) * qz + qx * qz));
  int boundary = 0, interior = 0;
  for (const MeshEdge& e : edges) {
    EXPECT_LT(e.a, e.b);
    if (e.faces.size() == 1) ++boundary;
    if (e.faces.size() == 2) ++interior;
  }
  EXPECT_EQ(boundary, 2 * (qx + qz));
  EXPECT_EQ(interior, static_cast<int>(edges.size()) - 2 * (qx + qz));
}

TEST(GridMesh, SceneGridUsesTheSameConvention) {
  nlohmann::json doc = test::gridScene(1.0, 4, 0.01, 1);
  doc["cloths"][0]["mesh"]["grid"] = {{"size", {2.0, 1.0}}, {"resolution", {4, 2}}};
  const Scene scene = test::parse(doc);
  const TriangleMesh expected = makeGrid(2.0, 1.0, 4, 2);
  ASSERT_EQ(scene.cloths.size(), 1u);
  EXPECT_EQ(scene.cloths[0].mesh.vertices, expected.vertices);
  EXPECT_EQ(scene.cloths[0].mesh.triangles, expected.triangles);
}

}  // namespace
}  // namespace weft
