#include <weft/render/ShapeTessellation.h>

#include <algorithm>
#include <cmath>

namespace weft::render {
namespace {

constexpr float kPi = 3.14159265358979f;

// One ring of a surface of revolution: at `axial` along the axis, `radius` from it, with the
// normal's axial and radial components.
struct Ring {
  float axial, radius, normalAxial, normalRadial;
};

// Revolves a profile (rings in order from the start of the axis to its end) about the axis
// from `base` along `axis` (unit), stitching consecutive rings.
void revolve(LitMesh& mesh, const Vec3f& base, const Vec3f& axis, const std::vector<Ring>& profile,
             int slices) {
  Vec3f e1, e2;
  perpendicularFrame(axis, e1, e2);
  const unsigned first = static_cast<unsigned>(mesh.positions.size());
  for (const Ring& ring : profile) {
    for (int s = 0; s <= slices; ++s) {
      const float phi = 2.0f * kPi * float(s % slices) / float(slices);
      const Vec3f radial = std::cos(phi) * e1 + std::sin(phi) * e2;
      mesh.positions.push_back(base + ring.axial * axis + ring.radius * radial);
      mesh.normals.push_back((ring.normalAxial * axis + ring.normalRadial * radial).normalized());
    }
  }
  const unsigned stride = static_cast<unsigned>(slices + 1);
  for (unsigned r = 0; r + 1 < profile.size(); ++r) {
    for (unsigned s = 0; s < static_cast<unsigned>(slices); ++s) {
      const unsigned i0 = first + r * stride + s, i1 = i0 + 1, j0 = i0 + stride, j1 = j0 + 1;
      // e1 x e2 = axis, so (i0, i1, j1) winds counter-clockwise seen from outside.
      mesh.indices.insert(mesh.indices.end(), {i0, i1, j1, i0, j1, j0});
    }
  }
}

// A hemisphere cap profile from the pole (-1: at the axis start, +1: at the end) to the equator.
std::vector<Ring> capProfile(float radius, float axialCenter, int stacks, bool atStart) {
  std::vector<Ring> rings;
  for (int k = 0; k <= stacks; ++k) {
    const float theta = 0.5f * kPi * float(k) / float(stacks);  // 0 at the pole
    const float axialNormal = (atStart ? -1.0f : 1.0f) * std::cos(theta);
    rings.push_back({axialCenter + radius * axialNormal, radius * std::sin(theta), axialNormal,
                     std::sin(theta)});
  }
  if (!atStart) std::reverse(rings.begin(), rings.end());
  return rings;
}

}  // namespace

void perpendicularFrame(const Vec3f& axis, Vec3f& e1, Vec3f& e2) {
  const Vec3f helper = std::abs(axis.x()) < 0.9f ? Vec3f::UnitX() : Vec3f::UnitY();
  e1 = axis.cross(helper).normalized();
  e2 = axis.cross(e1);
}

void LitMesh::append(const LitMesh& other) {
  const unsigned offset = static_cast<unsigned>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  for (unsigned i : other.indices) indices.push_back(i + offset);
}

std::vector<Vec3f> vertexNormals(const PointMatrix& positions, const TriangleList& triangles) {
  std::vector<Vec3f> normals(static_cast<std::size_t>(positions.rows()), Vec3f::Zero());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const Vec3f pa = positions.row(a), pb = positions.row(b), pc = positions.row(c);
    const Vec3f n = (pb - pa).cross(pc - pa);  // length = twice the area: area weighting
    normals[a] += n, normals[b] += n, normals[c] += n;
  }
  for (Vec3f& n : normals) {
    const float len = n.norm();
    if (len > 0.0f && std::isfinite(len)) n /= len;
  }
  return normals;
}

LitMesh tessellateSphere(const Vec3f& center, float radius, int slices, int stacks) {
  LitMesh mesh;
  std::vector<Ring> profile;
  for (int k = 0; k <= stacks; ++k) {
    const float theta = kPi * float(k) / float(stacks);  // from the -Y pole to the +Y pole
    // Exact poles: sin(pi) in float is not zero, and a hair-thin ring there winds at random.
    const bool pole = k == 0 || k == stacks;
    const float axial = pole ? (k == 0 ? -1.0f : 1.0f) : -std::cos(theta),
                radial = pole ? 0.0f : std::sin(theta);
    profile.push_back({radius * axial, radius * radial, axial, radial});
  }
  revolve(mesh, center, Vec3f::UnitY(), profile, slices);
  return mesh;
}

LitMesh tessellateCapsule(const Vec3f& a, const Vec3f& b, float radius, int slices, int stacks) {
  const Vec3f d = b - a;
  const float length = d.norm();
  const Vec3f axis = length > 0.0f ? Vec3f(d / length) : Vec3f::UnitY();
  std::vector<Ring> profile = capProfile(radius, 0.0f, stacks, true);
  const std::vector<Ring> top = capProfile(radius, length, stacks, false);
  profile.insert(profile.end(), top.begin(), top.end());
  LitMesh mesh;
  revolve(mesh, a, axis, profile, slices);
  return mesh;
}

LitMesh tessellateCylinder(const Vec3f& a, const Vec3f& b, float radius, int slices) {
  const Vec3f d = b - a;
  const float length = d.norm();
  const Vec3f axis = length > 0.0f ? Vec3f(d / length) : Vec3f::UnitY();
  LitMesh mesh;
  // Three separate pieces so the rims stay sharp: bottom cap, side, top cap.
  revolve(mesh, a, axis, {{0.0f, 0.0f, -1.0f, 0.0f}, {0.0f, radius, -1.0f, 0.0f}}, slices);
  revolve(mesh, a, axis, {{0.0f, radius, 0.0f, 1.0f}, {length, radius, 0.0f, 1.0f}}, slices);
  revolve(mesh, a, axis, {{length, radius, 1.0f, 0.0f}, {length, 0.0f, 1.0f, 0.0f}}, slices);
  return mesh;
}

LitMesh tessellateBox(const Vec3f& center, const Vec3f& halfExtents,
                      const Eigen::Matrix3f& rotation) {
  LitMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sign : {-1.0f, 1.0f}) {
      Vec3f n = Vec3f::Zero();
      n[axis] = sign;
      // u x v = n, so the face winds counter-clockwise seen from outside.
      Vec3f u = Vec3f::Zero(), v;
      u[(axis + 1) % 3] = 1.0f;
      v = n.cross(u);
      const unsigned first = static_cast<unsigned>(mesh.positions.size());
      for (auto [su, sv] : {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}}) {
        const Vec3f local = (n + su * u + sv * v).cwiseProduct(halfExtents);
        mesh.positions.push_back(center + rotation * local);
        mesh.normals.push_back(rotation * n);
      }
      mesh.indices.insert(mesh.indices.end(),
                          {first, first + 1, first + 2, first, first + 2, first + 3});
    }
  }
  return mesh;
}

LitMesh tessellatePlane(const Vec3f& point, const Vec3f& normal, const Vec3f& sceneCenter,
                        float halfSize) {
  const Vec3f n = normal.normalized();
  Vec3f e1, e2;
  perpendicularFrame(n, e1, e2);
  const Vec3f c = sceneCenter - (sceneCenter - point).dot(n) * n;
  LitMesh mesh;
  for (auto [s1, s2] : {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}}) {
    mesh.positions.push_back(c + halfSize * (s1 * e1 + s2 * e2));
    mesh.normals.push_back(n);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

LitMesh tessellateMesh(const SurfaceMesh& surface, bool smoothNormals) {
  LitMesh mesh;
  if (smoothNormals) {
    const std::vector<Vec3f> normals = vertexNormals(surface.positions, surface.triangles);
    for (Eigen::Index i = 0; i < surface.positions.rows(); ++i)
      mesh.positions.push_back(surface.positions.row(i));
    mesh.normals = normals;
    for (Eigen::Index t = 0; t < surface.triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k)
        mesh.indices.push_back(static_cast<unsigned>(surface.triangles(t, k)));
    return mesh;
  }
  for (Eigen::Index t = 0; t < surface.triangles.rows(); ++t) {
    const Vec3f a = surface.positions.row(surface.triangles(t, 0)),
                b = surface.positions.row(surface.triangles(t, 1)),
                c = surface.positions.row(surface.triangles(t, 2));
    Vec3f n = (b - a).cross(c - a);
    n = n.norm() > 0.0f ? Vec3f(n.normalized()) : Vec3f::UnitY();
    const unsigned first = static_cast<unsigned>(mesh.positions.size());
    for (const Vec3f& p : {a, b, c}) mesh.positions.push_back(p), mesh.normals.push_back(n);
    mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
  }
  return mesh;
}

LitMesh tessellateObstacle(const ObstacleShape& shape, const Vec3f& sceneCenter,
                           float planeHalfSize) {
  switch (shape.kind) {
    case ObstacleShape::Kind::Plane:
      return tessellatePlane(shape.point, shape.normal, sceneCenter, planeHalfSize);
    case ObstacleShape::Kind::Sphere:
      return tessellateSphere(shape.center, shape.radius);
    case ObstacleShape::Kind::Capsule:
      return tessellateCapsule(shape.a, shape.b, shape.radius);
    case ObstacleShape::Kind::Box:
      return tessellateBox(shape.center, shape.halfExtents, shape.rotation);
    case ObstacleShape::Kind::Cylinder:
      return tessellateCylinder(shape.a, shape.b, shape.radius);
    case ObstacleShape::Kind::Mesh:
      return tessellateMesh(shape.mesh, shape.smoothNormals);
  }
  return {};
}

void appendArrow(LitMesh& mesh, const Vec3f& origin, const Vec3f& vector, float minRadius,
                 int sides) {
  const float length = vector.norm();
  if (!(length > 0.0f) || !std::isfinite(length)) return;
  const Vec3f axis = vector / length;
  const float shaftRadius = std::max(0.025f * length, minRadius);
  const float headRadius = 2.5f * shaftRadius;
  const float headLength = std::min(0.35f * length, 4.0f * headRadius);
  const float shaftLength = length - headLength;
  const float slope = headRadius / headLength;  // the cone's normal leans toward the tip
  // Three open pieces (shaft, underside of the head, cone): the shaft's foot sits on the cloth
  // and needs no cap, and separate pieces keep the rims sharp without degenerate triangles.
  // Arrows come by the thousand, so every triangle counts.
  revolve(mesh, origin, axis,
          {{0.0f, shaftRadius, 0.0f, 1.0f}, {shaftLength, shaftRadius, 0.0f, 1.0f}}, sides);
  revolve(mesh, origin, axis,
          {{shaftLength, shaftRadius, -1.0f, 0.0f}, {shaftLength, headRadius, -1.0f, 0.0f}}, sides);
  revolve(mesh, origin, axis, {{shaftLength, headRadius, slope, 1.0f}, {length, 0.0f, slope, 1.0f}},
          sides);
}

}  // namespace weft::render
