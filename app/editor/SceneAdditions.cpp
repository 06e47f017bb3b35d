#include "SceneAdditions.h"

#include "ObstacleTemplates.h"

#include <filesystem>

namespace weft::editor {

MeshImport SceneAdditions::previewGarment(const MeshImportOptions& options) const {
  return prepareGarment(options, document_.file(), document_.directory());
}

std::string SceneAdditions::importGarment(const MeshImportOptions& options) {
  const MeshImport prepared = previewGarment(options);
  if (!prepared.ok()) return prepared.error;
  const std::string name = std::filesystem::path(options.file).filename().string();
  return document_.edit("Import garment " + name, [&](nlohmann::json& doc) {
    if (!doc.contains("cloths") || !doc["cloths"].is_array())
      doc["cloths"] = nlohmann::json::array();
    doc["cloths"].push_back(prepared.entry);
  });
}

std::string SceneAdditions::addObstacle(const std::string& shape,
                                        const std::vector<int>& selected) {
  nlohmann::json obstacle;
  try {
    obstacle = defaultObstacle(shape);
  } catch (const std::exception& e) {
    return e.what();
  }
  // The cloths' rest positions, in global node order (ClothNodes.h).
  NodeMatrix positions(0, 3);
  if (const Scene* scene = document_.scene()) {
    Eigen::Index rows = 0;
    for (const auto& cloth : scene->cloths) rows += cloth.mesh.vertices.rows();
    positions.resize(rows, 3);
    Eigen::Index at = 0;
    for (const auto& cloth : scene->cloths) {
      positions.middleRows(at, cloth.mesh.vertices.rows()) = cloth.mesh.vertices;
      at += cloth.mesh.vertices.rows();
    }
  }
  moveObstacleTo(obstacle, newObstaclePlace(obstacle, positions, selected));
  return document_.edit("Add " + shape, [&](nlohmann::json& doc) {
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array())
      doc["obstacles"] = nlohmann::json::array();
    doc["obstacles"].push_back(obstacle);
  });
}

std::string SceneAdditions::importMeshObstacle(const MeshImportOptions& options) {
  const MeshImport prepared = prepareMeshObstacle(options, document_.file(), document_.directory());
  if (!prepared.ok()) return prepared.error;
  const std::string name = std::filesystem::path(options.file).filename().string();
  return document_.edit("Add mesh obstacle " + name, [&](nlohmann::json& doc) {
    if (!doc.contains("obstacles") || !doc["obstacles"].is_array())
      doc["obstacles"] = nlohmann::json::array();
    doc["obstacles"].push_back(prepared.entry);
  });
}

}  // namespace weft::editor
