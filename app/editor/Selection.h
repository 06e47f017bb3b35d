#pragma once
// Vertex selection in the viewport, as plain geometry: a ray through a pixel of the orbit
// camera, the nearest cloth triangle it hits and that triangle's vertex closest to the hit
// (click), and the vertices whose projection falls inside a screen rectangle (box). Also turns
// a selection of global nodes into per-cloth fixed attachments in the scene document.
// No GL, no window: unit tested.

#include <weft/render/Camera.h>
#include <weft/render/RenderScene.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

struct Ray {
  Eigen::Vector3f origin, direction;  // direction is unit length
};

// The ray through pixel (x, y) of a width x height image (x right, y down, pixel centres at
// +0.5) seen through `camera`.
Ray pixelRay(const render::Camera& camera, float x, float y, int width, int height);

// Where world point p lands in the image (x right, y down); nullopt behind the camera.
std::optional<Eigen::Vector2f> projectToPixel(const render::Camera& camera,
                                              const Eigen::Vector3f& p, int width, int height);

// The nearest triangle a ray hits (from either side) and the distance along the ray to the hit.
struct TriangleHit {
  int triangle = -1;
  float distance = 0.0f;
};
std::optional<TriangleHit> nearestTriangleHit(const render::SurfaceMesh& mesh, const Ray& ray);

// The vertex picked by a click: of the nearest triangle the ray hits, the corner closest to the
// hit point. nullopt when the ray misses the mesh.
std::optional<int> pickVertex(const render::SurfaceMesh& mesh, const Ray& ray);

// Vertices whose projection lies in the rectangle spanned by two corners (any order). Hidden
// vertices are included: the box selects through the cloth.
std::vector<int> boxSelect(const render::SurfaceMesh& mesh, const render::Camera& camera,
                           Eigen::Vector2f corner0, Eigen::Vector2f corner1, int width, int height);

// A sorted, duplicate-free set of global node indices, and the one vertex the inspector shows
// (the focus): the vertex last clicked, or the first one named by the last selecting call.
class Selection {
 public:
  const std::vector<int>& nodes() const { return nodes_; }
  bool empty() const { return nodes_.empty(); }
  bool contains(int node) const;
  void clear() { nodes_.clear(), focus_ = -1; }
  void set(std::vector<int> nodes);
  void add(const std::vector<int>& nodes);
  void toggle(int node);
  // The inspected vertex, or -1; always one of nodes().
  int focus() const { return focus_; }

 private:
  std::vector<int> nodes_;
  int focus_ = -1;
};

// Adds one fixed attachment per cloth touched by `nodes` (global indices; `vertexOffset` as in
// ClothModel, size cloths + 1) to `document`, with cloth-local vertex indices. Throws
// std::invalid_argument for a node out of range.
void addFixedAttachments(nlohmann::json& document, const std::vector<int>& nodes,
                         const std::vector<int>& vertexOffset);

}  // namespace weft::editor
