#pragma once
// What one frame shows, as plain data: no physics, no GL. The app builds it from a scene and
// simulated positions; tests build it by hand. Positions are in scene units (m), Y up.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include <cstdint>
#include <optional>
#include <vector>

namespace weft::render {

using Vec3f = Eigen::Vector3f;
using Rgb = Eigen::Vector3f;  // components in [0, 1], written to 8-bit images as they are
using PointMatrix = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;  // n x 3
using TriangleList = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;   // t x 3

// Triangles are counter-clockwise seen from the front side.
struct SurfaceMesh {
  PointMatrix positions;
  TriangleList triangles;
};

enum class ColorMapKind {
  Sequential,  // dark to bright (speed, magnitudes)
  Diverging    // blue, neutral at the middle, red (signed strain)
};

// A per-vertex scalar (strain, speed, |dL/dx|) shown as colour, with a legend bar.
struct ScalarColoring {
  std::vector<float> values;      // one per cloth vertex
  float low = 0.0f, high = 1.0f;  // values mapped to the two ends of the map
  ColorMapKind map = ColorMapKind::Sequential;
};

// The Signorini-Coulomb branch of a contact node (DiffCloth Sec. 4).
enum class ContactBranch : std::uint8_t { None = 0, TakeOff = 1, Stick = 2, Slip = 3 };

struct ContactOverlay {
  std::vector<ContactBranch> branches;  // one per cloth vertex
  std::vector<Vec3f> forces;            // empty, or one per cloth vertex (N); zero draws nothing
  // Arrow length per newton; 0 scales the longest arrow to a tenth of the scene's size.
  float metersPerNewton = 0.0f;
};

struct ObstacleShape {
  enum class Kind { Plane, Sphere, Capsule, Box, Cylinder, Mesh };
  Kind kind = Kind::Sphere;
  Vec3f point = Vec3f::Zero();                             // plane
  Vec3f normal = Vec3f::UnitY();                           // plane (unit)
  Vec3f center = Vec3f::Zero();                            // sphere, box
  float radius = 0.0f;                                     // sphere, capsule, cylinder
  Vec3f a = Vec3f::Zero(), b = Vec3f::Zero();              // capsule, cylinder axis end points
  Vec3f halfExtents = Vec3f::Zero();                       // box
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity();  // box: local to world
  SurfaceMesh mesh;                                        // mesh obstacle
  bool smoothNormals = true;                               // mesh obstacle
};

struct Curve {
  std::vector<Vec3f> points;  // a polyline
  Rgb color{0.15f, 0.55f, 0.25f};
};

// A target shape drawn see-through over the cloth.
struct GhostMesh {
  SurfaceMesh mesh;
  Rgb color{0.55f, 0.25f, 0.75f};
  float opacity = 0.35f;
};

struct RenderScene {
  SurfaceMesh cloth;  // all cloth pieces as one mesh, vertices in scene order
  std::optional<ScalarColoring> scalars;
  std::optional<ContactOverlay> contacts;
  std::vector<ObstacleShape> obstacles;
  std::vector<Vec3f> fixedPoints;  // fixed attachment vertices
  // Per fixed point, its pin group: the index of its fixed attachment among the scene's, cloths
  // in order (pinGroupColor); empty draws every fixed point in the style's fixedPoint colour.
  std::vector<int> fixedPointGroups;
  std::vector<Vec3f> handlePoints;  // moving attachment vertices
  std::vector<Vec3f> targetPoints;  // target vertices (keypoint losses)
  std::vector<Curve> curves;        // handle trajectories
  std::vector<GhostMesh> ghosts;    // target meshes
};

}  // namespace weft::render
