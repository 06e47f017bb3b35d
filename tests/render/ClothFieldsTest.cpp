// The per-vertex fields the overlays colour: strain and speed.

#include <weft/frames/ClothFields.h>
#include <weft/frames/SyntheticDrape.h>

#include <weft/mesh/GridMesh.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

TEST(ClothFields, StrainIsZeroAtRestAndUnderRigidMotion) {
  const TriangleMesh rest = makeGrid(1.0, 0.5, 6, 3);
  EXPECT_LT(vertexStrain(rest, rest.vertices).cwiseAbs().maxCoeff(), 1e-12);
  const Mat3 rotation = Eigen::AngleAxisd(0.8, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const NodeMatrix moved =
      (rest.vertices * rotation.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  EXPECT_LT(vertexStrain(rest, moved).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ClothFields, StrainIsSignedByStretchOrCompression) {
  const TriangleMesh rest = makeGrid(1.0, 1.0, 4, 4);
  NodeMatrix stretched = rest.vertices;
  stretched.col(0) *= 1.1;  // 10 % along X
  const Eigen::VectorXd s = vertexStrain(rest, stretched);
  EXPECT_NEAR(s.minCoeff(), 0.1, 1e-9);
  EXPECT_NEAR(s.maxCoeff(), 0.1, 1e-9);
  NodeMatrix squeezed = rest.vertices;
  squeezed.col(2) *= 0.8;
  EXPECT_NEAR(vertexStrain(rest, squeezed).maxCoeff(), -0.2, 1e-9);
}

TEST(ClothFields, DrapeWrapsTheSphereWithoutStretchingTheCap) {
  DrapeSphere sphere;
  const TriangleMesh rest = makeGrid(1.6, 1.6, 20, 20);
  const NodeMatrix draped = drapeOverSphere(rest.vertices, sphere);
  for (Eigen::Index i = 0; i < draped.rows(); ++i)
    EXPECT_GE((draped.row(i).transpose() - sphere.center).norm(), sphere.radius)
        << "vertex " << i << " inside";
  // Wrapping a plane onto a sphere compresses it around the circles of latitude.
  const Eigen::VectorXd strain = vertexStrain(rest, draped);
  EXPECT_LT(strain.minCoeff(), -0.05);
  EXPECT_LT(strain.maxCoeff(), 0.05);
}

TEST(ClothFields, SpeedIsDisplacementOverTime) {
  NodeMatrix a = NodeMatrix::Zero(2, 3), b = a;
  b.row(1) << 0.3, 0.4, 0.0;
  const Eigen::VectorXd v = vertexSpeed(a, b, 0.01);
  EXPECT_DOUBLE_EQ(v[0], 0.0);
  EXPECT_NEAR(v[1], 50.0, 1e-12);
}

}  // namespace
}  // namespace weft::test
