#pragma once
// The analytic obstacles the editor adds from its menu, each a valid obstacles[] entry with
// placeholder dimensions the user then edits (the Obstacles panel's numeric fields).

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

// "plane", "sphere", "capsule", "box", "cylinder".
const std::vector<std::string>& analyticObstacleShapes();

// An obstacles[] entry of that shape with friction 0.3. Throws std::invalid_argument for any
// other name (mesh obstacles come from a file: MeshImport).
nlohmann::json defaultObstacle(const std::string& shape);

}  // namespace weft::editor
