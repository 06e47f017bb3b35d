#pragma once
// Broad phase of continuous collision detection (Liang et al. 2019 Sec. 3.3: "a bounding volume
// hierarchy for collision detection"): a BVH over the boxes each triangle of one collision mesh
// sweeps during a step, inflated by the thickness. Its topology (median splits of the rest-state
// centroids) is built once; each call refits the boxes to the step's start and end positions and
// traverses the tree against itself.
//
// Candidates: vertex-face pairs (vertex not a corner of the face) and edge-edge pairs (edges
// sharing no vertex), each once. A vertex's (an edge's) path lies inside the swept box of every
// triangle containing it, so each vertex and edge is owned by one of its triangles and a pair
// is emitted only from the overlap of its owners' boxes: exact deduplication, nothing lost.
// Pairs whose four nodes are all flagged static (an obstacle mesh concatenated into the
// collision mesh) are skipped: obstacles do not collide with themselves.
//
// findImpacts runs the narrow phase (PairCcd) over the candidates in parallel and returns the
// impacts in mesh node indices sorted by (time, kind, nodes): the same list for any number of
// threads.

#include <weft/collision/PairCcd.h>
#include <weft/mesh/TriangleMesh.h>

#include <vector>

namespace weft::collision {

struct CcdCandidate {
  ImpactKind kind = ImpactKind::VertexFace;
  std::array<int, 4> nodes{
      {-1, -1, -1, -1}};  // vertex-face {v, f0, f1, f2}; edge-edge {a0, a1, b0, b1}
};

class SweptBroadPhase {
 public:
  // staticVertex: empty (nothing static) or one flag per mesh vertex.
  explicit SweptBroadPhase(const TriangleMesh& mesh, std::vector<bool> staticVertex = {});

  // The candidate pairs for a step from start to end (m x 3 each), sorted by (kind, nodes).
  const std::vector<CcdCandidate>& findCandidates(const NodeMatrix& start, const NodeMatrix& end,
                                                  double thickness);
  // The narrow phase over findCandidates; sorted by (time, kind, nodes).
  std::vector<Impact> findImpacts(const NodeMatrix& start, const NodeMatrix& end, double thickness);

  const std::vector<MeshEdge>& edges() const { return edges_; }
  int vertexCount() const { return vertexCount_; }

 private:
  struct Node {
    Vec3 lower, upper;
    int first = 0, count = 0;   // leaf: triangles order_[first, first + count)
    int left = -1, right = -1;  // inner node children (index greater than the parent's)
  };
  int build(int first, int count, const std::vector<Vec3>& centroids, int depth);
  void refit(const NodeMatrix& start, const NodeMatrix& end, double thickness);
  void leafPairs(const Node& a, const Node& b);
  void trianglePair(int t1, int t2);

  int vertexCount_ = 0;
  TriangleIndices triangles_;
  std::vector<MeshEdge> edges_;
  std::vector<bool> static_;
  std::vector<std::array<int, 3>> triangleEdges_;     // per triangle: its owned edges (-1: none)
  std::vector<std::array<int, 3>> triangleVertices_;  // per triangle: its owned vertices
  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<Vec3> triLower_, triUpper_;
  std::vector<std::pair<int, int>> stack_;
  std::vector<CcdCandidate> candidates_;
  std::vector<std::vector<Impact>> perThread_;
};

// Orders impacts by (time, kind, nodes): the deterministic order of findImpacts.
bool impactLess(const Impact& a, const Impact& b);

}  // namespace weft::collision
