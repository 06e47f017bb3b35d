#include <weft/mesh/SphereProjection.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace weft {

TriangleMesh projectOntoSphere(const TriangleMesh& mesh, const Vec3& center, double radius) {
  TriangleMesh out = mesh;
  for (int i = 0; i < out.vertexCount(); ++i) {
    const double dx = out.vertices(i, 0) - center.x(), dz = out.vertices(i, 2) - center.z();
    const double h2 = radius * radius - dx * dx - dz * dz;
    if (!(h2 > 0.0))
      throw std::invalid_argument("vertex " + std::to_string(i) +
                                  " lies outside the sphere's horizontal disc");
    out.vertices(i, 1) = center.y() + std::sqrt(h2);
  }
  return out;
}

}  // namespace weft
