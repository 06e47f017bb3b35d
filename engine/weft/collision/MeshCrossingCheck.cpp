#include <weft/collision/MeshCrossingCheck.h>

#include <weft/collision/EdgeTriangleCrossings.h>

namespace weft::collision {

int MeshCrossingCheck::count(const NodeMatrix& global) const {
  if (mesh_.empty()) return 0;
  mesh_.gather(global, local_);
  return findEdgeTriangleCrossings(mesh_.mesh, local_).count();
}

}  // namespace weft::collision
