#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>

namespace weft {

// Reads a glTF 2.0 file (`.gltf` with its buffers in data URIs or files beside it, or a binary
// `.glb`): every triangle primitive's POSITION vertices in accessor order, placed by the node
// hierarchy of the file's scene (each mesh once per node that references it, in depth-first node
// order; a mirroring node lists corners the other way round; a mesh no node references stays
// where it is). Primitives come in file order (mesh by mesh, a mesh's instances within each of
// its primitives); points and lines are left out. Every offset, stride and count is checked
// against the bytes it names before it is read. Throws InputError(path, "mesh", ...).
TriangleMesh readGltf(const std::string& path);

}  // namespace weft
