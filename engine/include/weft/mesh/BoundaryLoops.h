#pragma once
// The open borders of a triangle mesh: its boundary edges (edges of exactly one triangle) joined
// into loops, such as a skirt's waist and hem or a sleeve's cuff. The editor selects a garment's
// waist or hem by them.

#include <weft/mesh/TriangleMesh.h>

#include <vector>

namespace weft {

// One vector of vertex indices per connected run of boundary edges, in the order the run walks
// them (a closed loop starts at its smallest index and goes towards its smaller neighbour).
// Where a boundary vertex has more than two boundary edges (two borders touching at a vertex),
// the walk cannot choose, and that run is listed sorted instead. Loops are ordered by their
// first vertex. A closed surface has none.
std::vector<std::vector<int>> boundaryLoops(const TriangleMesh& mesh);

}  // namespace weft
