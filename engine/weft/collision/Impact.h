#pragma once
// One impact found by continuous collision detection (Liang et al. 2019 Sec. 3.3): a vertex-face
// or edge-edge pair of a collision mesh that comes closer than the thickness within a step.
// It is the common currency of the collision folder: CCD produces impacts, impact zones
// (Liang Sec. 3.4) turn them into the QP's linear constraints.
//
// Convention (as in ARCSim): the pair's separation vector is s(x) = sum_k weights[k] x[nodes[k]]
//   vertex-face: nodes = {v, f0, f1, f2}, weights = {1, -b0, -b1, -b2} (b: barycentric of the
//                closest face point at the time of impact);
//   edge-edge:   nodes = {a0, a1, b0, b1}, weights = {1 - s, s, -(1 - u), -u} (s, u: the closest
//                points' parameters on edges a and b at the time of impact);
// and normal is the unit direction the pair must stay apart along: the direction of s at the time
// of impact where that is defined, else oriented so that normal . s(x_start) >= 0 (PairCcd.h). The
// impact constraint is normal . s(z) >= thickness, that is one row of Liang Eq. 9, G z + h <= 0,
// with G's row -weights[k] normal^T at node k and h = thickness.

#include <weft/core/Types.h>

#include <array>

namespace weft::collision {

enum class ImpactKind : int { VertexFace = 0, EdgeEdge = 1 };

struct Impact {
  ImpactKind kind = ImpactKind::VertexFace;
  std::array<int, 4> nodes{{-1, -1, -1, -1}};  // indices into the collision mesh's vertices
  std::array<double, 4> weights{{0.0, 0.0, 0.0, 0.0}};
  Vec3 normal = Vec3::UnitZ();
  double time = 0.0;  // fraction of the step in [0, 1] at which the pair is closest
};

}  // namespace weft::collision
