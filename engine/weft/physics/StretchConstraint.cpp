#include <weft/physics/StretchConstraint.h>

#include <weft/physics/ClothModel.h>
#include <weft/scene/Scene.h>

#include <Eigen/Dense>
#include <cmath>

namespace weft {
namespace {

// Orthonormal frame of a triangle: e1 along x1 - x0, e2 Gram-Schmidt of x2 - x0. Both the rest
// and the current frame are built this way, so T^T F always has a positive determinant and the
// 2x2 polar factor is a rotation (no reflection case).
Eigen::Matrix<double, 3, 2> triangleFrame(const Vec3& x0, const Vec3& x1, const Vec3& x2) {
  Vec3 e1 = x1 - x0;
  Vec3 e2 = x2 - x0;
  double l1 = e1.norm();
  if (l1 < 1e-300) {  // collapsed edge: any frame in the plane of the other edge will do
    e1 = e2;
    l1 = e1.norm();
    if (l1 < 1e-300) e1 = Vec3::UnitX(), l1 = 1.0;
  }
  e1 /= l1;
  e2 -= e1.dot(e2) * e1;
  double l2 = e2.norm();
  if (l2 < 1e-12 * l1) {  // collinear: pick any unit vector orthogonal to e1
    e2 = e1.unitOrthogonal();
    l2 = 1.0;
  }
  Eigen::Matrix<double, 3, 2> t;
  t.col(0) = e1;
  t.col(1) = e2 / l2;
  return t;
}

}  // namespace

Eigen::Matrix<double, 3, 2> StretchConstraint::project(const Eigen::Matrix<double, 3, 2>& f,
                                                       const Vec3& x0, const Vec3& x1, const Vec3& x2) {
  const Eigen::Matrix<double, 3, 2> t = triangleFrame(x0, x1, x2);
  const Eigen::Matrix2d s = t.transpose() * f;
  // Closed-form polar rotation of a 2x2 matrix: the angle maximising tr(R^T S).
  const double c = s(0, 0) + s(1, 1), d = s(1, 0) - s(0, 1);
  const double n = std::hypot(c, d);
  Eigen::Matrix2d r;
  if (n > 0.0)
    r << c / n, -d / n, d / n, c / n;
  else
    r.setIdentity();
  return t * r;
}

StretchConstraint::StretchConstraint(const NodeMatrix& rest, const TriangleIndices& triangles,
                                     const std::vector<double>& stiffness) {
  const int count = static_cast<int>(triangles.rows());
  nodes_.resize(count);
  coeff_.resize(count);
  weights_.resize(2 * count);
  std::vector<Eigen::Triplet<double>> rows;
  rows.reserve(6 * count);
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3i n = triangles.row(t).transpose();
    const Vec3 x0 = rest.row(n[0]), x1 = rest.row(n[1]), x2 = rest.row(n[2]);
    const Eigen::Matrix<double, 3, 2> frame = triangleFrame(x0, x1, x2);
    Eigen::Matrix2d d;  // rest edges in the rest frame: upper triangular, positive diagonal
    d.col(0) = frame.transpose() * (x1 - x0);
    d.col(1) = frame.transpose() * (x2 - x0);
    const Eigen::Matrix2d dinv = d.inverse();
    Coefficients c;
    for (int col = 0; col < 2; ++col) {
      c(col, 1) = dinv(0, col);
      c(col, 2) = dinv(1, col);
      c(col, 0) = -dinv(0, col) - dinv(1, col);
    }
    const double area = 0.5 * std::abs(d.determinant());
    nodes_[t] = n;
    coeff_[t] = c;
    weights_[2 * t] = weights_[2 * t + 1] = stiffness[t] * area;
    for (int col = 0; col < 2; ++col)
      for (int j = 0; j < 3; ++j) rows.emplace_back(2 * t + col, n[j], c(col, j));
  }
  setSelection(static_cast<int>(rest.rows()), rows);
}

double StretchConstraint::project(const NodeMatrix& x, NodeMatrix& wp) const {
  double energy = 0.0;
  const int count = triangleCount();
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3i& n = nodes_[t];
    const Vec3 x0 = x.row(n[0]), x1 = x.row(n[1]), x2 = x.row(n[2]);
    const Coefficients& c = coeff_[t];
    Eigen::Matrix<double, 3, 2> f;
    for (int col = 0; col < 2; ++col) f.col(col) = c(col, 0) * x0 + c(col, 1) * x1 + c(col, 2) * x2;
    const Eigen::Matrix<double, 3, 2> q = project(f, x0, x1, x2);
    const double w = weights_[2 * t];
    energy += 0.5 * w * (f - q).squaredNorm();
    wp.row(2 * t) = w * q.col(0).transpose();
    wp.row(2 * t + 1) = w * q.col(1).transpose();
  }
  return energy;
}

StretchConstraint makeStretchConstraint(const Scene& scene, const ClothModel& model) {
  std::vector<int> keep;
  std::vector<double> stiffness;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const double k = scene.cloths[c].material.stretch;
    if (k <= 0.0) continue;
    for (int t = model.triangleOffset[c]; t < model.triangleOffset[c + 1]; ++t) {
      keep.push_back(t);
      stiffness.push_back(k);
    }
  }
  TriangleIndices tris(static_cast<int>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) tris.row(static_cast<int>(i)) = model.rest.triangles.row(keep[i]);
  return StretchConstraint(model.rest.vertices, tris, stiffness);
}

}  // namespace weft
