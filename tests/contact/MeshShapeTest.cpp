// Mesh obstacles: the BVH's nearest-point query against a brute-force scan of all triangles,
// the sign of the distance (pseudo-normals) on a closed mesh, and the smoothed normals, which
// must turn continuously across edges while the face normals jump (DiffCloth Sec. 5.1, Fig. 2).

#include <weft/contact/MeshShape.h>
#include <weft/contact/TriangleBvh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace weft {
namespace {

// A sphere of `radius` at `centre`: an octahedron subdivided `levels` times, projected onto the
// sphere, outward counter-clockwise triangles.
TriangleMesh geodesicSphere(const Vec3& centre, double radius, int levels) {
  std::vector<Vec3> v = {Vec3::UnitX(),  -Vec3::UnitX(), Vec3::UnitY(),
                         -Vec3::UnitY(), Vec3::UnitZ(),  -Vec3::UnitZ()};
  std::vector<std::array<int, 3>> t = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : t) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({ab, f[1], bc});
      next.push_back({ca, bc, f[2]});
      next.push_back({ab, bc, ca});
    }
    t.swap(next);
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<int>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    mesh.vertices.row(i) = (centre + radius * v[i]).transpose();
  mesh.triangles.resize(static_cast<int>(t.size()), 3);
  for (std::size_t i = 0; i < t.size(); ++i) mesh.triangles.row(i) << t[i][0], t[i][1], t[i][2];
  return mesh;
}

double bruteForceSquaredDistance(const TriangleMesh& mesh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Vec3 bary;
    TriangleFeature feature;
    const Vec3 q = closestPointOnTriangle(p, mesh.vertices.row(mesh.triangles(t, 0)),
                                          mesh.vertices.row(mesh.triangles(t, 1)),
                                          mesh.vertices.row(mesh.triangles(t, 2)), bary, feature);
    best = std::min(best, (p - q).squaredNorm());
  }
  return best;
}

const Vec3 kCentre(0.1, -0.05, 0.2);

TEST(TriangleBvh, NearestPointMatchesBruteForce) {
  // An irregular mesh: a sphere with jittered vertices, so no two triangles are alike.
  TriangleMesh mesh = geodesicSphere(kCentre, 0.5, 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < mesh.vertexCount(); ++i)
    mesh.vertices.row(i) += 0.02 * Vec3(u(rng), u(rng), u(rng)).transpose();
  const TriangleBvh bvh(mesh);
  EXPECT_GT(bvh.depth(), 3);
  for (int k = 0; k < 1500; ++k) {
    const Vec3 p = kCentre + Vec3(u(rng), u(rng), u(rng));
    const double expected = bruteForceSquaredDistance(mesh, p);
    TriangleBvh::Nearest nearest;
    ASSERT_TRUE(bvh.nearest(p, std::numeric_limits<double>::infinity(), nearest));
    ASSERT_NEAR(nearest.squaredDistance, expected, 1e-14) << "at " << p.transpose();
    ASSERT_NEAR((nearest.point - p).squaredNorm(), expected, 1e-14);
    // The barycentric coordinates reproduce the point on the reported triangle.
    const int t = nearest.triangle;
    const Vec3 q = nearest.barycentric[0] * Vec3(mesh.vertices.row(mesh.triangles(t, 0))) +
                   nearest.barycentric[1] * Vec3(mesh.vertices.row(mesh.triangles(t, 1))) +
                   nearest.barycentric[2] * Vec3(mesh.vertices.row(mesh.triangles(t, 2)));
    ASSERT_LT((q - nearest.point).norm(), 1e-12);
    // A bounded query finds it exactly when it is within the bound.
    const double bound = 0.01;
    TriangleBvh::Nearest bounded;
    ASSERT_EQ(bvh.nearest(p, bound, bounded), expected < bound) << "at " << p.transpose();
    if (expected < bound) {
      ASSERT_NEAR(bounded.squaredDistance, expected, 1e-14);
    }
  }
}

TEST(MeshShape, SignedDistanceOfAClosedMesh) {
  const double radius = 0.5;
  const TriangleMesh mesh = geodesicSphere(kCentre, radius, 3);
  const MeshShape shape(mesh, true);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // The mesh lies between the sphere and its inscribed polyhedron: chord error below this.
  const double chord = 0.02;
  int inside = 0;
  for (int k = 0; k < 1500; ++k) {
    const Vec3 p = kCentre + 0.9 * Vec3(u(rng), u(rng), u(rng));
    SurfaceSample s;
    ASSERT_TRUE(shape.sample(p, 1e9, s));
    ASSERT_NEAR(std::abs(s.distance), std::sqrt(bruteForceSquaredDistance(mesh, p)), 1e-12);
    const double sphere = (p - kCentre).norm() - radius;
    if (std::abs(sphere) > chord) {
      ASSERT_EQ(s.distance < 0.0, sphere < 0.0) << "at " << p.transpose();
    }
    ASSERT_NEAR(s.distance, sphere, chord) << "at " << p.transpose();
    inside += s.distance < 0.0;
    ASSERT_NEAR(s.normal.norm(), 1.0, 1e-12);
  }
  EXPECT_GT(inside, 100);
}

// Walks a great circle 2 cm above the mesh, crossing many edges, and measures how much the
// normal turns per step.
TEST(MeshShape, SmoothNormalsAreContinuousAcrossEdgesFaceNormalsJump) {
  const double radius = 0.5;
  const TriangleMesh mesh = geodesicSphere(kCentre, radius, 2);
  const MeshShape smooth(mesh, true), faceted(mesh, false);
  const Vec3 e1 = Vec3(1.0, 0.3, 0.2).normalized();
  const Vec3 e2 = e1.cross(Vec3(0.1, 1.0, -0.4)).normalized();
  const int steps = 20000;
  const double dAngle = 2.0 * M_PI / steps;
  double smoothJump = 0.0, facetJump = 0.0, smoothError = 0.0;
  Vec3 previousSmooth = Vec3::Zero(), previousFacet = Vec3::Zero();
  for (int k = 0; k <= steps; ++k) {
    const Vec3 dir = std::cos(k * dAngle) * e1 + std::sin(k * dAngle) * e2;
    const Vec3 p = kCentre + (radius + 0.02) * dir;
    SurfaceSample s, f;
    ASSERT_TRUE(smooth.sample(p, 1.0, s));
    ASSERT_TRUE(faceted.sample(p, 1.0, f));
    if (k > 0) {
      smoothJump = std::max(smoothJump, (s.normal - previousSmooth).norm());
      facetJump = std::max(facetJump, (f.normal - previousFacet).norm());
    }
    smoothError = std::max(smoothError, (s.normal - dir).norm());
    previousSmooth = s.normal;
    previousFacet = f.normal;
  }
  // Continuous: the normal turns by O(step) (a few times the path's own turning dAngle), never
  // by a jump. Faceted: jumps of the order of the dihedral angle (~0.3 rad at 2 levels).
  EXPECT_LT(smoothJump, 20 * dAngle);
  EXPECT_GT(facetJump, 0.1);
  EXPECT_LT(smoothError, 0.1);
}

}  // namespace
}  // namespace weft
