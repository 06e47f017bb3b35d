#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>

namespace weft {

// Reads a mesh file through assimp (FBX, Collada, STL, 3DS, ...): every mesh placed by the node
// transforms that reference it, polygons fan-triangulated, vertex order and count the file's.
// `joinCorners` (for FBX, whose corners assimp unrolls) joins corners at one position again, in
// order of first use. assimp runs in a child
// process (ChildProcess.h): Debian's assimp 5.2 crashes on some malformed FBX files
// (docs/hardening.md), and a crash, a hang past kAssimpTimeoutSeconds or an allocation past
// kAssimpMemoryLimitBytes there becomes an InputError(path, "mesh", ...) here.
TriangleMesh readWithAssimp(const std::string& path, bool joinCorners);

inline constexpr double kAssimpTimeoutSeconds = 120.0;
inline constexpr long long kAssimpMemoryLimitBytes = 8LL << 30;

}  // namespace weft
