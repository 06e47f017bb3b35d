#include <weft/frames/SyntheticDrape.h>

#include <weft/mesh/GridMesh.h>

#include <cmath>

namespace weft {

NodeMatrix drapeOverSphere(const NodeMatrix& flat, const DrapeSphere& sphere, int folds,
                           double amplitude) {
  const double pi = 3.14159265358979323846;
  const double r = sphere.radius + sphere.gap;
  const double equatorArc = 0.5 * pi * r;
  NodeMatrix draped(flat.rows(), 3);
  for (Eigen::Index i = 0; i < flat.rows(); ++i) {
    const double dx = flat(i, 0) - sphere.center.x(), dz = flat(i, 2) - sphere.center.z();
    const double s = std::hypot(dx, dz);  // arc length from the top of the sphere
    const double phi = std::atan2(dz, dx);
    const Vec3 radial(std::cos(phi), 0.0, std::sin(phi));
    Vec3 p;
    if (s <= equatorArc) {
      const double theta = s / r;
      p = sphere.center + r * (std::sin(theta) * radial + std::cos(theta) * Vec3::UnitY());
    } else {
      const double hang = s - equatorArc;
      // Folds grow with the hanging length, like a tablecloth's.
      const double wave = amplitude * hang * std::sin(folds * phi);
      const Vec3 tangent(-std::sin(phi), 0.0, std::cos(phi));
      p = sphere.center + (r + 0.5 * std::abs(wave)) * radial + 0.5 * wave * tangent -
          hang * Vec3::UnitY();
    }
    draped.row(i) = p.transpose();
  }
  return draped;
}

TriangleMesh drapedGrid(double size, int quads, const DrapeSphere& sphere) {
  TriangleMesh mesh = makeGrid(size, size, quads, quads);
  mesh.vertices.rowwise() += Eigen::RowVector3d(sphere.center.x(), 0.0, sphere.center.z());
  mesh.vertices = drapeOverSphere(mesh.vertices, sphere);
  return mesh;
}

}  // namespace weft
