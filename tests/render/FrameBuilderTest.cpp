// The adapter from scenes to frame descriptions: obstacles, attachment markers, handle
// trajectories and target ghosts come from the scene; the cloth from the state given.

#include <weft/frames/FrameBuilder.h>

#include <support/SceneBuilder.h>
#include <support/TempDir.h>

#include <weft/io/Npy.h>
#include <weft/model/ClothModel.h>

#include <gtest/gtest.h>

namespace weft::test {
namespace {

TEST(FrameBuilder, DescribesObstaclesMarkersAndHandleCurves) {
  nlohmann::json doc = hangingClothScene(0.5, 4, 0.01, 100, 500.0);  // fixed vertices 0 and 4
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {20, 24}},
       {"kind", "handle"},
       {"trajectory",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 0.5}, {"offset", {0, 0.3, 0.2}}}}}}}});
  doc["obstacles"] = {
      {{"sphere", {{"center", {0, 0.2, 0.4}}, {"radius", 0.1}}}, {"friction", 0.3}},
      {{"plane", {{"point", {0, -1, 0}}, {"normal", {0, 1, 0}}}}, {"friction", 0.3}}};
  const Scene scene = parse(doc);
  const ClothModel model = buildClothModel(scene);
  FrameBuilder builder(scene, model);
  NodeMatrix x = model.rest.vertices;
  x.col(2).array() += 0.05;  // the state, not the rest shape, is what is drawn
  const render::RenderScene frame = builder.frame(x, 3);

  ASSERT_EQ(frame.cloth.positions.rows(), model.nodeCount());
  EXPECT_FLOAT_EQ(frame.cloth.positions(7, 2), float(x(7, 2)));
  EXPECT_EQ(frame.cloth.triangles.rows(), model.rest.triangleCount());
  ASSERT_EQ(frame.obstacles.size(), 2u);
  EXPECT_EQ(frame.obstacles[0].kind, render::ObstacleShape::Kind::Sphere);
  EXPECT_FLOAT_EQ(frame.obstacles[0].radius, 0.1f);
  EXPECT_EQ(frame.obstacles[1].kind, render::ObstacleShape::Kind::Plane);
  ASSERT_EQ(frame.fixedPoints.size(), 2u);
  EXPECT_TRUE(frame.fixedPoints[1].isApprox(x.row(4).transpose().cast<float>()));
  ASSERT_EQ(frame.handlePoints.size(), 2u);
  EXPECT_TRUE(frame.handlePoints[0].isApprox(x.row(20).transpose().cast<float>()));

  // One curve: the handle centroid's path over the whole run, ending 0.3 up and 0.2 forward.
  ASSERT_EQ(frame.curves.size(), 1u);
  const Vec3 centroid =
      0.5 * (model.rest.vertices.row(20) + model.rest.vertices.row(24)).transpose();
  EXPECT_TRUE(frame.curves[0].points.front().isApprox(centroid.cast<float>(), 1e-5f));
  EXPECT_TRUE(
      frame.curves[0].points.back().isApprox((centroid + Vec3(0, 0.3, 0.2)).cast<float>(), 1e-5f));
  EXPECT_GT(frame.curves[0].points.size(), 100u);
}

// Pin groups: with more than one fixed attachment, each fixed point carries its group (its
// attachment's number among the scene's fixed ones, handles not counted), for its colour.
TEST(FrameBuilder, FixedPointsCarryTheirPinGroupWhenThereAreSeveral) {
  nlohmann::json doc = hangingClothScene(0.5, 4, 0.01, 10, 500.0);  // fixed vertices 0 and 4
  {
    const Scene scene = parse(doc);
    const ClothModel model = buildClothModel(scene);
    EXPECT_TRUE(FrameBuilder(scene, model).frame(model.rest.vertices, 0).fixedPointGroups.empty())
        << "one group: the style's colour";
  }
  doc["cloths"][0]["attachments"].push_back(
      {{"vertices", {20}},
       {"kind", "handle"},
       {"trajectory", {{"keyframes", {{{"time", 0.0}, {"offset", {0, 0, 0}}}}}}}});
  doc["cloths"][0]["attachments"].push_back({{"vertices", {22, 23}}, {"name", "hem"}});
  const Scene scene = parse(doc);
  const ClothModel model = buildClothModel(scene);
  const render::RenderScene frame = FrameBuilder(scene, model).frame(model.rest.vertices, 0);
  ASSERT_EQ(frame.fixedPoints.size(), 4u);
  EXPECT_EQ(frame.fixedPointGroups, (std::vector<int>{0, 0, 1, 1}));
  EXPECT_TRUE(frame.fixedPoints[2].isApprox(model.rest.vertices.row(22).transpose().cast<float>()));
}

TEST(FrameBuilder, MovingObstaclesAreDrawnWhereTheyAreAtEachState) {
  nlohmann::json doc = hangingClothScene(0.5, 2, 0.01, 100, 500.0);
  doc["obstacles"] = nlohmann::json::parse(R"([
    { "sphere": { "center": [0, 0, 0.5], "radius": 0.1 }, "friction": 0.3,
      "motion": { "keyframes": [ { "time": 0.0, "offset": [0, 0, 0] }, { "time": 1.0, "offset": [1, 0, 0] } ] } },
    { "box": { "center": [0, 0, 0], "size": [0.2, 0.2, 0.2] }, "friction": 0.3,
      "motion": { "rotate": { "center": [0, 0, 0], "axis": [0, 1, 0], "degrees_per_second": 90.0 } } } ])");
  const Scene scene = parse(doc);
  const ClothModel model = buildClothModel(scene);
  FrameBuilder builder(scene, model);
  const render::RenderScene frame = builder.frame(model.rest.vertices, 50);  // t = 0.5 s
  EXPECT_TRUE(frame.obstacles[0].center.isApprox(render::Vec3f(0.5f, 0.0f, 0.5f), 1e-5f));
  // 45 degrees about +Y: the box's local X axis turns towards -Z.
  const render::Vec3f x = frame.obstacles[1].rotation.col(0);
  EXPECT_NEAR(x.x(), std::sqrt(0.5f), 1e-5f);
  EXPECT_NEAR(x.z(), -std::sqrt(0.5f), 1e-5f);
  EXPECT_TRUE(builder.frame(model.rest.vertices, 0)
                  .obstacles[0]
                  .center.isApprox(render::Vec3f(0, 0, 0.5f)));
}

TEST(FrameBuilder, ShowsTaskTargetsAsGhostsOrPoints) {
  TempDir dir;
  nlohmann::json doc = hangingClothScene(0.5, 2, 0.01, 10, 500.0);
  const Scene rest = parse(doc);
  const ClothModel model = buildClothModel(rest);
  const int n = model.nodeCount();
  std::vector<double> states;
  for (int s = 0; s < 3; ++s)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        states.push_back(model.rest.vertices(i, c) + (c == 1 ? 0.1 * s : 0.0));
  writeNpy(dir.file("target.npy"), {3, std::size_t(n), 3}, states.data());
  doc["task"] = {{"loss",
                  {{"trajectory", {{"target", dir.file("target.npy")}}},
                   {"final", {{"target", dir.file("target.npy")}, {"vertices", {0, 2}}}}}},
                 {"parameters", {"cloths.0.material.stretch"}}};
  const Scene scene = parse(doc);
  std::vector<std::string> warnings;
  FrameBuilder builder(scene, model, &warnings);
  EXPECT_TRUE(warnings.empty());
  const render::RenderScene frame = builder.frame(model.rest.vertices, 1);
  ASSERT_EQ(frame.ghosts.size(), 1u);  // the trajectory target at this state
  EXPECT_NEAR(frame.ghosts[0].mesh.positions(0, 1), model.rest.vertices(0, 1) + 0.1, 1e-6);
  ASSERT_EQ(frame.targetPoints.size(), 2u);  // the final target's listed vertices, last state
  EXPECT_NEAR(frame.targetPoints[1].y(), model.rest.vertices(2, 1) + 0.2, 1e-6);

  // A target that cannot be shown is a warning, not a failed render.
  doc["task"]["loss"] = {{"trajectory", {{"target", dir.file("missing.npy")}}}};
  std::vector<std::string> missing;
  FrameBuilder without(parse(doc), model, &missing);
  EXPECT_EQ(missing.size(), 1u);
  EXPECT_TRUE(without.frame(model.rest.vertices, 0).ghosts.empty());
}

}  // namespace
}  // namespace weft::test
