#include "ObjectPlacement.h"

#include "ObjectPicking.h"

#include <weft/render/Bounds.h>
#include <weft/scene/JsonPath.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace weft::editor {
namespace {

// The entry at `path` of a document copy being edited; throws when it is gone (an undo during a
// drag can take it away), which the document turns into the edit's error text.
nlohmann::json& entryAt(nlohmann::json& document, const std::string& path) {
  nlohmann::json* entry = findJsonPath(document, path);
  if (!entry) throw std::runtime_error(path + " is no longer in the scene");
  return *entry;
}

}  // namespace

ObjectPlacement::ObjectPlacement(EditorDocument& document, Timeline& timeline,
                                 const render::Camera& camera, ViewportFrame& viewport,
                                 const SimulationCache& cache)
    : document_(document),
      timeline_(timeline),
      camera_(camera),
      viewport_(viewport),
      cache_(cache) {}

void ObjectPlacement::reset() {
  active_ = EditorObject();
  drag_.reset();
  pending_.reset();
}

std::string ObjectPlacement::clickObject(float x, float y, int width, int height) {
  const render::RenderScene* frame = viewport_.scene();
  // The scene the picture comes from, at the time of the state it shows.
  const std::shared_ptr<const Scene> shown = viewport_.shownScene();
  if (!frame || !shown) return "there is nothing in the viewport to pick";
  double time = 0.0;
  if (viewport_.showingCache())
    if (const auto f =
            cache_.frame(std::min(timeline_.playback().frame(), cache_.frameCount() - 1)))
      time = f->state * shown->time.dt;
  // Planes count where they are drawn (the renderer's square around the rest of the frame).
  const render::Bounds bounds = render::sceneBounds(*frame);
  const DrawnPlaneExtent planes{
      bounds.empty() ? Vec3(camera_.target.cast<double>()) : Vec3(bounds.center().cast<double>()),
      double(render::planeHalfSize(bounds))};
  const auto hit = pickObject(*shown, time, frame->cloth, pixelRay(camera_, x, y, width, height),
                              camera_.farPlane, planes);
  return setActiveObject(hit ? hit->object.path() : "");
}

std::string ObjectPlacement::setActiveObject(const std::string& path) {
  EditorObject object;
  const std::string error = findEditorObject(document_.document(), path, object);
  if (!error.empty()) return error;
  if (object != active_) endGizmoDrag();
  active_ = object;
  return "";
}

void ObjectPlacement::dropStaleActiveObject() {
  // An undo or a removal can take the active object away (or turn a handle into a fixed pin).
  EditorObject still;
  if (active_.kind != EditorObject::Kind::None &&
      !findEditorObject(document_.document(), active_.path(), still).empty()) {
    active_ = EditorObject();
    drag_.reset();
  }
}

std::optional<Vec3> ObjectPlacement::objectOrigin() const {
  const Scene* scene = document_.scene();
  if (!scene) return std::nullopt;
  auto boundsCentre = [](const NodeMatrix& v) -> std::optional<Vec3> {
    if (v.rows() == 0) return std::nullopt;
    return Vec3(0.5 * (v.colwise().minCoeff() + v.colwise().maxCoeff()).transpose());
  };
  switch (active_.kind) {
    case EditorObject::Kind::None:
      return std::nullopt;
    case EditorObject::Kind::Obstacle: {
      if (active_.index >= int(scene->obstacles.size())) return std::nullopt;
      const Obstacle& o = scene->obstacles[std::size_t(active_.index)];
      switch (o.shape) {
        case Obstacle::Shape::Plane:
          return o.point;
        case Obstacle::Shape::Sphere:
        case Obstacle::Shape::Box:
          return o.center;
        case Obstacle::Shape::Capsule:
        case Obstacle::Shape::Cylinder:
          return Vec3(0.5 * (o.a + o.b));
        case Obstacle::Shape::Mesh:
          return boundsCentre(o.mesh.vertices);
      }
      return std::nullopt;
    }
    case EditorObject::Kind::Cloth:
      if (active_.index >= int(scene->cloths.size())) return std::nullopt;
      return boundsCentre(scene->cloths[std::size_t(active_.index)].mesh.vertices);
    case EditorObject::Kind::Handle: {
      if (active_.index >= int(scene->cloths.size())) return std::nullopt;
      const Cloth& cloth = scene->cloths[std::size_t(active_.index)];
      if (active_.attachment >= int(cloth.attachments.size())) return std::nullopt;
      const Attachment& a = cloth.attachments[std::size_t(active_.attachment)];
      if (a.vertices.empty()) return std::nullopt;
      Vec3 centroid = Vec3::Zero();
      for (int v : a.vertices) centroid += cloth.mesh.vertices.row(v).transpose();
      centroid /= double(a.vertices.size());
      // Where the trajectory puts the centroid now, with the offset being edited in place of its
      // own.
      const double t = timeline_.time();
      const auto offset = handleOffset();
      return Vec3(a.trajectory.target(centroid, t) - a.trajectory.offset(t) +
                  offset.value_or(a.trajectory.offset(t)));
    }
  }
  return std::nullopt;
}

RigidPose ObjectPlacement::shownPose() const {
  const Scene* scene = document_.scene();
  if (!scene || active_.kind != EditorObject::Kind::Obstacle ||
      active_.index >= int(scene->obstacles.size()))
    return RigidPose();
  const Obstacle& o = scene->obstacles[std::size_t(active_.index)];
  return o.motion ? poseAt(*o.motion, timeline_.time()) : RigidPose();
}

std::optional<Gizmo> ObjectPlacement::gizmo(int width, int height) const {
  const auto origin = objectOrigin();
  if (!origin || !origin->allFinite()) return std::nullopt;
  // A moving obstacle's gizmo sits on the obstacle as the viewport shows it at this time.
  const Vec3 shown = shownPose().apply(*origin);
  return Gizmo(shown.cast<float>(), objectRotates(document_.document(), active_), camera_, width,
               height);
}

GizmoHandle ObjectPlacement::pickGizmo(float x, float y, int width, int height) const {
  const auto g = gizmo(width, height);
  return g ? g->pickPixel(x, y) : GizmoHandle::None;
}

std::string ObjectPlacement::beginGizmoDrag(GizmoHandle handle, float x, float y, int width,
                                            int height) {
  endGizmoDrag();
  const auto g = gizmo(width, height);
  if (!g) {
    if (active_.kind == EditorObject::Kind::None)
      return "nothing to move: choose an obstacle, a cloth or a handle first";
    return "the scene does not validate: " + document_.validationError();
  }
  if (!g->has(handle))
    return std::string("this object has no ") + gizmoHandleName(handle) + " handle";
  if (active_.kind == EditorObject::Kind::Handle && !handleError().empty()) return handleError();
  auto drag = GizmoDrag::begin(*g, handle, Eigen::Vector2f(x, y));
  if (!drag)
    return isRotation(handle) ? "press on the ring, away from the gizmo's centre"
                              : "this axis points at the camera: turn the view to drag along it";
  const char* axes = "XYZ";
  DragState state{*drag, active_, nlohmann::json(), Vec3(g->origin().cast<double>()), Vec3::Zero(),
                  "",    ""};
  if (active_.kind == EditorObject::Kind::Handle) {
    state.startOffset = handleOffset().value_or(Vec3::Zero());
  } else {
    const nlohmann::json* entry = document_.find(active_.path());
    if (!entry) return active_.path() + " is no longer in the scene";
    state.start = *entry;
    // The exact centre from the scene, not the gizmo's single-precision copy.
    state.centre = objectOrigin().value_or(state.centre);
  }
  state.label = std::string(isRotation(handle) ? "Turn " : "Move ") + active_.path() +
                (isRotation(handle) ? " about " : " along ") + axes[gizmoAxis(handle)];
  state.coalesceKey = "gizmo drag " + std::to_string(++dragCount_);
  drag_ = std::move(state);
  return "";
}

std::string ObjectPlacement::dragGizmo(float x, float y) {
  if (!drag_) return "no gizmo drag in progress";
  if (drag_->object != active_) {
    drag_.reset();
    return "the object being moved has gone";
  }
  const double amount = drag_->drag.update(Eigen::Vector2f(x, y));
  const GizmoHandle handle = drag_->drag.handle();
  const int axis = gizmoAxis(handle);
  if (active_.kind == EditorObject::Kind::Handle) {
    Vec3 offset = drag_->startOffset;
    offset[axis] += amount;
    pending_ = PendingOffset{active_, timeline_.playback().frame(), offset};
    return "";
  }
  nlohmann::json entry = drag_->start;
  // A moving obstacle is dragged where it is shown; the scene holds its rest pose, which the
  // motion turns by R: a world move d is R^T d at rest. A turn about a world axis is one about a
  // rest axis only while R is the identity.
  const Mat3 shownRotation = shownPose().rotation;
  const bool turned = !shownRotation.isApprox(Mat3::Identity(), 1e-12);
  if (turned && isRotation(handle))
    return active_.path() +
           ": its motion has turned it at this time; turn it at a time where it is not turned "
           "(e.g. frame 0)";
  try {
    if (isRotation(handle)) {
      rotateObject(entry, active_.kind, axis, amount, drag_->centre);
    } else if (!turned) {
      translateObject(entry, active_.kind, axis, amount);
    } else {
      const Vec3 atRest = shownRotation.transpose() * (amount * Vec3::Unit(axis));
      for (int k = 0; k < 3; ++k)
        if (atRest[k] != 0.0) translateObject(entry, active_.kind, k, atRest[k]);
    }
  } catch (const std::exception& e) {
    return active_.path() + ": " + e.what();
  }
  const std::string path = active_.path();
  // One undo step per drag: every move of the same drag merges into the step it started.
  return document_.editWithSidecar(
      drag_->label, [&](nlohmann::json& doc, nlohmann::json&) { entryAt(doc, path) = entry; },
      drag_->coalesceKey);
}

void ObjectPlacement::endGizmoDrag() {
  drag_.reset();
}

std::string ObjectPlacement::handleError() const {
  if (active_.kind != EditorObject::Kind::Handle)
    return "choose a handle first (make one from a selection)";
  if (!document_.valid()) return "the scene does not validate: " + document_.validationError();
  const nlohmann::json* attachment = document_.find(active_.path());
  if (!attachment || !hasKeyframes(*attachment))
    return "this handle follows a Hermite spline: edit its knots and tangents in the scene file";
  return "";
}

std::vector<HandleKey> ObjectPlacement::keys() const {
  if (active_.kind != EditorObject::Kind::Handle) return {};
  const nlohmann::json* attachment = document_.find(active_.path());
  return attachment ? handleKeys(*attachment) : std::vector<HandleKey>{};
}

std::optional<Vec3> ObjectPlacement::handleOffset() const {
  if (active_.kind != EditorObject::Kind::Handle) return std::nullopt;
  if (handleOffsetPending()) return pending_->offset;
  const Scene* scene = document_.scene();
  if (!scene || active_.index >= int(scene->cloths.size())) return std::nullopt;
  const Cloth& cloth = scene->cloths[std::size_t(active_.index)];
  if (active_.attachment >= int(cloth.attachments.size())) return std::nullopt;
  return cloth.attachments[std::size_t(active_.attachment)].trajectory.offset(timeline_.time());
}

bool ObjectPlacement::handleOffsetPending() const {
  return pending_ && active_.kind == EditorObject::Kind::Handle && pending_->object == active_ &&
         pending_->frame == timeline_.playback().frame();
}

std::string ObjectPlacement::setHandleOffset(const Vec3& offset) {
  const std::string error = handleError();
  if (!error.empty()) return error;
  if (!offset.allFinite()) return "the offset must be finite";
  pending_ = PendingOffset{active_, timeline_.playback().frame(), offset};
  return "";
}

std::string ObjectPlacement::setKey() {
  std::string error = handleError();
  if (!error.empty()) return error;
  const auto offset = handleOffset();
  if (!offset) return "the handle has no offset here";
  const double t = timeline_.time();
  const double dt = document_.scene()->time.dt;
  const std::string path = active_.path();
  char label[64];
  std::snprintf(label, sizeof label, "Set key at t = %.4g s", t);
  error = document_.edit(
      label, [&](nlohmann::json& doc) { setHandleKey(entryAt(doc, path), t, *offset, 0.5 * dt); });
  if (error.empty()) pending_.reset();
  return error;
}

std::string ObjectPlacement::deleteKey() {
  std::string error = handleError();
  if (!error.empty()) return error;
  const double t = timeline_.time();
  const double dt = document_.scene()->time.dt;
  const std::vector<HandleKey> list = keys();
  bool here = false;
  for (const HandleKey& k : list) here = here || std::abs(k.time - t) < 0.5 * dt;
  if (!here) return "there is no key at this frame";
  if (list.size() == 1) return "a handle needs at least one key: remove the attachment instead";
  const std::string path = active_.path();
  char label[64];
  std::snprintf(label, sizeof label, "Delete key at t = %.4g s", t);
  error = document_.edit(
      label, [&](nlohmann::json& doc) { deleteHandleKey(entryAt(doc, path), t, 0.5 * dt); });
  if (error.empty()) pending_.reset();
  return error;
}

std::string ObjectPlacement::jumpToKey(int direction) {
  const Scene* scene = timeline_.scene();
  if (active_.kind != EditorObject::Kind::Handle || !scene) return "choose a handle first";
  const int frame = timeline_.playback().frame();
  int best = -1;
  for (const HandleKey& k : keys()) {
    const int f = int(std::llround(k.time / scene->time.dt));
    if (direction > 0 ? f > frame && (best < 0 || f < best)
                      : f < frame && f >= 0 && (best < 0 || f > best))
      best = f;
  }
  if (best < 0) return direction > 0 ? "no key after this frame" : "no key before this frame";
  timeline_.playback().scrub(best, timeline_.frames());
  timeline_.playback().pause();
  return "";
}

}  // namespace weft::editor
