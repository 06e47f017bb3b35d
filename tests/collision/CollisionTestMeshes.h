#pragma once
// Small meshes for the collision tests: a grid of nu x nv cells spanned by two vectors, each
// cell split by the diagonal from its corner (i, j) to (i + 1, j + 1), so that the crossing
// counts of the tests can be derived by hand.

#include <weft/mesh/TriangleMesh.h>

namespace weft::collision::test {

inline TriangleMesh gridMesh(const Vec3& origin, const Vec3& u, const Vec3& v, int nu, int nv) {
  TriangleMesh mesh;
  mesh.vertices.resize((nu + 1) * (nv + 1), 3);
  auto id = [&](int i, int j) { return j * (nu + 1) + i; };
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      mesh.vertices.row(id(i, j)) = (origin + i * u + j * v).transpose();
  mesh.triangles.resize(2 * nu * nv, 3);
  int t = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      mesh.triangles.row(t++) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      mesh.triangles.row(t++) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return mesh;
}

}  // namespace weft::collision::test
