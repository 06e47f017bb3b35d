#pragma once
#include <weft/mesh/TriangleMesh.h>

namespace weft {

// The scene contract's `grid`: a rectangle in the local XZ plane centred at the origin with
// normal +Y; size = [extent X, extent Z], resolution = [quads X, quads Z], two triangles per
// quad, vertex (i, j) at index j * (resolution[0] + 1) + i.
TriangleMesh makeGrid(double sizeX, double sizeZ, int quadsX, int quadsZ);

}  // namespace weft
