#pragma once
// The analytic obstacles the editor adds from its menu, each a valid obstacles[] entry with
// placeholder dimensions the user then edits (the Obstacles panel's numeric fields).

#include <weft/core/Types.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

// "plane", "sphere", "capsule", "box", "cylinder".
const std::vector<std::string>& analyticObstacleShapes();

// An obstacles[] entry of that shape with friction 0.3. Throws std::invalid_argument for any
// other name (mesh obstacles come from a file: MeshImport).
nlohmann::json defaultObstacle(const std::string& shape);

// Where a new obstacle goes, so that it is seen and near the garment (a template at the origin
// lands inside a garment there and hides): centred on the `selected` rows of `clothPositions`
// (their centroid) when any are given, the user's pick; else just below the cloths, under the
// centre of their bounding box, its top 2 cm below their lowest vertex; the origin without
// cloths. `obstacle` is the template (defaultObstacle), whose height it reads.
Vec3 newObstaclePlace(const nlohmann::json& obstacle, const NodeMatrix& clothPositions,
                      const std::vector<int>& selected);

// Moves a template (defaultObstacle, centred on the origin) so that its centre, or a plane's
// point, lies at `at`.
void moveObstacleTo(nlohmann::json& obstacle, const Vec3& at);

}  // namespace weft::editor
