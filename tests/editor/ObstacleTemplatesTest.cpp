// The Add menu's obstacles: each template is a valid entry, and a new obstacle is placed where it
// is seen, near the garment: on the selection, else just below the cloths.

#include "ObstacleTemplates.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace weft::editor {
namespace {

Vec3 vec(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// A 1 m square cloth at height 1.5 m spanning x in [2, 3], z in [-1, 0], with a dip to 1.2 m.
NodeMatrix cloth() {
  NodeMatrix x(5, 3);
  x << 2, 1.5, -1, 3, 1.5, -1, 3, 1.5, 0, 2, 1.5, 0, 2.5, 1.2, -0.5;
  return x;
}

TEST(ObstacleTemplates, NewObstacleSitsJustBelowTheClothsWhenNothingIsSelected) {
  for (const std::string& shape : analyticObstacleShapes()) {
    SCOPED_TRACE(shape);
    nlohmann::json o = defaultObstacle(shape);
    const Vec3 at = newObstaclePlace(o, cloth(), {});
    moveObstacleTo(o, at);
    EXPECT_DOUBLE_EQ(at.x(), 2.5);
    EXPECT_DOUBLE_EQ(at.z(), -0.5);
    // The obstacle's top is 2 cm under the lowest cloth vertex (1.2 m).
    double top = 0.0;
    if (shape == "plane") top = vec(o["plane"]["point"]).y();
    if (shape == "sphere")
      top = vec(o["sphere"]["center"]).y() + o["sphere"]["radius"].get<double>();
    if (shape == "box") top = vec(o["box"]["center"]).y() + 0.5 * o["box"]["size"][1].get<double>();
    if (shape == "capsule")
      top = std::max(vec(o["capsule"]["a"]).y(), vec(o["capsule"]["b"]).y()) +
            o["capsule"]["radius"].get<double>();
    if (shape == "cylinder")
      top = std::max(vec(o["cylinder"]["a"]).y(), vec(o["cylinder"]["b"]).y());
    EXPECT_NEAR(top, 1.18, 1e-12);
  }
}

TEST(ObstacleTemplates, NewObstacleIsCentredOnTheSelection) {
  nlohmann::json o = defaultObstacle("capsule");
  const Vec3 at = newObstaclePlace(o, cloth(), {0, 1, 99});  // 99 is no node: ignored
  EXPECT_TRUE(at.isApprox(Vec3(2.5, 1.5, -1.0)));
  moveObstacleTo(o, at);
  // The capsule keeps its length and axis, now about the selection's centroid.
  EXPECT_TRUE(vec(o["capsule"]["a"]).isApprox(Vec3(2.2, 1.5, -1.0)));
  EXPECT_TRUE(vec(o["capsule"]["b"]).isApprox(Vec3(2.8, 1.5, -1.0)));
  EXPECT_TRUE(newObstaclePlace(o, NodeMatrix(0, 3), {}).isZero()) << "no cloth: the origin";
}

}  // namespace
}  // namespace weft::editor
