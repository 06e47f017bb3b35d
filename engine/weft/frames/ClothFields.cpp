#include <weft/frames/ClothFields.h>

#include <Eigen/Dense>

#include <cmath>

namespace weft {

Eigen::VectorXd vertexStrain(const TriangleMesh& rest, const NodeMatrix& deformed) {
  const int n = rest.vertexCount();
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), weight = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < rest.triangleCount(); ++t) {
    const int a = rest.triangles(t, 0), b = rest.triangles(t, 1), c = rest.triangles(t, 2);
    // Rest edges in the triangle's own 2D frame, so F = D_deformed * D_rest^-1 is 3 x 2.
    const Vec3 e1 = rest.vertices.row(b) - rest.vertices.row(a),
               e2 = rest.vertices.row(c) - rest.vertices.row(a);
    const double area = 0.5 * e1.cross(e2).norm();
    if (!(area > 0.0)) continue;
    const Vec3 u = e1.normalized(), v = (e2 - e2.dot(u) * u).normalized();
    Eigen::Matrix2d restEdges;
    restEdges << e1.dot(u), e2.dot(u), e1.dot(v), e2.dot(v);
    Eigen::Matrix<double, 3, 2> deformedEdges;
    deformedEdges.col(0) = deformed.row(b) - deformed.row(a);
    deformedEdges.col(1) = deformed.row(c) - deformed.row(a);
    const Eigen::Matrix<double, 3, 2> F = deformedEdges * restEdges.inverse();
    const Eigen::Vector2d stretches =
        Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(F).singularValues();
    const double high = stretches(0) - 1.0, low = stretches(1) - 1.0;
    const double strain = std::abs(high) >= std::abs(low) ? high : low;
    if (!std::isfinite(strain)) continue;
    for (int k : {a, b, c}) sum[k] += area * strain, weight[k] += area;
  }
  return (weight.array() > 0.0).select(sum.array() / weight.array(), 0.0);
}

Eigen::VectorXd vertexSpeed(const NodeMatrix& previous, const NodeMatrix& next, double dt) {
  return (next - previous).rowwise().norm() / dt;
}

}  // namespace weft
