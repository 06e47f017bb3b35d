#include <weft/scene/Scene.h>

namespace weft {

int Scene::vertexCount() const {
  int n = 0;
  for (const Cloth& c : cloths) n += c.mesh.vertexCount();
  return n;
}

bool Scene::hasSelfCollision() const {
  for (const Cloth& c : cloths)
    if (c.selfCollision) return true;
  return false;
}

}  // namespace weft
