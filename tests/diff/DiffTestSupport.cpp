#include <diff/DiffTestSupport.h>

#include <support/SceneBuilder.h>
#include <weft/diff/ForwardPass.h>
#include <weft/diff/GradientCheck.h>
#include <weft/diff/TaskLoss.h>
#include <weft/io/Npy.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace weft::test {

nlohmann::json windClothScene(int quads, int steps) {
  nlohmann::json doc = hangingClothScene(0.4, quads, 0.01, steps, 300.0, 0.001, 0.1);
  doc["wind"] = {
      {"direction", {0.2, 0.0, 1.0}}, {"strength", 1.5}, {"frequency", 2.0}, {"phase", 0.3}};
  nlohmann::json& cloth = doc["cloths"][0];
  const int bottomMiddle = quads * (quads + 1) + quads / 2;
  cloth["forces"] =
      nlohmann::json::array({{{"vertices", {bottomMiddle}}, {"force", {0.0, 0.0, 0.002}}}});
  cloth["initial_velocity"] = {0.0, 0.0, 0.1};
  return doc;
}

nlohmann::json handleScene(int steps) {
  nlohmann::json doc = test::windClothScene(6, steps);
  doc["cloths"][0]["attachments"] = nlohmann::json::array(
      {{{"vertices", {0}}, {"kind", "fixed"}, {"stiffness", 2000.0}},
       {{"vertices", {6}},
        {"kind", "handle"},
        {"stiffness", 500.0},
        {"trajectory",
         {{"hermite",
           {{"times", {0.0, 0.1, 0.2}},
            {"points", {{0.0, 0.0, 0.0}, {0.02, 0.03, 0.05}, {0.05, 0.02, 0.12}}},
            {"tangents", {{0.2, 0.1, 0.3}, {0.3, 0.0, 0.8}, {0.1, -0.1, 0.2}}}}}}}}});
  return doc;
}

std::string writeTargetTrajectory(const nlohmann::json& document, const std::string& path) {
  const Scene scene = withTightForwardSolver(parse(document), 1e-8);
  const ForwardPass pass = runForwardPass(scene);
  const std::vector<double> flat = pass.trajectory.flattenedPositions();
  writeNpy(
      path,
      {pass.trajectory.positions.size(), static_cast<std::size_t>(pass.trajectory.nodeCount()), 3},
      flat.data());
  return path;
}

void addTask(nlohmann::json& document, const std::string& kind, const std::string& target,
             const std::vector<std::string>& parameters) {
  document["task"] = {{"loss", {{kind, {{"target", target}}}}}, {"parameters", parameters}};
}

nlohmann::json softWindClothScene(int quads, int steps) {
  nlohmann::json doc = windClothScene(quads, steps);
  doc["cloths"][0]["material"]["stretch"] = 30.0;
  doc["cloths"][0]["material"]["density"] = 1.0;
  return doc;
}

Scene withTrajectoryTask(const TempDir& dir, const nlohmann::json& document,
                         const std::vector<std::string>& parameters) {
  nlohmann::json doc = document;
  nlohmann::json targetDoc = doc;
  targetDoc["cloths"][0]["material"]["stretch"] =
      doc["cloths"][0]["material"]["stretch"].get<double>() * 5.0 / 6.0;
  targetDoc["wind"]["strength"] = 2.0;
  const std::string target = writeTargetTrajectory(targetDoc, dir.file("target.npy"));
  addTask(doc, "trajectory", target, parameters);
  return parse(doc);
}

Scene softNapkinTaskScene(const TempDir& dir, int quads) {
  std::ifstream in(std::string(WEFT_ASSET_DIR) + "/scenes/wind_reference.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["cloths"][0]["mesh"]["grid"]["resolution"] = {quads, quads};
  doc["cloths"][0]["attachments"][0]["vertices"] = {0, quads};
  nlohmann::json targetDoc = doc;
  targetDoc["wind"]["strength"] = 1.5 * doc["wind"]["strength"].get<double>();
  const std::string name = "soft" + std::to_string(quads);
  const std::string target = writeTargetTrajectory(targetDoc, dir.file(name + ".npy"));
  addTask(doc, "trajectory", target, {"wind.strength"});
  return withTightForwardSolver(parse(doc), 1e-8);
}

Scene windTaskScene(const TempDir& dir, const std::vector<std::string>& parameters, int steps) {
  return withTrajectoryTask(dir, windClothScene(6, steps), parameters);
}

HistoryGradients gradientsWithAndWithoutHistory(const Scene& scene, BackwardSettings gmres) {
  const ForwardPass pass = runForwardPass(scene);
  const TaskLoss loss(scene);
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  HistoryGradients g;
  BackwardSettings direct = gmres;
  direct.method = "direct";
  g.direct = backpropagate(pass.trajectory, loss, parameters, direct);
  gmres.history = 8;
  g.combined = backpropagate(pass.trajectory, loss, parameters, gmres);
  gmres.history = 0;
  g.lastOnly = backpropagate(pass.trajectory, loss, parameters, gmres);
  return g;
}

void expectAdjointMatchesFiniteDifferences(const Scene& scene) {
  const ParameterSet parameters = ParameterSet::fromTask(scene);
  ASSERT_FALSE(parameters.empty());
  GradientCheckOptions options;
  options.backwardMethod = "direct";
  const GradientCheckReport report = checkGradient(scene, parameters, options);
  EXPECT_GT(report.loss, 0.0);
  EXPECT_EQ(report.unconvergedSteps, 0);
  for (const GradientCheckEntry& e : report.entries) {
    SCOPED_TRACE(e.param);
    EXPECT_NE(e.adjoint, 0.0);
    EXPECT_LT(e.relativeError, 1e-4) << "adjoint " << e.adjoint << " fd " << e.finiteDifference;
  }
}

void expectGradientAgreement(const GradientCheckReport& report, double relative, double floor) {
  double largest = 0.0;
  for (const GradientCheckEntry& e : report.entries)
    largest = std::max(largest, std::abs(e.adjoint));
  ASSERT_GT(largest, 0.0);
  EXPECT_EQ(report.unconvergedSteps, 0);
  for (const GradientCheckEntry& e : report.entries) {
    SCOPED_TRACE(e.param);
    const double allowed =
        relative * std::max(std::abs(e.adjoint), std::abs(e.finiteDifference)) + floor * largest;
    EXPECT_LE(std::abs(e.adjoint - e.finiteDifference), allowed)
        << "adjoint " << e.adjoint << " fd " << e.finiteDifference << " (largest component "
        << largest << ")";
  }
}

nlohmann::json inclineScene() {
  return nlohmann::json::parse(R"({
    "name": "incline", "time": {"dt": 0.01, "steps": 30}, "gravity": [0, -9.8, 0],
    "solver": {"pd_iterations": 200, "pd_tolerance": 1e-4},
    "cloths": [{"mesh": {"grid": {"size": [0.3, 0.1], "resolution": [6, 2]},
                         "transform": {"rotate_deg": [0, 0, 20], "translate": [0, 0.001, 0]}},
                "material": {"density": 0.2, "stretch": 100.0, "bend": 0.001},
                "initial_velocity": [-0.1, 0, 0.05]}],
    "obstacles": [{"plane": {"point": [0, 0, 0], "normal": [-0.34202, 0.939693, 0]}, "friction": 0.2}]})");
}

}  // namespace weft::test
