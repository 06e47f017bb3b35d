#include <weft/physics/StretchConstraint.h>

#include <weft/model/ClothModel.h>
#include <weft/scene/Scene.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace weft {
namespace {

// Smallest singular value of F the derivative divides by (a collapsed triangle's is 0).
constexpr double kSmallestStretch = 1e-12;

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
                                                       const Vec3& x0, const Vec3& x1,
                                                       const Vec3& x2) {
  const Eigen::Matrix<double, 3, 2> t = triangleFrame(x0, x1, x2);
  const Eigen::Matrix2d s = t.transpose() * f;
  // Closed-form polar rotation of a 2x2 matrix: the angle maximising tr(R^T S).
  const double c = s(0, 0) + s(1, 1), d = s(1, 0) - s(0, 1);
  const double n = std::sqrt(c * c + d * d);
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
  // Closed form of the projection above, without forming F or the frame as matrices. With
  // e1 = x1 - x0, e2 = x2 - x0, column c of F is a_c e1 + b_c e2 (a_c = coeff(c,1),
  // b_c = coeff(c,2)). In the current frame t1 = e1/|e1|, t2 = (e2 - (t1.e2) t1)/|...|, F = T S
  // with S = [[a_c |e1| + b_c (t1.e2)], [b_c |u|]], so |F - T R|^2 = |S|^2 - 2 |(s00 + s11,
  // s10 - s01)| + 2 (evaluated as |S - R|^2), and the projection is T R.
  double energy = 0.0;
  const int count = triangleCount();
  const double* px = x.col(0).data();
  const double* py = x.col(1).data();
  const double* pz = x.col(2).data();
  double* wx = wp.col(0).data();
  double* wy = wp.col(1).data();
  double* wz = wp.col(2).data();
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3i& n = nodes_[t];
    const Vec3 x0(px[n[0]], py[n[0]], pz[n[0]]);
    const Vec3 e1 = Vec3(px[n[1]], py[n[1]], pz[n[1]]) - x0;
    const Vec3 e2 = Vec3(px[n[2]], py[n[2]], pz[n[2]]) - x0;
    const Coefficients& c = coeff_[t];
    const double w = weights_[2 * t];
    const double l1 = e1.norm();
    Eigen::Matrix<double, 3, 2> q;
    double s00, s01, s10, s11;
    if (l1 > 0.0) {
      const Vec3 t1 = e1 / l1;
      const double d = t1.dot(e2);
      Vec3 u = e2 - d * t1;
      const double lu = u.norm();
      const Vec3 t2 = lu > 1e-12 * l1 ? Vec3(u / lu) : Vec3(t1.unitOrthogonal());
      s00 = c(0, 1) * l1 + c(0, 2) * d;
      s01 = c(1, 1) * l1 + c(1, 2) * d;
      s10 = c(0, 2) * lu;
      s11 = c(1, 2) * lu;
      const double cs = s00 + s11, sn = s10 - s01;
      const double norm = std::sqrt(cs * cs + sn * sn);
      const double r00 = norm > 0.0 ? cs / norm : 1.0, r10 = norm > 0.0 ? sn / norm : 0.0;
      // R = [[r00, -r10], [r10, r00]]; Q = T R.
      q.col(0) = r00 * t1 + r10 * t2;
      q.col(1) = -r10 * t1 + r00 * t2;
      // |S - R|^2 term by term: the expanded |S|^2 - 2|.| + 2 cancels catastrophically near rest,
      // and the Anderson safeguard compares energies that differ in the 12th digit.
      const double d00 = s00 - r00, d01 = s01 + r10, d10 = s10 - r10, d11 = s11 - r00;
      energy += 0.5 * w * (d00 * d00 + d01 * d01 + d10 * d10 + d11 * d11);
    } else {  // collapsed edge: the general routine picks a frame
      Eigen::Matrix<double, 3, 2> f;
      for (int col = 0; col < 2; ++col) f.col(col) = c(col, 1) * e1 + c(col, 2) * e2;
      q = project(f, x0, x0 + e1, x0 + e2);
      energy += 0.5 * w * (f - q).squaredNorm();
    }
    const int r0 = 2 * t, r1 = 2 * t + 1;
    wx[r0] = w * q(0, 0), wy[r0] = w * q(1, 0), wz[r0] = w * q(2, 0);
    wx[r1] = w * q(0, 1), wy[r1] = w * q(1, 1), wz[r1] = w * q(2, 1);
  }
  return energy;
}

void StretchConstraint::prepareDerivative(const NodeMatrix& x, bool definite) {
  const int count = triangleCount();
  derivative_.resize(count);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3i& n = nodes_[t];
    const Vec3 x0 = x.row(n[0]), x1 = x.row(n[1]), x2 = x.row(n[2]);
    const Coefficients& c = coeff_[t];
    Eigen::Matrix<double, 3, 2> f;
    for (int col = 0; col < 2; ++col) f.col(col) = c(col, 1) * (x1 - x0) + c(col, 2) * (x2 - x0);
    Derivative& d = derivative_[t];
    d.q = project(f, x0, x1, x2);
    d.n = d.q.col(0).cross(d.q.col(1));
    // S = Q^T F is symmetric positive (semi-)definite: F = Q S is the polar decomposition.
    // Its eigenvalues in closed form (an iterative 2x2 eigensolver was a third of this loop).
    const Eigen::Matrix2d s2 = d.q.transpose() * f;
    const double sa = s2(0, 0), sb = 0.5 * (s2(0, 1) + s2(1, 0)), sc = s2(1, 1);
    const double mean = 0.5 * (sa + sc), radius = std::hypot(0.5 * (sa - sc), sb);
    const double sigma0 = std::max(mean - radius, kSmallestStretch),
                 sigma1 = std::max(mean + radius, kSmallestStretch);
    // The Hessian of |F - Q(F)|^2 / 2 is I - dQ/dF with eigenvalues 1 - 2/(s1+s2) (in-plane
    // rotation) and 1 - 1/s_i (out of plane); `definite` clamps dQ's to at most 1, keeping them >=
    // 0.
    const double cap = definite ? 1.0 : std::numeric_limits<double>::infinity();
    const double rot = std::min(2.0 / (sigma0 + sigma1), cap);
    // B = g(S), g(s) = min(1 / s, cap) on the clamped eigenvalues: g0 I + (g1 - g0) v1 v1^T with
    // v1 the eigenvector of the larger one, v1 v1^T = (I + [[cos 2t, sin 2t], [sin 2t, -cos 2t]])
    // / 2.
    const double g0 = std::min(1.0 / sigma0, cap), g1 = std::min(1.0 / sigma1, cap);
    const double cos2 = radius > 0.0 ? 0.5 * (sa - sc) / radius : 1.0,
                 sin2 = radius > 0.0 ? sb / radius : 0.0;
    const double lift = 0.5 * (g1 - g0);
    const double b00 = g0 + lift * (1.0 + cos2), b01 = lift * sin2, b11 = g0 + lift * (1.0 - cos2);
    d.rot = rot;
    d.b00 = b00, d.b01 = b01, d.b11 = b11;
  }
}

void StretchConstraint::applyDerivative(const NodeMatrix& dx, NodeMatrix& wp) const {
  const int count = triangleCount();
#pragma omp parallel for schedule(static)
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3i& n = nodes_[t];
    const Coefficients& c = coeff_[t];
    const Derivative& d = derivative_[t];
    const Vec3 d0 = dx.row(n[0]), d1 = dx.row(n[1]) - d0.transpose(),
               d2 = dx.row(n[2]) - d0.transpose();
    const Vec3 f0 = c(0, 1) * d1 + c(0, 2) * d2, f1 = c(1, 1) * d1 + c(1, 2) * d2;
    // In-plane rotation: QJ = [q1, -q0].
    const double omega = 0.5 * d.rot * (d.q.col(1).dot(f0) - d.q.col(0).dot(f1));
    const double a0 = d.n.dot(f0), a1 = d.n.dot(f1);  // out-of-plane row n^T dF
    const double o0 = a0 * d.b00 + a1 * d.b01, o1 = a0 * d.b01 + a1 * d.b11;
    const double w = weights_[2 * t];
    wp.row(2 * t) = w * (omega * d.q.col(1) + o0 * d.n).transpose();
    wp.row(2 * t + 1) = w * (-omega * d.q.col(0) + o1 * d.n).transpose();
  }
}

bool StretchConstraint::derivativeBlocks(DerivativeBlockSink& sink) const {
  // applyDerivative as a matrix on the stacked F columns (f0, f1) = (A_0 dx, A_1 dx):
  // w D = w (rot/2 u u^T + blockdiag(n, n) B blockdiag(n, n)^T), u = (q1, -q0), symmetric;
  // the triangle's block is C^T (w D) C with C = coeff (x) I_3.
  Eigen::Matrix<double, 9, 9> block;
  for (int t = 0; t < triangleCount(); ++t) {
    const Coefficients& c = coeff_[t];
    const Derivative& d = derivative_[t];
    const double w = weights_[2 * t];
    const Vec3 u[2] = {d.q.col(1), -d.q.col(0)};
    const double b[2][2] = {{d.b00, d.b01}, {d.b01, d.b11}};
    Mat3 rows[2][2];  // w D_rs
    for (int r = 0; r < 2; ++r)
      for (int s = 0; s < 2; ++s)
        rows[r][s] = w * (0.5 * d.rot * u[r] * u[s].transpose() + b[r][s] * d.n * d.n.transpose());
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        Mat3 sum = Mat3::Zero();
        for (int r = 0; r < 2; ++r)
          for (int s = 0; s < 2; ++s) sum += (c(r, j) * c(s, k)) * rows[r][s];
        block.block<3, 3>(3 * j, 3 * k) = sum;
      }
    sink.add(nodes_[t].data(), 3, block.data());
  }
  return true;
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
  for (std::size_t i = 0; i < keep.size(); ++i)
    tris.row(static_cast<int>(i)) = model.rest.triangles.row(keep[i]);
  return StretchConstraint(model.rest.vertices, tris, stiffness);
}

}  // namespace weft
