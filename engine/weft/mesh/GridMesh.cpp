#include <weft/mesh/GridMesh.h>

namespace weft {

TriangleMesh makeGrid(double sizeX, double sizeZ, int quadsX, int quadsZ) {
  TriangleMesh mesh;
  const int nx = quadsX + 1, nz = quadsZ + 1;
  mesh.vertices.resize(nx * nz, 3);
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i)
      mesh.vertices.row(j * nx + i) << -0.5 * sizeX + sizeX * i / quadsX, 0.0,
          -0.5 * sizeZ + sizeZ * j / quadsZ;
  mesh.triangles.resize(2 * quadsX * quadsZ, 3);
  int t = 0;
  for (int j = 0; j < quadsZ; ++j) {
    for (int i = 0; i < quadsX; ++i) {
      const int v00 = j * nx + i, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
      // Both triangles wind so that their normal is +Y.
      mesh.triangles.row(t++) << v00, v01, v10;
      mesh.triangles.row(t++) << v10, v01, v11;
    }
  }
  return mesh;
}

}  // namespace weft
