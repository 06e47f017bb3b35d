// Mesh checks: every problem is reported with the indices of the triangles or vertices at fault.

#include <weft/mesh/GridMesh.h>
#include <weft/mesh/MeshCheck.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace weft {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

// Two triangles forming the unit square in the XY plane: vertices 0..3, plus `extra` more.
TriangleMesh square() {
  TriangleMesh mesh;
  mesh.vertices.resize(4, 3);
  mesh.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  mesh.triangles.resize(2, 3);
  mesh.triangles << 0, 1, 2, 0, 2, 3;
  return mesh;
}

void addVertex(TriangleMesh& mesh, const Vec3& p) {
  mesh.vertices.conservativeResize(mesh.vertexCount() + 1, 3);
  mesh.vertices.row(mesh.vertexCount() - 1) = p.transpose();
}

void addTriangle(TriangleMesh& mesh, int a, int b, int c) {
  mesh.triangles.conservativeResize(mesh.triangleCount() + 1, 3);
  mesh.triangles.row(mesh.triangleCount() - 1) << a, b, c;
}

TEST(MeshCheck, CleanGridHasNoFindings) {
  const MeshReport r = checkMesh(makeGrid(1.0, 0.5, 6, 3));
  EXPECT_FALSE(r.hasErrors());
  EXPECT_THAT(r.degenerateTriangles, IsEmpty());
  EXPECT_THAT(r.unreferencedVertices, IsEmpty());
  EXPECT_THAT(r.nonManifoldEdges, IsEmpty());
  EXPECT_THAT(r.thinTriangles, IsEmpty());
}

TEST(MeshCheck, ReportsCollinearAndCoincidentTrianglesAsDegenerate) {
  TriangleMesh mesh = square();
  addVertex(mesh, Vec3(2, 0, 0));  // 4: on the line through 0 and 1
  addVertex(mesh, Vec3(1, 1, 0));  // 5: same position as 2
  addTriangle(mesh, 0, 1, 4);      // 2: collinear, zero area
  addTriangle(mesh, 1, 2, 3);      // 3: fine
  addTriangle(mesh, 3, 2, 5);      // 4: two corners coincide
  const MeshReport r = checkMesh(mesh);
  EXPECT_TRUE(r.hasErrors());
  EXPECT_THAT(r.degenerateTriangles, ElementsAre(2, 4));
  EXPECT_THAT(r.badIndexTriangles, IsEmpty());
}

TEST(MeshCheck, ReportsOutOfRangeAndRepeatedIndices) {
  TriangleMesh mesh = square();
  addTriangle(mesh, 0, 1, 4);   // 2: index 4 does not exist
  addTriangle(mesh, 2, 2, 3);   // 3: repeated index
  addTriangle(mesh, -1, 1, 2);  // 4: negative
  const MeshReport r = checkMesh(mesh);
  EXPECT_TRUE(r.hasErrors());
  EXPECT_THAT(r.badIndexTriangles, ElementsAre(2, 3, 4));
}

TEST(MeshCheck, ReportsUnreferencedVertices) {
  TriangleMesh mesh = square();
  addVertex(mesh, Vec3(5, 5, 5));  // 4
  addVertex(mesh, Vec3(6, 5, 5));  // 5
  const MeshReport r = checkMesh(mesh);
  EXPECT_TRUE(r.hasErrors());
  EXPECT_THAT(r.unreferencedVertices, ElementsAre(4, 5));
}

TEST(MeshCheck, ReportsNonManifoldEdgesAsVertexPairs) {
  TriangleMesh mesh = square();
  addVertex(mesh, Vec3(0.5, 0.5, 1));  // 4: a fin on the diagonal (0, 2)
  addTriangle(mesh, 0, 2, 4);
  const MeshReport r = checkMesh(mesh);
  ASSERT_EQ(r.nonManifoldEdges.size(), 1u);
  EXPECT_EQ(r.nonManifoldEdges[0], std::make_pair(0, 2));
  // A non-manifold edge is simulable (no hinge across it), so it is not an error.
  EXPECT_FALSE(r.hasErrors());
}

TEST(MeshCheck, ReportsNonFiniteVertices) {
  TriangleMesh mesh = square();
  mesh.vertices(1, 2) = std::numeric_limits<double>::quiet_NaN();
  mesh.vertices(3, 0) = std::numeric_limits<double>::infinity();
  const MeshReport r = checkMesh(mesh);
  EXPECT_TRUE(r.hasErrors());
  EXPECT_THAT(r.nonFiniteVertices, ElementsAre(1, 3));
}

TEST(MeshCheck, ThinTrianglesOnlyWarn) {
  TriangleMesh mesh = square();
  addVertex(mesh, Vec3(2, 0.05, 0));  // 4
  addVertex(mesh, Vec3(3, 0, 0));     // 5
  addTriangle(mesh, 1, 5, 4);         // 2: a sliver, angles of 2.9 degrees at 1 and 5
  const MeshReport r = checkMesh(mesh);
  EXPECT_THAT(r.thinTriangles, ElementsAre(2));
  EXPECT_THAT(r.degenerateTriangles, IsEmpty());
  EXPECT_FALSE(r.hasErrors());
}

TEST(MeshCheck, DegeneracyIsRelativeToTheTriangleSize) {
  // A well-shaped triangle of micrometre size is not degenerate: the test must not depend on units.
  TriangleMesh mesh = square();
  mesh.vertices *= 1e-6;
  EXPECT_FALSE(checkMesh(mesh).hasErrors());
  mesh.vertices *= 1e9;
  EXPECT_FALSE(checkMesh(mesh).hasErrors());
}

TEST(MeshCheck, RemoveTrianglesKeepsVerticesAndOrder) {
  TriangleMesh mesh = makeGrid(1.0, 1.0, 2, 2);
  const TriangleMesh before = mesh;
  removeTriangles(mesh, {1, 4, 7});
  EXPECT_EQ(mesh.vertices, before.vertices);
  ASSERT_EQ(mesh.triangleCount(), before.triangleCount() - 3);
  const int kept[] = {0, 2, 3, 5, 6};
  for (int k = 0; k < mesh.triangleCount(); ++k)
    EXPECT_EQ(mesh.triangles.row(k), before.triangles.row(kept[k])) << "row " << k;
}

TEST(MeshCheck, FormatIndexListCountsAndTruncates) {
  EXPECT_EQ(formatIndexList({12, 40, 41}), "3 (12, 40, 41)");
  EXPECT_EQ(formatIndexList({}), "0 ()");
  EXPECT_EQ(formatIndexList({1, 2, 3, 4}, 2), "4 (1, 2, ...)");
}

}  // namespace
}  // namespace weft
