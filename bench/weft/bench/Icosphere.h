#pragma once
// A triangulated sphere for benchmarks that compare a mesh obstacle with the analytic sphere
// (DiffCloth Fig. 2): a subdivided icosahedron, whose triangles are nearly uniform, so the
// jumps of its face normals are the same everywhere on the surface.

#include <weft/mesh/TriangleMesh.h>

namespace weft::bench {

// Outward-oriented, closed. `subdivisions` splits every triangle into four that many times:
// 20 * 4^subdivisions triangles.
TriangleMesh icosphere(const Vec3& center, double radius, int subdivisions);

}  // namespace weft::bench
