#pragma once
// An independent check of a static state: the (edge, triangle) pairs of a mesh, sharing no
// vertex, where the edge's segment passes through the triangle. A state reached by collision
// handling that is free of intersections (Liang et al. 2019 Sec. 3.3-3.4: cloth that never passes
// through itself) has none, so a step that starts with none must end with none. Deliberately
// shares nothing with the continuous collision code (PairCcd, SweptBroadPhase): its own box
// broad phase (a uniform grid) and orientation predicates instead of closest points.
//
// Segment PQ crosses triangle ABC when P and Q lie strictly on opposite sides of the triangle's
// plane, sign det[B-A, C-A, P-A] = -sign det[B-A, C-A, Q-A] != 0, and the line PQ passes strictly
// inside the triangle, the three determinants det[Q-P, A-P, B-P], det[Q-P, B-P, C-P],
// det[Q-P, C-P, A-P] all nonzero and of one sign. Ties (a zero determinant: an endpoint in the
// plane, the segment coplanar with the triangle, or through its boundary) count as no crossing,
// so only proper transversal crossings are reported. The determinants are evaluated in floating
// point, and one within 1e-10 of its factors' lengths' product counts as zero: configurations
// within rounding of a tie (a flat sheet in any orientation) are ties, not crossings.

#include <weft/mesh/TriangleMesh.h>

#include <utility>
#include <vector>

namespace weft::collision {

struct EdgeTriangleCrossings {
  std::vector<std::pair<int, int>> pairs;  // (edge index in buildEdges(mesh), triangle index)
  int count() const { return static_cast<int>(pairs.size()); }
};

// The crossings of the mesh's topology with its vertices at `positions` (m x 3), sorted.
EdgeTriangleCrossings findEdgeTriangleCrossings(const TriangleMesh& mesh,
                                                const NodeMatrix& positions);

// Whether segment [p, q] crosses triangle (a, b, c) by the rule above.
bool segmentCrossesTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c);

}  // namespace weft::collision
