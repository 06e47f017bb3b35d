#include <weft/physics/BendingConstraint.h>

#include <weft/mesh/TriangleMesh.h>
#include <weft/physics/ClothModel.h>
#include <weft/scene/Scene.h>

#include <algorithm>
#include <cmath>

namespace weft {
namespace {

// Cotangent of the angle at `apex` in the triangle (apex, p, q).
double cotangent(const Vec3& apex, const Vec3& p, const Vec3& q) {
  const Vec3 u = p - apex, v = q - apex;
  return u.dot(v) / u.cross(v).norm();
}

int oppositeVertex(const TriangleIndices& tris, int t, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (tris(t, k) != a && tris(t, k) != b) return tris(t, k);
  return -1;
}

}  // namespace

std::vector<Hinge> buildHinges(const NodeMatrix& rest, const TriangleIndices& triangles,
                               double stiffness) {
  TriangleMesh mesh;
  mesh.vertices = rest;
  mesh.triangles = triangles;
  std::vector<Hinge> hinges;
  for (const MeshEdge& e : buildEdges(mesh)) {
    if (e.faces.size() != 2) continue;  // boundary or non-manifold: no hinge
    Hinge h;
    h.nodes[0] = e.a;
    h.nodes[1] = e.b;
    h.nodes[2] = oppositeVertex(triangles, e.faces[0], e.a, e.b);
    h.nodes[3] = oppositeVertex(triangles, e.faces[1], e.a, e.b);
    const Vec3 x0 = rest.row(h.nodes[0]), x1 = rest.row(h.nodes[1]), x2 = rest.row(h.nodes[2]),
               x3 = rest.row(h.nodes[3]);
    const double c00 = cotangent(x0, x1, x2), c01 = cotangent(x1, x0, x2);  // triangle 0
    const double c10 = cotangent(x0, x1, x3), c11 = cotangent(x1, x0, x3);  // triangle 1
    h.cot[0] = c01 + c11;
    h.cot[1] = c00 + c10;
    h.cot[2] = -(c00 + c01);
    h.cot[3] = -(c10 + c11);
    const Vec3 restVector = h.cot[0] * x0 + h.cot[1] * x1 + h.cot[2] * x2 + h.cot[3] * x3;
    const double edgeLength = (x1 - x0).norm();
    h.restNorm = restVector.norm() > 1e-8 * edgeLength ? restVector.norm() : 0.0;
    const double area = 0.5 * ((x1 - x0).cross(x2 - x0).norm() + (x1 - x0).cross(x3 - x0).norm());
    h.weight = stiffness * 3.0 / area;
    hinges.push_back(h);
  }
  return hinges;
}

BendingConstraint::BendingConstraint(std::vector<Hinge> hinges, int nodes)
    : hinges_(std::move(hinges)) {
  weights_.resize(static_cast<int>(hinges_.size()));
  std::vector<Eigen::Triplet<double>> rows;
  rows.reserve(4 * hinges_.size());
  for (std::size_t r = 0; r < hinges_.size(); ++r) {
    weights_[static_cast<int>(r)] = hinges_[r].weight;
    allFlat_ = allFlat_ && hinges_[r].restNorm == 0.0;
    for (int k = 0; k < 4; ++k)
      rows.emplace_back(static_cast<int>(r), hinges_[r].nodes[k], hinges_[r].cot[k]);
  }
  setSelection(nodes, rows);
}

namespace {

// The hinge's cotangent-weighted mean-curvature vector sum_k cot_k x_k (zero on a flat hinge).
Vec3 curvature(const Hinge& h, const NodeMatrix& x) {
  Vec3 e = Vec3::Zero();
  for (int k = 0; k < 4; ++k) e += h.cot[k] * x.row(h.nodes[k]).transpose();
  return e;
}

}  // namespace

double BendingConstraint::project(const NodeMatrix& x, NodeMatrix& wp) const {
  double energy = 0.0;
  const int count = static_cast<int>(hinges_.size());
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (int r = 0; r < count; ++r) {
    const Hinge& h = hinges_[r];
    const Vec3 e = curvature(h, x);
    Vec3 p = Vec3::Zero();
    if (h.restNorm > 0.0) {
      const double n = e.norm();
      if (n > 0.0) p = (h.restNorm / n) * e;
    }
    energy += 0.5 * h.weight * (e - p).squaredNorm();
    wp.row(r) = h.weight * p.transpose();
  }
  return energy;
}

double BendingConstraint::energy(const NodeMatrix& x) const {
  double energy = 0.0;
  const int count = static_cast<int>(hinges_.size());
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (int r = 0; r < count; ++r) {
    const Hinge& h = hinges_[r];
    const Vec3 e = curvature(h, x);
    const double excess = h.restNorm > 0.0 ? e.norm() - h.restNorm : e.norm();
    energy += 0.5 * h.weight * excess * excess;
  }
  return energy;
}

void BendingConstraint::prepareDerivative(const NodeMatrix& x, bool definite) {
  const int count = static_cast<int>(hinges_.size());
  unit_.resize(count);
  scale_.resize(count);
  for (int r = 0; r < count; ++r) {
    const Hinge& h = hinges_[r];
    const Vec3 e = curvature(h, x);
    const double n = e.norm();
    if (h.restNorm == 0.0 || n == 0.0) {
      unit_[r].setZero();
      scale_[r] = 0.0;
      continue;
    }
    unit_[r] = e / n;
    // Hessian eigenvalue across u is 1 - |e_rest|/|e|: clamp the derivative to keep it >= 0.
    scale_[r] = definite ? std::min(1.0, h.restNorm / n) : h.restNorm / n;
  }
}

void BendingConstraint::applyDerivative(const NodeMatrix& dx, NodeMatrix& wp) const {
  const int count = static_cast<int>(hinges_.size());
  for (int r = 0; r < count; ++r) {
    const Hinge& h = hinges_[r];
    Vec3 de = Vec3::Zero();
    for (int k = 0; k < 4; ++k) de += h.cot[k] * dx.row(h.nodes[k]).transpose();
    const Vec3 dp = scale_[r] * (de - unit_[r] * unit_[r].dot(de));
    wp.row(r) = h.weight * dp.transpose();
  }
}

bool BendingConstraint::derivativeBlocks(DerivativeBlockSink& sink) const {
  // applyDerivative is w scale (I - u u^T) (sum_k c_k dx_k): the hinge's block is
  // w scale (c c^T) (x) (I - u u^T).
  Eigen::Matrix<double, 12, 12> block;
  for (std::size_t r = 0; r < hinges_.size(); ++r) {
    if (scale_[r] == 0.0) continue;
    const Hinge& h = hinges_[r];
    const Mat3 across = h.weight * scale_[r] * (Mat3::Identity() - unit_[r] * unit_[r].transpose());
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) block.block<3, 3>(3 * j, 3 * k) = (h.cot[j] * h.cot[k]) * across;
    sink.add(h.nodes, 4, block.data());
  }
  return true;
}

BendingConstraint makeBendingConstraint(const Scene& scene, const ClothModel& model) {
  std::vector<Hinge> all;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const double k = scene.cloths[c].material.bend;
    if (k <= 0.0) continue;
    const int t0 = model.triangleOffset[c], t1 = model.triangleOffset[c + 1];
    const TriangleIndices tris = model.rest.triangles.middleRows(t0, t1 - t0);
    const auto hinges = buildHinges(model.rest.vertices, tris, k);
    all.insert(all.end(), hinges.begin(), hinges.end());
  }
  return BendingConstraint(std::move(all), model.nodeCount());
}

}  // namespace weft
