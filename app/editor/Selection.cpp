#include "Selection.h"

#include "ClothNodes.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace weft::editor {

Ray pixelRay(const render::Camera& camera, float x, float y, int width, int height) {
  const float aspect = float(width) / float(std::max(height, 1));
  const Eigen::Matrix4f inverse = (camera.projection(aspect) * camera.view()).inverse();
  const float ndcX = 2.0f * x / float(width) - 1.0f;
  const float ndcY = 1.0f - 2.0f * y / float(height);
  auto unproject = [&](float z) {
    const Eigen::Vector4f p = inverse * Eigen::Vector4f(ndcX, ndcY, z, 1.0f);
    return Eigen::Vector3f(p.head<3>() / p.w());
  };
  const Eigen::Vector3f nearPoint = unproject(-1.0f), farPoint = unproject(1.0f);
  return Ray{nearPoint, (farPoint - nearPoint).normalized()};
}

std::optional<Eigen::Vector2f> projectToPixel(const render::Camera& camera,
                                              const Eigen::Vector3f& p, int width, int height) {
  const float aspect = float(width) / float(std::max(height, 1));
  const Eigen::Vector4f clip = camera.projection(aspect) * camera.view() * p.homogeneous();
  if (clip.w() <= 1e-8f) return std::nullopt;
  const Eigen::Vector3f ndc = clip.head<3>() / clip.w();
  return Eigen::Vector2f((ndc.x() + 1.0f) * 0.5f * float(width),
                         (1.0f - ndc.y()) * 0.5f * float(height));
}

std::optional<TriangleHit> nearestTriangleHit(const render::SurfaceMesh& mesh, const Ray& ray) {
  float best = std::numeric_limits<float>::infinity();
  int bestTriangle = -1;
  for (int t = 0; t < mesh.triangles.rows(); ++t) {
    // Moller-Trumbore, both sides.
    const Eigen::Vector3f a = mesh.positions.row(mesh.triangles(t, 0)).transpose();
    const Eigen::Vector3f b = mesh.positions.row(mesh.triangles(t, 1)).transpose();
    const Eigen::Vector3f c = mesh.positions.row(mesh.triangles(t, 2)).transpose();
    const Eigen::Vector3f e1 = b - a, e2 = c - a;
    const Eigen::Vector3f p = ray.direction.cross(e2);
    const float det = e1.dot(p);
    if (std::abs(det) < 1e-12f) continue;
    const float inv = 1.0f / det;
    const Eigen::Vector3f s = ray.origin - a;
    const float u = s.dot(p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const Eigen::Vector3f q = s.cross(e1);
    const float v = ray.direction.dot(q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float distance = e2.dot(q) * inv;
    if (distance > 0.0f && distance < best) {
      best = distance;
      bestTriangle = t;
    }
  }
  if (bestTriangle < 0) return std::nullopt;
  return TriangleHit{bestTriangle, best};
}

std::optional<int> pickVertex(const render::SurfaceMesh& mesh, const Ray& ray) {
  const auto nearestHit = nearestTriangleHit(mesh, ray);
  if (!nearestHit) return std::nullopt;
  const Eigen::Vector3f hit = ray.origin + nearestHit->distance * ray.direction;
  int vertex = mesh.triangles(nearestHit->triangle, 0);
  float nearest = std::numeric_limits<float>::infinity();
  for (int corner = 0; corner < 3; ++corner) {
    const int v = mesh.triangles(nearestHit->triangle, corner);
    const float d = (mesh.positions.row(v).transpose() - hit).squaredNorm();
    if (d < nearest) nearest = d, vertex = v;
  }
  return vertex;
}

std::vector<int> boxSelect(const render::SurfaceMesh& mesh, const render::Camera& camera,
                           Eigen::Vector2f corner0, Eigen::Vector2f corner1, int width,
                           int height) {
  const Eigen::Vector2f low = corner0.cwiseMin(corner1), high = corner0.cwiseMax(corner1);
  std::vector<int> inside;
  for (int v = 0; v < mesh.positions.rows(); ++v) {
    const auto pixel = projectToPixel(camera, mesh.positions.row(v).transpose(), width, height);
    if (pixel && (pixel->array() >= low.array()).all() && (pixel->array() <= high.array()).all())
      inside.push_back(v);
  }
  return inside;
}

bool Selection::contains(int node) const {
  return std::binary_search(nodes_.begin(), nodes_.end(), node);
}

void Selection::set(std::vector<int> nodes) {
  focus_ = nodes.empty() ? -1 : nodes.front();
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  nodes_ = std::move(nodes);
}

void Selection::add(const std::vector<int>& nodes) {
  const int focus = nodes.empty() ? focus_ : nodes.front();
  std::vector<int> all = nodes_;
  all.insert(all.end(), nodes.begin(), nodes.end());
  set(std::move(all));
  focus_ = focus;
}

void Selection::toggle(int node) {
  auto it = std::lower_bound(nodes_.begin(), nodes_.end(), node);
  if (it != nodes_.end() && *it == node) {
    nodes_.erase(it);
    if (focus_ == node) focus_ = nodes_.empty() ? -1 : nodes_.front();
  } else {
    nodes_.insert(it, node);
    focus_ = node;
  }
}

void addFixedAttachments(nlohmann::json& document, const std::vector<int>& nodes,
                         const std::vector<int>& vertexOffset) {
  const int cloths = static_cast<int>(vertexOffset.size()) - 1;
  std::vector<std::vector<int>> perCloth(static_cast<std::size_t>(std::max(cloths, 0)));
  for (int node : nodes) {
    const int cloth = clothOfNode(vertexOffset, node);
    if (cloth < 0)
      throw std::invalid_argument("vertex " + std::to_string(node) + " is not a cloth vertex");
    perCloth[static_cast<std::size_t>(cloth)].push_back(
        node - vertexOffset[static_cast<std::size_t>(cloth)]);
  }
  for (int c = 0; c < cloths; ++c) {
    auto& local = perCloth[static_cast<std::size_t>(c)];
    if (local.empty()) continue;
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    nlohmann::json& cloth = document.at("cloths").at(static_cast<std::size_t>(c));
    if (!cloth.contains("attachments")) cloth["attachments"] = nlohmann::json::array();
    cloth["attachments"].push_back({{"vertices", local}, {"kind", "fixed"}});
  }
}

}  // namespace weft::editor
