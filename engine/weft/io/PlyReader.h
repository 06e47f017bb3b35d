#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>

namespace weft {

// Reads a PLY file (ASCII, binary little- or big-endian): the `vertex` element's x, y, z in file
// order and the `face` element's `vertex_indices` (or `vertex_index`) lists, fan-triangulated.
// Other elements and properties are read past. Every count the header states is checked against
// the bytes that follow before anything is allocated, so a malformed file is refused quickly.
// Throws InputError(path, "mesh", ...).
TriangleMesh readPly(const std::string& path);

}  // namespace weft
