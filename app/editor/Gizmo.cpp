#include "Gizmo.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace weft::editor {
namespace {

constexpr float kPi = 3.14159265358979f;

const char* const kNames[] = {"translate_x", "translate_y", "translate_z",
                              "rotate_x",    "rotate_y",    "rotate_z"};

// Squared distance between a ray (t >= 0) and a segment, and the ray parameter of the closest
// point. The infinite lines' closest points, clamped to the segment and then to the ray: exact
// unless both clamps bind, and then off by less than the pick radius matters.
float raySegmentDistance2(const Ray& ray, const Eigen::Vector3f& p, const Eigen::Vector3f& q,
                          float& t) {
  const Eigen::Vector3f v = q - p, w = ray.origin - p;
  const float b = ray.direction.dot(v), c = v.dot(v), d = ray.direction.dot(w), e = v.dot(w);
  const float denominator = c - b * b;  // |direction| = 1
  float s = denominator > 1e-12f * c ? (e - b * d) / denominator : 0.0f;
  s = std::clamp(s, 0.0f, 1.0f);
  t = std::max(0.0f, (p + s * v - ray.origin).dot(ray.direction));
  if (c > 0.0f) s = std::clamp((ray.origin + t * ray.direction - p).dot(v) / c, 0.0f, 1.0f);
  return (ray.origin + t * ray.direction - (p + s * v)).squaredNorm();
}

}  // namespace

const char* gizmoHandleName(GizmoHandle handle) {
  return handle == GizmoHandle::None ? "none" : kNames[static_cast<int>(handle)];
}

bool parseGizmoHandle(const std::string& text, GizmoHandle& handle) {
  for (int i = 0; i < 6; ++i)
    if (text == kNames[i]) {
      handle = static_cast<GizmoHandle>(i);
      return true;
    }
  return false;
}

Gizmo::Gizmo(const Eigen::Vector3f& origin, bool rotates, const render::Camera& camera, int width,
             int height)
    : origin_(origin),
      rotates_(rotates),
      camera_(camera),
      width_(std::max(width, 1)),
      height_(std::max(height, 1)) {
  if (camera.orthographic) {
    metresPerPixel_ = 2.0f * camera.orthoHalfHeight / float(height_);
  } else {
    const float depth = std::max((origin - camera.eye()).dot(-camera.backward()), camera.nearPlane);
    metresPerPixel_ = 2.0f * depth * std::tan(camera.fovYDeg * kPi / 360.0f) / float(height_);
  }
}

std::vector<Eigen::Vector3f> Gizmo::polyline(GizmoHandle handle) const {
  if (!has(handle)) return {};
  const Eigen::Vector3f axis = Eigen::Vector3f::Unit(gizmoAxis(handle));
  if (!isRotation(handle)) {
    const float length = kArrowPixels * metresPerPixel_;
    return {origin_ + kArrowStart * length * axis, origin_ + length * axis};
  }
  // The ring lies in the plane of the other two axes.
  const Eigen::Vector3f e1 = Eigen::Vector3f::Unit((gizmoAxis(handle) + 1) % 3);
  const Eigen::Vector3f e2 = Eigen::Vector3f::Unit((gizmoAxis(handle) + 2) % 3);
  const float radius = kRingPixels * metresPerPixel_;
  std::vector<Eigen::Vector3f> ring;
  for (int k = 0; k <= kRingSegments; ++k) {
    const float angle = 2.0f * kPi * float(k % kRingSegments) / float(kRingSegments);
    ring.push_back(origin_ + radius * (std::cos(angle) * e1 + std::sin(angle) * e2));
  }
  return ring;
}

std::vector<Eigen::Vector2f> Gizmo::screenPolyline(GizmoHandle handle) const {
  std::vector<Eigen::Vector2f> pixels;
  for (const Eigen::Vector3f& p : polyline(handle))
    if (const auto pixel = projectToPixel(camera_, p, width_, height_)) pixels.push_back(*pixel);
  return pixels;
}

GizmoHandle Gizmo::pick(const Ray& ray) const {
  const float radius2 = std::pow(kPickPixels * metresPerPixel_, 2.0f);
  // Arrows before rings: a ring seen edge-on is a line across the whole gizmo, in front of the
  // arrows for half its length, and would take every press near an arrow.
  for (const bool rings : {false, true}) {
    GizmoHandle best = GizmoHandle::None;
    float bestT = std::numeric_limits<float>::infinity();
    for (int h = rings ? 3 : 0; h < (rings ? 6 : 3); ++h) {
      const GizmoHandle handle = static_cast<GizmoHandle>(h);
      const std::vector<Eigen::Vector3f> line = polyline(handle);
      for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        float t = 0.0f;
        if (raySegmentDistance2(ray, line[i], line[i + 1], t) <= radius2 && t < bestT)
          bestT = t, best = handle;
      }
    }
    if (best != GizmoHandle::None) return best;
  }
  return GizmoHandle::None;
}

GizmoHandle Gizmo::pickPixel(float x, float y) const {
  return pick(pixelRay(camera_, x, y, width_, height_));
}

std::optional<Eigen::Vector2f> Gizmo::grabPixel(GizmoHandle handle) const {
  if (!has(handle)) return std::nullopt;
  std::vector<Eigen::Vector2f> candidates;
  if (!isRotation(handle)) {
    const std::vector<Eigen::Vector3f> shaft = polyline(handle);
    const auto p = projectToPixel(camera_, origin_ + 0.75f * (shaft[1] - origin_), width_, height_);
    if (p) candidates.push_back(*p);
  } else {
    // The ring's points from the farthest from the centre on screen (where it is seen face-on
    // and clear of the arrows) inwards.
    const auto centre = projectToPixel(camera_, origin_, width_, height_);
    if (!centre) return std::nullopt;
    candidates = screenPolyline(handle);
    std::stable_sort(candidates.begin(), candidates.end(),
                     [&](const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
                       return (a - *centre).squaredNorm() > (b - *centre).squaredNorm();
                     });
  }
  for (const Eigen::Vector2f& p : candidates)
    if (p.x() >= 0 && p.y() >= 0 && p.x() < float(width_) && p.y() < float(height_) &&
        pickPixel(p.x(), p.y()) == handle)
      return p;
  return std::nullopt;
}

std::optional<GizmoDrag> GizmoDrag::begin(const Gizmo& gizmo, GizmoHandle handle,
                                          const Eigen::Vector2f& pixel) {
  if (!gizmo.has(handle)) return std::nullopt;
  const auto centre = projectToPixel(gizmo.camera(), gizmo.origin(), gizmo.width(), gizmo.height());
  if (!centre) return std::nullopt;
  GizmoDrag drag;
  drag.handle_ = handle;
  drag.start_ = drag.previous_ = pixel;
  drag.centre_ = *centre;
  const Eigen::Vector3f axis = Eigen::Vector3f::Unit(gizmoAxis(handle));
  if (!isRotation(handle)) {
    // The axis's image over one arrow length, per metre: linear in the mouse motion, as a
    // drag along a line on screen should be (perspective makes the true mapping nonlinear).
    const float length = Gizmo::kArrowPixels * gizmo.metresPerPixel();
    const auto tip = projectToPixel(gizmo.camera(), gizmo.origin() + length * axis, gizmo.width(),
                                    gizmo.height());
    if (!tip || (*tip - *centre).norm() < 2.0f)
      return std::nullopt;  // the arrow points at the camera
    drag.pixelsPerMetre_ = (*tip - *centre) / length;
  } else {
    if ((pixel - *centre).norm() < 1.0f) return std::nullopt;  // no angle about the centre itself
    drag.sign_ = (gizmo.camera().eye() - gizmo.origin()).dot(axis) >= 0.0f ? 1.0f : -1.0f;
  }
  return drag;
}

double GizmoDrag::update(const Eigen::Vector2f& pixel) {
  if (!isRotation(handle_)) {
    amount_ = double((pixel - start_).dot(pixelsPerMetre_)) / double(pixelsPerMetre_.squaredNorm());
    return amount_;
  }
  const Eigen::Vector2f from = previous_ - centre_, to = pixel - centre_;
  if (to.norm() < 1.0f) return amount_;  // too close to the centre to have a direction: wait
  // Pixels are y-down, so a positive cross product is a clockwise turn on screen; a rotation
  // about an axis pointing at the viewer turns counter-clockwise.
  const double swept = std::atan2(double(from.x()) * to.y() - double(from.y()) * to.x(),
                                  double(from.x()) * to.x() + double(from.y()) * to.y());
  amount_ -= double(sign_) * swept;
  previous_ = pixel;
  return amount_;
}

Eigen::Vector3d eulerXyzDegrees(const Eigen::Matrix3d& r, const Eigen::Vector3d& near) {
  const double toDegrees = 180.0 / M_PI;
  const double cosY = std::hypot(r(0, 0), r(1, 0));
  Eigen::Vector3d first, second;
  if (cosY > 1e-12) {
    first = Eigen::Vector3d(std::atan2(r(2, 1), r(2, 2)), std::atan2(-r(2, 0), cosY),
                            std::atan2(r(1, 0), r(0, 0))) *
            toDegrees;
    // The same rotation with the Y angle past +-90: (x + 180, 180 - y, z + 180).
    second = Eigen::Vector3d(first.x() + 180.0, 180.0 - first.y(), first.z() + 180.0);
  } else {
    // R = Ry(+-90) Rx(x) with z = 0: its second row is (0, cos x, -sin x).
    first = second =
        Eigen::Vector3d(std::atan2(-r(1, 2), r(1, 1)), std::atan2(-r(2, 0), cosY), 0.0) * toDegrees;
  }
  // Each angle moved by whole turns to lie nearest `near`, then the nearer of the two triples:
  // a drag turns the numbers continuously instead of flipping them at 90 or 180 degrees.
  auto wrapNear = [&](Eigen::Vector3d a) {
    for (int i = 0; i < 3; ++i) a[i] -= 360.0 * std::round((a[i] - near[i]) / 360.0);
    return a;
  };
  first = wrapNear(first);
  second = wrapNear(second);
  return (second - near).squaredNorm() < (first - near).squaredNorm() ? second : first;
}

}  // namespace weft::editor
