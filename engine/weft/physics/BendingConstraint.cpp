#include <weft/physics/BendingConstraint.h>

#include <weft/mesh/TriangleMesh.h>
#include <weft/model/ClothModel.h>
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

// N = n0/|n0| + n1/|n1| of the hinge's triangles (x0, x1, x2) and (x0, x3, x1), oriented alike
// (x2 and x3 lie on opposite sides of the edge x0 x1); zero where a triangle is degenerate.
Vec3 hingeNormal(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 n0 = (x1 - x0).cross(x2 - x0), n1 = (x3 - x0).cross(x1 - x0);
  const double a0 = n0.norm(), a1 = n1.norm();
  if (!(a0 > 0.0) || !(a1 > 0.0)) return Vec3::Zero();
  return n0 / a0 + n1 / a1;
}

// Below this |N| (the triangles folded onto each other) the oriented target falls back to the
// magnitude projection of the start's curvature.
constexpr double kFoldedNormal = 1e-6;

// The hinge frame [t, N^, t x N^] (N is orthogonal to the edge); false where it is undefined
// (a degenerate triangle, or the two folded onto each other).
bool hingeFrame(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3, Mat3& frame) {
  const Vec3 n = hingeNormal(x0, x1, x2, x3);
  const double length = n.norm(), edge = (x1 - x0).norm();
  if (!(length > kFoldedNormal) || !(edge > 0.0)) return false;
  frame.col(0) = (x1 - x0) / edge;
  frame.col(1) = n / length;
  frame.col(2) = frame.col(0).cross(frame.col(1));
  return true;
}

int oppositeVertex(const TriangleIndices& tris, int t, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (tris(t, k) != a && tris(t, k) != b) return tris(t, k);
  return -1;
}

}  // namespace

std::vector<Hinge> buildHinges(const NodeMatrix& rest, const TriangleIndices& triangles,
                               double stiffness, bool oriented) {
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
    Mat3 frame;
    h.oriented = oriented && h.restNorm > 0.0 && hingeFrame(x0, x1, x2, x3, frame);
    if (h.oriented) h.restLocal = frame.transpose() * restVector;
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
    anyOriented_ = anyOriented_ || hinges_[r].oriented;
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

void BendingConstraint::beginStep(double /*time*/, const NodeMatrix& start) {
  if (!anyOriented_) return;
  target_.assign(hinges_.size(), Vec3::Zero());
  for (std::size_t r = 0; r < hinges_.size(); ++r) {
    const Hinge& h = hinges_[r];
    if (!h.oriented) continue;
    Mat3 frame;
    if (hingeFrame(start.row(h.nodes[0]), start.row(h.nodes[1]), start.row(h.nodes[2]),
                   start.row(h.nodes[3]), frame)) {
      target_[r] = frame * h.restLocal;
    } else {
      const Vec3 e = curvature(h, start);
      if (e.norm() > 0.0) target_[r] = (h.restNorm / e.norm()) * e;
    }
  }
}

void BendingConstraint::addStartGradient(const NodeMatrix& start, const NodeMatrix& q, double scale,
                                         NodeMatrix& out) const {
  // p = c_t t + c_n N^ + c_b (t x N^). For g = scale w (A q): g . dp = dt . g_t + dN^ . g_N with
  // g_t = c_t g + c_b N^ x g and g_N = c_n g + c_b g x t; then t = a/|a| ((I - t t^T)/|a|),
  // N^ = N/|N| ((I - N^ N^^T)/|N|), n_i/|n_i| and the cross products n0 = a x b, n1 = c x a
  // (a = x1 - x0, b = x2 - x0, c = x3 - x0). (The folded fallback's is left out.)
  for (const Hinge& h : hinges_) {
    if (!h.oriented) continue;
    const Vec3 x0 = start.row(h.nodes[0]), x1 = start.row(h.nodes[1]), x2 = start.row(h.nodes[2]),
               x3 = start.row(h.nodes[3]);
    const Vec3 a = x1 - x0, b = x2 - x0, c = x3 - x0;
    const Vec3 n0 = a.cross(b), n1 = c.cross(a);
    const double l0 = n0.norm(), l1 = n1.norm();
    if (!(l0 > 0.0) || !(l1 > 0.0)) continue;
    const Vec3 u0 = n0 / l0, u1 = n1 / l1, n = u0 + u1;
    const double length = n.norm();
    if (!(length > kFoldedNormal)) continue;
    const double edge = a.norm();
    if (!(edge > 0.0)) continue;
    Vec3 aq = Vec3::Zero();
    for (int k = 0; k < 4; ++k) aq += h.cot[k] * q.row(h.nodes[k]).transpose();
    const Vec3 g = (scale * h.weight) * aq;
    const Vec3 nHat = n / length, t = a / edge;
    const Vec3& cl = h.restLocal;
    const Vec3 gt = cl[0] * g + cl[2] * nHat.cross(g);
    const Vec3 gN = cl[1] * g + cl[2] * g.cross(t);
    const Vec3 gn = (gN - nHat * nHat.dot(gN)) / length;  // d(N/|N|)^T g_N
    const Vec3 g0 = (gn - u0 * u0.dot(gn)) / l0;          // d(n0/|n0|)^T gn
    const Vec3 g1 = (gn - u1 * u1.dot(gn)) / l1;
    // d(a x b)^T g0: b x g0 for a, g0 x a for b; d(c x a)^T g1: a x g1 for c, g1 x c for a.
    const Vec3 da = b.cross(g0) + g1.cross(c) + (gt - t * t.dot(gt)) / edge;
    const Vec3 db = g0.cross(a), dc = a.cross(g1);
    out.row(h.nodes[1]) += da.transpose();
    out.row(h.nodes[2]) += db.transpose();
    out.row(h.nodes[3]) += dc.transpose();
    out.row(h.nodes[0]) -= (da + db + dc).transpose();
  }
}

double BendingConstraint::project(const NodeMatrix& x, NodeMatrix& wp) const {
  double energy = 0.0;
  const int count = static_cast<int>(hinges_.size());
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (int r = 0; r < count; ++r) {
    const Hinge& h = hinges_[r];
    const Vec3 e = curvature(h, x);
    Vec3 p = Vec3::Zero();
    if (h.oriented && !target_.empty()) {
      p = target_[r];
    } else if (h.restNorm > 0.0) {
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
    if (h.oriented && !target_.empty()) {
      energy += 0.5 * h.weight * (e - target_[r]).squaredNorm();
      continue;
    }
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
    if (h.restNorm == 0.0 || n == 0.0 || h.oriented) {  // (oriented: p constant in a step)
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
    const auto hinges =
        buildHinges(model.rest.vertices, tris, k,
                    scene.cloths[c].material.bendModel == Material::BendModel::Oriented);
    all.insert(all.end(), hinges.begin(), hinges.end());
  }
  return BendingConstraint(std::move(all), model.nodeCount());
}

}  // namespace weft
