#include "ObstacleTemplates.h"

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

}  // namespace weft::editor
