// A flat grid laid onto a sphere (the cloth of `weft bench continuity`): every vertex on the
// sphere, the horizontal coordinates kept, the triangles facing outwards, and a clear error
// for a vertex the sphere does not cover.

#include <weft/mesh/GridMesh.h>
#include <weft/mesh/SphereProjection.h>

#include <gtest/gtest.h>

#include <stdexcept>

namespace weft {
namespace {

TEST(SphereProjection, PutsEveryVertexOnTheUpperSphereFacingOutwards) {
  const Vec3 c(0.3, -1.0, 0.2);
  const double r = 2.0;
  TriangleMesh grid = makeGrid(1.0, 0.8, 6, 4);
  grid.vertices.col(0).array() += 0.9;  // off-centre, so the patch is tilted
  const TriangleMesh patch = projectOntoSphere(grid, c, r);
  ASSERT_EQ(patch.vertexCount(), grid.vertexCount());
  EXPECT_EQ(patch.triangles, grid.triangles);
  for (int i = 0; i < patch.vertexCount(); ++i) {
    const Vec3 p = patch.vertices.row(i);
    EXPECT_NEAR((p - c).norm(), r, 1e-12) << "vertex " << i;
    EXPECT_GT(p.y(), c.y());
    EXPECT_EQ(p.x(), grid.vertices(i, 0));
    EXPECT_EQ(p.z(), grid.vertices(i, 2));
  }
  for (int t = 0; t < patch.triangleCount(); ++t) {
    const Vec3 a = patch.vertices.row(patch.triangles(t, 0));
    const Vec3 b = patch.vertices.row(patch.triangles(t, 1));
    const Vec3 d = patch.vertices.row(patch.triangles(t, 2));
    const Vec3 n = (b - a).cross(d - a);
    EXPECT_GT(n.dot((a + b + d) / 3.0 - c), 0.0) << "triangle " << t << " faces inwards";
  }
}

TEST(SphereProjection, RefusesAVertexOutsideTheSphere) {
  const TriangleMesh grid = makeGrid(3.0, 1.0, 2, 2);  // corners 1.58 m from the axis
  EXPECT_THROW(projectOntoSphere(grid, Vec3::Zero(), 1.5), std::invalid_argument);
  EXPECT_NO_THROW(projectOntoSphere(grid, Vec3::Zero(), 1.6));
}

}  // namespace
}  // namespace weft
