#include <weft/mesh/RigidTransform.h>

#include <Eigen/Geometry>
#include <cmath>

namespace weft {

Mat3 RigidTransform::rotation() const {
  const double d2r = M_PI / 180.0;
  using Eigen::AngleAxisd;
  // X first, then Y, then Z: the rotation applied to a point is Rz * Ry * Rx.
  return (AngleAxisd(rotateDeg.z() * d2r, Vec3::UnitZ()) *
          AngleAxisd(rotateDeg.y() * d2r, Vec3::UnitY()) *
          AngleAxisd(rotateDeg.x() * d2r, Vec3::UnitX()))
      .toRotationMatrix();
}

void RigidTransform::applyTo(NodeMatrix& points) const {
  const Mat3 r = rotation();
  for (int i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).transpose();
    points.row(i) = (r * p + translate).transpose();
  }
}

}  // namespace weft
