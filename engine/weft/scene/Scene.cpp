#include <weft/scene/Scene.h>

namespace weft {

int Scene::vertexCount() const {
  int n = 0;
  for (const Cloth& c : cloths) n += c.mesh.vertexCount();
  return n;
}

bool Scene::hasSelfCollision() const {
  for (const Cloth& c : cloths)
    if (c.selfCollision && c.selfCollision->nodeModel) return true;
  return false;
}

bool Scene::hasImpactZones() const {
  for (const Cloth& c : cloths)
    if (c.selfCollision && c.selfCollision->impactZones) return true;
  return false;
}

}  // namespace weft
