#pragma once
// Triangle meshes with normals for the shapes the renderer draws: obstacles (analytic shapes
// tessellated, mesh obstacles with smooth or flat normals) and force arrows.

#include <weft/render/Bounds.h>
#include <weft/render/RenderScene.h>

#include <vector>

namespace weft::render {

struct LitMesh {
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;     // unit, one per position
  std::vector<unsigned> indices;  // triangles, counter-clockwise seen from outside

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return indices.size() / 3; }
  void append(const LitMesh& other);
};

// Two unit vectors completing the unit `axis` to a right-handed frame (e1 x e2 = axis).
void perpendicularFrame(const Vec3f& axis, Vec3f& e1, Vec3f& e2);

// Area-weighted vertex normals of a triangle mesh (zero rows stay zero: isolated vertices).
std::vector<Vec3f> vertexNormals(const PointMatrix& positions, const TriangleList& triangles);

// An obstacle as triangles. A plane becomes a square of half-size `planeHalfSize` centred
// where `sceneCenter` projects onto it.
LitMesh tessellateObstacle(const ObstacleShape& shape, const Vec3f& sceneCenter,
                           float planeHalfSize);

LitMesh tessellateSphere(const Vec3f& center, float radius, int slices = 48, int stacks = 24);
LitMesh tessellateCapsule(const Vec3f& a, const Vec3f& b, float radius, int slices = 48,
                          int stacks = 12);
LitMesh tessellateCylinder(const Vec3f& a, const Vec3f& b, float radius, int slices = 48);
LitMesh tessellateBox(const Vec3f& center, const Vec3f& halfExtents,
                      const Eigen::Matrix3f& rotation);
LitMesh tessellatePlane(const Vec3f& point, const Vec3f& normal, const Vec3f& sceneCenter,
                        float halfSize);
LitMesh tessellateMesh(const SurfaceMesh& mesh, bool smoothNormals);

// An arrow from `origin` along `vector`: a shaft and a cone head, thickness relative to length
// but at least `minRadius`.
void appendArrow(LitMesh& mesh, const Vec3f& origin, const Vec3f& vector, float minRadius,
                 int sides = 6);

}  // namespace weft::render
