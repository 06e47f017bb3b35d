#pragma once
#include <weft/mesh/TriangleMesh.h>

#include <string>
#include <vector>

namespace weft {

// Writes a mesh as OBJ (1-based indices, full double precision). `groupStarts` optionally
// splits the triangles into named objects (`o name`), e.g. one per cloth piece.
void writeObj(const std::string& path, const TriangleMesh& mesh,
              const std::vector<std::pair<std::string, int>>& groupStarts = {});

}  // namespace weft
