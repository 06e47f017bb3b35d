#include <weft/render/Camera.h>

#include <algorithm>
#include <cmath>

namespace weft::render {
namespace {

constexpr float kPi = 3.14159265358979f;
float radians(float degrees) {
  return degrees * kPi / 180.0f;
}

}  // namespace

bool parseNamedView(const std::string& text, NamedView& view) {
  if (text == "front")
    view = NamedView::Front;
  else if (text == "side")
    view = NamedView::Side;
  else if (text == "top")
    view = NamedView::Top;
  else if (text == "auto")
    view = NamedView::Auto;
  else
    return false;
  return true;
}

Vec3f Camera::backward() const {
  const float y = radians(yawDeg), p = radians(pitchDeg);
  return Vec3f(std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y));
}

// The derivative of backward() in pitch: never parallel to it, so the top view is well defined.
Vec3f Camera::up() const {
  const float y = radians(yawDeg), p = radians(pitchDeg);
  return Vec3f(-std::sin(p) * std::sin(y), std::cos(p), -std::sin(p) * std::cos(y));
}

Vec3f Camera::right() const {
  return up().cross(backward());
}

Vec3f Camera::eye() const {
  return target + distance * backward();
}

Eigen::Matrix4f Camera::view() const {
  const Vec3f r = right(), u = up(), b = backward(), e = eye();
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = b.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = -b.dot(e);
  return m;
}

Eigen::Matrix4f Camera::projection(float aspect) const {
  const float n = nearPlane, f = farPlane;
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  if (orthographic) {
    const float h = orthoHalfHeight, w = h * aspect;
    m(0, 0) = 1.0f / w;
    m(1, 1) = 1.0f / h;
    m(2, 2) = -2.0f / (f - n);
    m(2, 3) = -(f + n) / (f - n);
    m(3, 3) = 1.0f;
  } else {
    const float t = 1.0f / std::tan(0.5f * radians(fovYDeg));
    m(0, 0) = t / aspect;
    m(1, 1) = t;
    m(2, 2) = -(f + n) / (f - n);
    m(2, 3) = -2.0f * f * n / (f - n);
    m(3, 2) = -1.0f;
  }
  return m;
}

void Camera::orbit(float yawDegrees, float pitchDegrees) {
  yawDeg = std::fmod(yawDeg + yawDegrees, 360.0f);
  pitchDeg = std::clamp(pitchDeg + pitchDegrees, -89.0f, 89.0f);
}

void Camera::zoom(float factor) {
  distance = std::max(distance * factor, 1e-4f);
  orthoHalfHeight = std::max(orthoHalfHeight * factor, 1e-5f);
}

void Camera::pan(float rightAmount, float upAmount) {
  target += rightAmount * right() + upAmount * up();
}

void frameBounds(Camera& camera, const Bounds& bounds, float aspect, float margin) {
  const Bounds b = bounds.empty() ? Bounds{Vec3f::Constant(-0.5f), Vec3f::Constant(0.5f)} : bounds;
  camera.target = b.center();
  const Vec3f r = camera.right(), u = camera.up(), k = camera.backward();
  const float tanY = std::tan(0.5f * radians(camera.fovYDeg)), tanX = tanY * aspect;
  float distance = 0.0f, halfHeight = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3f p((corner & 1) ? b.max.x() : b.min.x(), (corner & 2) ? b.max.y() : b.min.y(),
                  (corner & 4) ? b.max.z() : b.min.z());
    const Vec3f q = p - camera.target;
    const float x = std::abs(q.dot(r)) * margin, y = std::abs(q.dot(u)) * margin, z = q.dot(k);
    // A corner at depth (distance - z) is inside the frustum when |x| <= (distance - z) tanX.
    distance = std::max({distance, z + x / tanX, z + y / tanY});
    halfHeight = std::max({halfHeight, y, x / aspect});
  }
  const float radius = b.radius();
  camera.distance = std::max(distance, 1e-3f);
  camera.orthoHalfHeight = std::max(halfHeight, 1e-4f);
  // Room behind the scene for the ground, which extends a few radii around it.
  camera.nearPlane = std::max(camera.distance - 4.0f * radius, camera.distance * 0.02f);
  camera.farPlane = camera.distance + 4.0f * radius;
}

Camera namedViewCamera(NamedView view, const Bounds& bounds, float aspect) {
  Camera c;
  switch (view) {
    case NamedView::Front:
      c.yawDeg = 0.0f, c.pitchDeg = 0.0f;
      break;
    case NamedView::Side:
      c.yawDeg = 90.0f, c.pitchDeg = 0.0f;
      break;
    case NamedView::Top:
      c.yawDeg = 0.0f, c.pitchDeg = 90.0f;
      break;
    case NamedView::Auto:
      c.yawDeg = 35.0f, c.pitchDeg = 25.0f;
      break;
  }
  frameBounds(c, bounds, aspect);
  return c;
}

}  // namespace weft::render
