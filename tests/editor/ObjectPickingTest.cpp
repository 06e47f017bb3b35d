// Ctrl+click picking of what the gizmo places: sphere tracing of every obstacle shape on the
// engine's signed distance (analytic shapes and a mesh), the nearest of obstacles and cloths
// winning, obstacles picked where their motion has taken them, and the session making the object
// under a known pixel the active one (a click on nothing takes the gizmo off).

#include <EditorSession.h>
#include <ObjectPicking.h>

#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>

#include <tuple>

#include <cmath>

namespace weft::editor {
namespace {

using test::TempDir;

Ray downAt(double x, double z, double height = 5.0) {
  return Ray{Eigen::Vector3f(float(x), float(height), float(z)), -Eigen::Vector3f::UnitY()};
}

// A 0.4 m square of two triangles at height y around (x, z), as OBJ.
std::string squareObj(double x, double y, double z) {
  std::string obj;
  for (auto [dx, dz] : {std::pair{-0.2, -0.2}, {0.2, -0.2}, {0.2, 0.2}, {-0.2, 0.2}})
    obj += "v " + std::to_string(x + dx) + " " + std::to_string(y) + " " + std::to_string(z + dz) +
           "\n";
  return obj + "f 1 2 3\nf 1 3 4\n";
}

// Every obstacle kind in a row along X (obstacle k at x = k), each with its top at a known height
// under a ray straight down from y = 5 just off its centre.
nlohmann::json everyShape(const std::string& meshFile) {
  nlohmann::json doc = test::gridScene(0.2, 1, 0.01, 1);
  doc["obstacles"] = {
      {{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}},
      {{"sphere", {{"center", {1, 0.5, 0}}, {"radius", 0.25}}}},
      {{"capsule", {{"a", {2, 0.2, -0.3}}, {"b", {2, 0.2, 0.3}}, {"radius", 0.2}}}},
      {{"box", {{"center", {3, 0.5, 0}}, {"size", {0.4, 0.6, 0.4}}, {"rotate_deg", {0, 45, 0}}}}},
      {{"cylinder", {{"a", {4, 0, 0}}, {"b", {4, 0.7, 0}}, {"radius", 0.1}}}},
      {{"mesh", {{"file", meshFile}}}}};
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {-3.0, 1.0, 0.0}}};  // out of the way
  return doc;
}

// All cloths of `scene` as the viewport draws them (RenderScene::cloth): one mesh, scene order.
render::SurfaceMesh clothSurface(const Scene& scene) {
  render::SurfaceMesh out;
  int vertices = 0, triangles = 0;
  for (const Cloth& c : scene.cloths)
    vertices += c.mesh.vertexCount(), triangles += c.mesh.triangleCount();
  out.positions.resize(vertices, 3);
  out.triangles.resize(triangles, 3);
  int v = 0, t = 0;
  for (const Cloth& c : scene.cloths) {
    out.positions.middleRows(v, c.mesh.vertexCount()) = c.mesh.vertices.cast<float>();
    out.triangles.middleRows(t, c.mesh.triangleCount()) = (c.mesh.triangles.array() + v).matrix();
    v += c.mesh.vertexCount(), t += c.mesh.triangleCount();
  }
  return out;
}

TEST(ObjectPicking, TracesEveryShapeToItsSurface) {
  TempDir dir;
  const Scene scene = test::parse(everyShape(dir.write("square.obj", squareObj(5, 0.9, 0))));
  // Ground, sphere, capsule, box, cylinder, mesh; the round tops by Pythagoras.
  const double tops[] = {0.0,
                         0.5 + std::sqrt(0.25 * 0.25 - 0.05 * 0.05),
                         0.2 + std::sqrt(0.2 * 0.2 - 0.05 * 0.05),
                         0.8,
                         0.7,
                         0.9};
  for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
    SCOPED_TRACE("obstacle " + std::to_string(k));
    const auto shape = makeObstacleShape(scene.obstacles[k]);
    // 0.05 m off centre, so that a round top is met below its highest point, where the height
    // depends on the shape's curvature and not only on its extent.
    const double x = double(k) + 0.05;
    const double top = tops[k];
    const auto hit = traceShape(*shape, RigidPose(), downAt(x, 0.0), 100.0);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(*hit, 5.0 - top, 1e-5);
    // Upwards it meets nothing, and nothing beyond the distance allowed.
    EXPECT_FALSE(traceShape(*shape, RigidPose(),
                            Ray{downAt(x, 0.0).origin, Eigen::Vector3f::UnitY()}, 100.0));
    EXPECT_FALSE(traceShape(*shape, RigidPose(), downAt(x, 0.0), 5.0 - top - 0.01));
  }
  // Beside the sphere, the ray passes it by (and meets the ground plane only).
  EXPECT_FALSE(
      traceShape(*makeObstacleShape(scene.obstacles[1]), RigidPose(), downAt(1.3, 0.0), 100.0));
  // A ray skimming the ground at a shallow angle still finds it (to within the stopping distance
  // over the sine of the angle, 2 mm here: far below what a click tells).
  const Ray skim{Eigen::Vector3f(0, 0.05f, 0), Eigen::Vector3f(1, -0.005f, 0).normalized()};
  const auto far = traceShape(*makeObstacleShape(scene.obstacles[0]), RigidPose(), skim, 100.0);
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(*far, std::hypot(10.0, 0.05), 5e-3);
}

TEST(ObjectPicking, NearestHitWinsAmongObstaclesAndCloths) {
  TempDir dir;
  nlohmann::json doc = everyShape(dir.write("square.obj", squareObj(5, 0.9, 0)));
  // A second cloth: a 0.2 m square at y = 1.2 over the sphere.
  doc["cloths"].push_back(doc["cloths"][0]);
  doc["cloths"][1]["mesh"]["transform"] = {{"translate", {1.0, 1.2, 0.0}}};
  const Scene scene = test::parse(doc);
  const render::SurfaceMesh cloth = clothSurface(scene);

  auto picked = [&](const Ray& ray) {
    const auto hit = pickObject(scene, 0.0, cloth, ray, 100.0);
    return hit ? hit->object.path() : std::string();
  };
  EXPECT_EQ(picked(downAt(1.0, 0.0)), "cloths.1") << "the cloth over the sphere is nearer";
  EXPECT_EQ(picked(downAt(1.0, 0.2)), "obstacles.1") << "beside the cloth, the sphere under it";
  EXPECT_EQ(picked(downAt(-3.0, 0.0)), "cloths.0");
  EXPECT_EQ(picked(downAt(3.0, 0.0)), "obstacles.3");
  EXPECT_EQ(picked(downAt(5.0, 0.1)), "obstacles.5") << "the mesh obstacle";
  EXPECT_EQ(picked(downAt(1.5, 0.0)), "obstacles.0") << "between the shapes, the ground";
  EXPECT_EQ(picked(Ray{Eigen::Vector3f(1, 5, 0), Eigen::Vector3f::UnitY()}), "") << "the sky";
  const auto hit = pickObject(scene, 0.0, cloth, downAt(1.0, 0.2), 100.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 5.0 - (0.5 + std::sqrt(0.25 * 0.25 - 0.2 * 0.2)), 1e-5);
}

TEST(ObjectPicking, ObstaclesArePickedWhereTheirMotionHasTakenThem) {
  nlohmann::json doc = test::gridScene(0.2, 1, 0.01, 100);
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {-3.0, 1.0, 0.0}}};
  doc["obstacles"] = {
      {{"sphere", {{"center", {0, 0.5, 0}}, {"radius", 0.25}}},
       {"motion",
        {{"keyframes",
          {{{"time", 0.0}, {"offset", {0, 0, 0}}}, {{"time", 1.0}, {"offset", {2, 0, 0}}}}}}}}};
  const Scene scene = test::parse(doc);
  const render::SurfaceMesh cloth = clothSurface(scene);
  EXPECT_TRUE(pickObject(scene, 0.0, cloth, downAt(0.0, 0.0), 100.0));
  EXPECT_FALSE(pickObject(scene, 0.0, cloth, downAt(2.0, 0.0), 100.0));
  EXPECT_FALSE(pickObject(scene, 1.0, cloth, downAt(0.0, 0.0), 100.0)) << "it has moved away";
  EXPECT_TRUE(pickObject(scene, 1.0, cloth, downAt(2.0, 0.0), 100.0));
}

// A plane is infinite to contact but drawn as a square (render::planeHalfSize around the frame's
// centre): with that extent a click beside the square is on the background.
TEST(ObjectPicking, APlaneIsPickedWhereItIsDrawn) {
  nlohmann::json doc = test::gridScene(0.2, 1, 0.01, 1);
  doc["cloths"][0]["mesh"]["transform"] = {{"translate", {0.0, 1.0, 0.0}}};
  doc["obstacles"] = {{{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
  const Scene scene = test::parse(doc);
  const render::SurfaceMesh cloth = clothSurface(scene);
  const DrawnPlaneExtent square{Vec3(0.5, 1.0, 0.0), 2.0};  // x, z in [-1.5, 2.5] x [-2, 2]
  for (const auto& [x, z, inside] : {std::tuple{0.0, 0.0, true},
                                     {2.4, 1.9, true},
                                     {-1.4, -1.9, true},
                                     {2.6, 0.0, false},
                                     {0.0, -2.1, false},
                                     {-1.6, 0.0, false}}) {
    SCOPED_TRACE(std::to_string(x) + ", " + std::to_string(z));
    EXPECT_TRUE(pickObject(scene, 0.0, cloth, downAt(x, z), 100.0)) << "infinite without an extent";
    const auto hit = pickObject(scene, 0.0, cloth, downAt(x, z), 100.0, square);
    EXPECT_EQ(hit.has_value(), inside);
  }
}

// The hanging cloth (x in [-0.5, 0.5], y in [0.5, 1.5], z = 0) with a sphere in front of its
// lower left corner and a box under it, seen from the front.
nlohmann::json clothSphereBox() {
  nlohmann::json doc = test::hangingClothScene(1.0, 4, 0.01, 3, 500.0);
  doc["obstacles"] = {
      {{"sphere", {{"center", {-0.4, 0.6, 0.3}}, {"radius", 0.15}}}, {"friction", 0.3}},
      {{"box", {{"center", {0.0, -0.2, 0.0}}, {"size", {1.2, 0.2, 0.8}}}}, {"friction", 0.3}}};
  return doc;
}

TEST(EditorSessionPicking, CtrlClickAtKnownPixelsChoosesWhatTheGizmoPlaces) {
  EditorSession session("");
  session.newDocument(clothSphereBox());
  ASSERT_TRUE(session.document().valid()) << session.document().validationError();
  render::Camera& camera = session.camera();
  camera.yawDeg = 0.0f, camera.pitchDeg = 0.0f, camera.distance = 4.0f;
  camera.target = render::Vec3f(0.0f, 0.5f, 0.0f);
  const int width = 800, height = 600;
  auto pixelOf = [&](float x, float y, float z) {
    const auto p = projectToPixel(camera, Eigen::Vector3f(x, y, z), width, height);
    EXPECT_TRUE(p.has_value());
    return p.value_or(Eigen::Vector2f::Zero());
  };
  ASSERT_EQ(session.selecting().selectNodes({7}, false), "");
  auto click = [&](const Eigen::Vector2f& p) {
    EXPECT_EQ(session.placement().clickObject(p.x(), p.y(), width, height), "");
    return session.placement().activeObject().path();
  };
  EXPECT_EQ(click(pixelOf(-0.4f, 0.6f, 0.3f)), "obstacles.0")
      << "the sphere, in front of the cloth";
  EXPECT_EQ(click(pixelOf(0.2f, 1.2f, 0.0f)), "cloths.0");
  EXPECT_EQ(click(pixelOf(0.3f, -0.2f, 0.4f)), "obstacles.1");
  ASSERT_TRUE(session.placement().gizmo(width, height).has_value()) << "the gizmo is on the box";
  EXPECT_EQ(session.placement().gizmo(width, height)->origin(), Eigen::Vector3f(0.0f, -0.2f, 0.0f));
  // Empty space takes the gizmo off (as Esc does).
  EXPECT_EQ(click(pixelOf(-1.2f, 1.4f, 0.0f)), "");
  EXPECT_FALSE(session.placement().gizmo(width, height).has_value());
  EXPECT_EQ(session.selection().nodes(), std::vector<int>{7})
      << "object picking leaves the vertex selection";
}

}  // namespace
}  // namespace weft::editor
