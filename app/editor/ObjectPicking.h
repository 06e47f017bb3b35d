#pragma once
// Choosing what the gizmo places by clicking it in the viewport (Ctrl+click; a plain click picks
// a cloth vertex, Selection.h): the ray through the pixel against every obstacle and every cloth,
// the nearest hit wins. An obstacle is traced on the engine's own signed distance (the surface
// contact sees, weft::ObstacleShape) placed by its motion at the time shown, so every shape the
// scene can hold is picked by the same code, mesh obstacles included; a cloth by its triangles as
// drawn. No GL, no window: unit tested.

#include "Placement.h"
#include "Selection.h"

#include <weft/contact/ContactObstacle.h>
#include <weft/render/RenderScene.h>
#include <weft/scene/Scene.h>

#include <optional>

namespace weft::editor {

// The distance along `ray` to where it first meets `shape`, whose body frame `pose` places in the
// world, found by sphere tracing: each step advances by the distance to the surface, which can
// never step through it. nullopt when the ray does not meet it within `maxDistance` metres (or
// only grazes it, taking more steps than a click is worth).
std::optional<double> traceShape(const ObstacleShape& shape, const RigidPose& pose, const Ray& ray,
                                 double maxDistance);

// The square a plane is drawn as (render::planeHalfSize): centred on `centre` projected onto the
// plane, sides along render::perpendicularFrame of its normal. A plane is infinite to contact,
// but a click beside its drawn square is on the background.
struct DrawnPlaneExtent {
  Vec3 centre = Vec3::Zero();
  double halfSize = 0.0;
};

struct ObjectHit {
  EditorObject object;    // an obstacle or a cloth
  double distance = 0.0;  // along the ray, m
};

// The object `ray` meets first within `maxDistance`: an obstacle of `scene` at time `time` (s; its
// motion's pose then), or a cloth of `cloth`, the cloths drawn as one mesh in scene order
// (RenderScene::cloth). Cloths are skipped when `cloth` does not have the scene's vertex count.
// nullopt when it meets nothing.
// With `planes`, a plane counts only inside its drawn square.
std::optional<ObjectHit> pickObject(const Scene& scene, double time,
                                    const render::SurfaceMesh& cloth, const Ray& ray,
                                    double maxDistance,
                                    const std::optional<DrawnPlaneExtent>& planes = std::nullopt);

}  // namespace weft::editor
