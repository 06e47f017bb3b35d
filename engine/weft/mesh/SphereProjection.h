#pragma once
#include <weft/mesh/TriangleMesh.h>

namespace weft {

// Moves every vertex of `mesh` along Y onto the upper half of the sphere (center, radius): a
// flat cloth in the XZ plane becomes a patch lying on the sphere, whose rest shape is that
// patch, so it starts unstretched and in contact everywhere (DiffCloth Fig. 2's cloth on a
// sphere). Triangles keep their winding, so a +Y-facing grid faces outwards. Throws
// std::invalid_argument when a vertex lies outside the sphere's horizontal disc.
TriangleMesh projectOntoSphere(const TriangleMesh& mesh, const Vec3& center, double radius);

}  // namespace weft
