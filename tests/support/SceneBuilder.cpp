#include <support/SceneBuilder.h>

#include <support/TempDir.h>
#include <weft/scene/SceneLoader.h>

#include <fstream>
#include <stdexcept>

namespace weft::test {

nlohmann::json gridScene(double size, int quads, double dt, int steps, double stretch, double bend,
                         double density) {
  nlohmann::json cloth = {
      {"mesh", {{"grid", {{"size", {size, size}}, {"resolution", {quads, quads}}}}}},
      {"material", {{"density", density}, {"stretch", stretch}, {"bend", bend}}}};
  return {{"name", "test"},
          {"time", {{"dt", dt}, {"steps", steps}}},
          {"solver", {{"pd_iterations", 2000}, {"pd_tolerance", 1e-8}}},
          {"cloths", nlohmann::json::array({cloth})}};
}

nlohmann::json hangingClothScene(double size, int quads, double dt, int steps, double stretch,
                                 double bend, double density) {
  nlohmann::json scene = gridScene(size, quads, dt, steps, stretch, bend, density);
  scene["gravity"] = {0.0, -9.8, 0.0};
  nlohmann::json& cloth = scene["cloths"][0];
  // Rotating the XZ grid by +90 degrees about X maps z to -y: row j = 0 becomes the top edge.
  cloth["mesh"]["transform"] = {{"rotate_deg", {90.0, 0.0, 0.0}}, {"translate", {0.0, 1.0, 0.0}}};
  cloth["attachments"] = nlohmann::json::array({{{"vertices", {0, quads}}, {"kind", "fixed"}}});
  return scene;
}

Scene parse(const nlohmann::json& document, const std::string& name) {
  return parseScene(document, name, WEFT_TEST_DATA_DIR);
}

std::string writeScene(const std::string& path, const nlohmann::json& document) {
  std::ofstream out(path);
  out << document.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
  return path;
}

}  // namespace weft::test
