#include "ObstacleTemplates.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft::editor {

const std::vector<std::string>& analyticObstacleShapes() {
  static const std::vector<std::string> shapes = {"plane", "sphere", "capsule", "box", "cylinder"};
  return shapes;
}

nlohmann::json defaultObstacle(const std::string& shape) {
  nlohmann::json o;
  if (shape == "plane")
    o["plane"] = {{"point", {0.0, 0.0, 0.0}}, {"normal", {0.0, 1.0, 0.0}}};
  else if (shape == "sphere")
    o["sphere"] = {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.3}};
  else if (shape == "capsule")
    o["capsule"] = {{"a", {-0.3, 0.0, 0.0}}, {"b", {0.3, 0.0, 0.0}}, {"radius", 0.1}};
  else if (shape == "cylinder")
    o["cylinder"] = {{"a", {0.0, -0.2, 0.0}}, {"b", {0.0, 0.2, 0.0}}, {"radius", 0.2}};
  else if (shape == "box")
    o["box"] = {
        {"center", {0.0, 0.0, 0.0}}, {"size", {0.4, 0.4, 0.4}}, {"rotate_deg", {0.0, 0.0, 0.0}}};
  else
    throw std::invalid_argument(
        "unknown obstacle shape '" + shape +
        "' (plane, sphere, capsule, box or cylinder; a mesh comes from a file)");
  o["friction"] = 0.3;
  return o;
}

namespace {

Vec3 vec(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

nlohmann::json json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

// How far a template centred on the origin reaches below its centre.
double halfHeight(const nlohmann::json& o) {
  if (o.contains("sphere")) return o["sphere"]["radius"].get<double>();
  if (o.contains("box")) return 0.5 * o["box"]["size"][1].get<double>();
  for (const char* axial : {"capsule", "cylinder"})
    if (o.contains(axial)) {
      const double ends = std::max(std::abs(o[axial]["a"][1].get<double>()),
                                   std::abs(o[axial]["b"][1].get<double>()));
      // A capsule's caps reach a radius past its ends; a cylinder's vertical axis does not.
      return std::string(axial) == "capsule" ? ends + o[axial]["radius"].get<double>() : ends;
    }
  return 0.0;  // a plane
}

}  // namespace

Vec3 newObstaclePlace(const nlohmann::json& obstacle, const NodeMatrix& clothPositions,
                      const std::vector<int>& selected) {
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (int node : selected)
    if (node >= 0 && node < clothPositions.rows())
      sum += clothPositions.row(node).transpose(), ++count;
  if (count > 0) return sum / count;
  if (clothPositions.rows() == 0) return Vec3::Zero();
  const Vec3 lower = clothPositions.colwise().minCoeff().transpose();
  const Vec3 upper = clothPositions.colwise().maxCoeff().transpose();
  constexpr double kGap = 0.02;
  return Vec3(0.5 * (lower.x() + upper.x()), lower.y() - kGap - halfHeight(obstacle),
              0.5 * (lower.z() + upper.z()));
}

void moveObstacleTo(nlohmann::json& o, const Vec3& at) {
  if (o.contains("plane")) o["plane"]["point"] = json(at);
  for (const char* centred : {"sphere", "box"})
    if (o.contains(centred)) o[centred]["center"] = json(vec(o[centred]["center"]) + at);
  for (const char* axial : {"capsule", "cylinder"})
    if (o.contains(axial)) {
      o[axial]["a"] = json(vec(o[axial]["a"]) + at);
      o[axial]["b"] = json(vec(o[axial]["b"]) + at);
    }
}

}  // namespace weft::editor
