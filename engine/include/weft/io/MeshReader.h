#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>

namespace weft {

// Reads a triangle mesh keeping the file's vertex order and count (no welding, splitting or
// reordering), since attachments, targets and outputs refer to vertices by index. FBX is the
// exception: assimp gives each triangle corner its own vertex, and corners at one position are
// joined again, numbered in order of first use (MeshReader.cpp).
// OBJ goes through tinyobjloader; PLY and glTF 2.0 through Weft's own readers (PlyReader.h,
// GltfReader.h: Debian's assimp 5.2 hangs on some malformed PLY files and reads past a buffer on
// some malformed glTF files, docs/hardening.md); every other format (FBX, Collada, STL, ...)
// through assimp, in a child process so that a crash or hang inside it is an InputError here
// (AssimpReader.h). Polygons are fan-triangulated. Throws InputError(path, "mesh", ...) on failure.
TriangleMesh readMesh(const std::string& path);

}  // namespace weft
