#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>

namespace weft {

// Reads a triangle mesh keeping the file's vertex order and count (no welding, splitting or
// reordering), since attachments, targets and outputs refer to vertices by index. FBX is the
// exception: assimp gives each triangle corner its own vertex, and corners at one position are
// joined again, numbered in order of first use (MeshReader.cpp).
// OBJ goes through tinyobjloader; every other format (glTF, FBX, PLY, ...) through assimp.
// Polygons are fan-triangulated. Throws InputError(path, "mesh", ...) on failure.
TriangleMesh readMesh(const std::string& path);

}  // namespace weft
