// The gizmo's geometry and drag arithmetic (Gizmo.h) and what placing writes into a scene
// document (Placement.h): picking handles by ray, translation as mouse motion projected onto
// the axis on screen, rotation as the angle swept about the centre, the edits of each obstacle
// kind and of a cloth's transform, and handle keyframes.

#include "EditorSession.h"
#include "Gizmo.h"
#include "Placement.h"

#include <weft/mesh/RigidTransform.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace weft::editor {
namespace {

constexpr int kWidth = 400, kHeight = 300;

// Looking along -Z at the origin from 2 m: X is right on screen, Y up.
render::Camera frontCamera() {
  render::Camera c;
  c.target = Eigen::Vector3f::Zero();
  c.distance = 2.0f;
  return c;
}

Gizmo frontGizmo(bool rotates = false) {
  return Gizmo(Eigen::Vector3f::Zero(), rotates, frontCamera(), kWidth, kHeight);
}

TEST(Gizmo, KeepsItsSizeOnScreen) {
  const Gizmo g = frontGizmo();
  const float expected = 2.0f * 2.0f * std::tan(35.0f * float(M_PI) / 360.0f) / kHeight;
  EXPECT_NEAR(g.metresPerPixel(), expected, 1e-7f);
  const std::vector<Eigen::Vector2f> arrow = g.screenPolyline(GizmoHandle::TranslateX);
  ASSERT_EQ(arrow.size(), 2u);
  EXPECT_NEAR(arrow[1].x() - kWidth / 2.0f, Gizmo::kArrowPixels, 1e-3f);
  EXPECT_NEAR(arrow[1].y(), kHeight / 2.0f, 1e-3f);
  // Twice as far away, the same pixels.
  render::Camera far = frontCamera();
  far.distance = 4.0f;
  const Gizmo g2(Eigen::Vector3f::Zero(), false, far, kWidth, kHeight);
  EXPECT_NEAR(g2.screenPolyline(GizmoHandle::TranslateX)[1].x() - kWidth / 2.0f,
              Gizmo::kArrowPixels, 1e-3f);
  EXPECT_TRUE(g.polyline(GizmoHandle::RotateX).empty()) << "no rings unless the object turns";
}

TEST(Gizmo, PicksTheHandleTheRayPassesNear) {
  const Gizmo g = frontGizmo(true);
  const float cx = kWidth / 2.0f, cy = kHeight / 2.0f;
  EXPECT_EQ(g.pickPixel(cx + 60, cy), GizmoHandle::TranslateX);
  EXPECT_EQ(g.pickPixel(cx + 60, cy + 4), GizmoHandle::TranslateX) << "within the pick radius";
  EXPECT_EQ(g.pickPixel(cx + 60, cy + 10), GizmoHandle::None) << "beyond it";
  EXPECT_EQ(g.pickPixel(cx, cy - 60), GizmoHandle::TranslateY);
  // The Z arrow points at the camera: the ray through the centre runs along it.
  EXPECT_EQ(g.pickPixel(cx, cy), GizmoHandle::TranslateZ);
  const float r = Gizmo::kRingPixels / std::sqrt(2.0f);
  EXPECT_EQ(g.pickPixel(cx + r, cy - r), GizmoHandle::RotateZ) << "the ring facing the camera";
  EXPECT_EQ(g.pickPixel(cx + 150, cy - 120), GizmoHandle::None);
  for (GizmoHandle h : {GizmoHandle::TranslateX, GizmoHandle::TranslateY, GizmoHandle::RotateX,
                        GizmoHandle::RotateY, GizmoHandle::RotateZ}) {
    const auto p = g.grabPixel(h);
    ASSERT_TRUE(p) << gizmoHandleName(h);
    EXPECT_EQ(g.pickPixel(p->x(), p->y()), h) << gizmoHandleName(h);
  }
}

TEST(Gizmo, TranslationIsTheMouseMotionAlongTheAxisOnScreen) {
  const Gizmo g = frontGizmo();
  const Eigen::Vector2f start(kWidth / 2.0f + 60, kHeight / 2.0f);
  auto drag = GizmoDrag::begin(g, GizmoHandle::TranslateX, start);
  ASSERT_TRUE(drag);
  // Only the motion along the axis's image counts: 40 px right (the 13 px down is ignored).
  EXPECT_NEAR(drag->update(start + Eigen::Vector2f(40, 13)), 40.0 * g.metresPerPixel(), 1e-6);
  EXPECT_NEAR(drag->update(start + Eigen::Vector2f(-10, 0)), -10.0 * g.metresPerPixel(), 1e-6)
      << "from the start, not the last move";
  auto up = GizmoDrag::begin(g, GizmoHandle::TranslateY, start);
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->update(start + Eigen::Vector2f(0, -25)), 25.0 * g.metresPerPixel(), 1e-6)
      << "pixels go down, Y up";
  EXPECT_FALSE(GizmoDrag::begin(g, GizmoHandle::TranslateZ, start))
      << "an axis pointing at the camera cannot be dragged";
  EXPECT_FALSE(GizmoDrag::begin(g, GizmoHandle::RotateZ, start)) << "no rings on this gizmo";
}

TEST(Gizmo, RotationIsTheAngleSweptAboutTheCentre) {
  const Gizmo g = frontGizmo(true);
  const Eigen::Vector2f centre(kWidth / 2.0f, kHeight / 2.0f);
  auto at = [&](double degrees) {
    const double a = degrees * M_PI / 180.0;
    return Eigen::Vector2f(centre.x() + 100.0f * float(std::cos(a)),
                           centre.y() - 100.0f * float(std::sin(a)));
  };
  auto drag = GizmoDrag::begin(g, GizmoHandle::RotateZ, at(45));
  ASSERT_TRUE(drag);
  // Counter-clockwise on screen about +Z, which points at the camera: a positive turn.
  for (double d = 60; d <= 135; d += 15) drag->update(at(d));
  EXPECT_NEAR(drag->amount(), M_PI / 2, 1e-5);
  // On past half a turn, and back.
  for (double d = 150; d <= 405; d += 15) drag->update(at(d));
  EXPECT_NEAR(drag->amount(), 2 * M_PI, 1e-5);
  for (double d = 390; d >= 0; d -= 15) drag->update(at(d));
  EXPECT_NEAR(drag->amount(), -M_PI / 4, 1e-5);
  // Seen from behind (-Z), the same screen motion turns the other way about +Z.
  render::Camera back = frontCamera();
  back.yawDeg = 180.0f;
  const Gizmo behind(Eigen::Vector3f::Zero(), true, back, kWidth, kHeight);
  auto reversed = GizmoDrag::begin(behind, GizmoHandle::RotateZ, at(45));
  ASSERT_TRUE(reversed);
  reversed->update(at(90));
  EXPECT_NEAR(reversed->amount(), -M_PI / 4, 1e-5);
}

TEST(Gizmo, EulerAnglesInvertTheSceneRotation) {
  for (const Vec3& degrees :
       {Vec3(10, -35, 170), Vec3(0, 0, 0), Vec3(-120, 60, 5), Vec3(90, 0, 0)}) {
    RigidTransform t;
    t.rotateDeg = degrees;
    EXPECT_LT((eulerXyzDegrees(t.rotation(), degrees) - degrees).norm(), 1e-9)
        << degrees.transpose();
    EXPECT_LT((eulerXyzDegrees(t.rotation()) - degrees).norm(), 1e-9) << degrees.transpose();
  }
  // Turning on about Y past 90 degrees keeps counting (rather than the equal (180, 80, 180)),
  // and past 180 too, given where the angles were.
  RigidTransform past;
  past.rotateDeg = Vec3(0, 100, 0);
  EXPECT_LT((eulerXyzDegrees(past.rotation()) - Vec3(0, 100, 0)).norm(), 1e-9);
  past.rotateDeg = Vec3(0, 0, 190);
  EXPECT_LT((eulerXyzDegrees(past.rotation(), Vec3(0, 0, 175)) - Vec3(0, 0, 190)).norm(), 1e-9);
  // Gimbal lock (Y = 90): other angles, the same rotation.
  RigidTransform lock;
  lock.rotateDeg = Vec3(30, 90, 20);
  RigidTransform back;
  back.rotateDeg = eulerXyzDegrees(lock.rotation());
  EXPECT_LT((back.rotation() - lock.rotation()).norm(), 1e-9);
  EXPECT_EQ(back.rotateDeg.z(), 0.0);
}

TEST(Placement, TranslationChangesOnlyThatComponent) {
  nlohmann::json capsule = {
      {"capsule", {{"a", {-0.3, 0.1, 0.2}}, {"b", {0.3, 0.1, 0.2}}, {"radius", 0.1}}},
      {"friction", 0.3}};
  translateObject(capsule, EditorObject::Kind::Obstacle, 1, 0.25);
  EXPECT_EQ(capsule["capsule"]["a"], nlohmann::json::array({-0.3, 0.1 + 0.25, 0.2}));
  EXPECT_EQ(capsule["capsule"]["b"], nlohmann::json::array({0.3, 0.1 + 0.25, 0.2}));
  EXPECT_EQ(capsule["friction"], 0.3);

  nlohmann::json plane = {{"plane", {{"point", {0.0, 0.0, 0.0}}, {"normal", {0.0, 1.0, 0.0}}}}};
  translateObject(plane, EditorObject::Kind::Obstacle, 2, -0.5);
  EXPECT_EQ(plane["plane"]["point"], nlohmann::json::array({0.0, 0.0, -0.5}));
  nlohmann::json box = {{"box", {{"center", {1.0, 2.0, 3.0}}, {"size", {1.0, 1.0, 1.0}}}}};
  translateObject(box, EditorObject::Kind::Obstacle, 0, 0.5);
  EXPECT_EQ(box["box"]["center"], nlohmann::json::array({1.5, 2.0, 3.0}));
  // A mesh (obstacle or cloth) without a transform gets one.
  nlohmann::json mesh = {{"mesh", {{"file", "m.obj"}}}};
  translateObject(mesh, EditorObject::Kind::Obstacle, 0, 0.125);
  EXPECT_EQ(mesh["mesh"]["transform"]["translate"], nlohmann::json::array({0.125, 0.0, 0.0}));
  nlohmann::json cloth = {{"mesh",
                           {{"grid", {{"size", {1, 1}}, {"resolution", {2, 2}}}},
                            {"transform", {{"translate", {0, 1, 0}}}}}}};
  translateObject(cloth, EditorObject::Kind::Cloth, 1, 0.5);
  EXPECT_EQ(cloth["mesh"]["transform"]["translate"], nlohmann::json::array({0, 1.5, 0}));
}

TEST(Placement, RotationTurnsAboutTheCentre) {
  const double quarter = M_PI / 2;
  nlohmann::json box = {
      {"box",
       {{"center", {1.0, 0.0, 0.0}}, {"size", {1.0, 1.0, 1.0}}, {"rotate_deg", {0.0, 0.0, 0.0}}}}};
  rotateObject(box, EditorObject::Kind::Obstacle, 1, quarter, Vec3(1, 0, 0));
  EXPECT_NEAR(box["box"]["rotate_deg"][1].get<double>(), 90.0, 1e-12);
  EXPECT_EQ(box["box"]["rotate_deg"][0], 0.0);
  EXPECT_EQ(box["box"]["rotate_deg"][2], 0.0);
  EXPECT_EQ(box["box"]["center"], nlohmann::json::array({1.0, 0.0, 0.0}));

  nlohmann::json cylinder = {
      {"cylinder", {{"a", {0.0, -0.2, 0.0}}, {"b", {0.0, 0.2, 0.0}}, {"radius", 0.2}}}};
  rotateObject(cylinder, EditorObject::Kind::Obstacle, 2, quarter, Vec3::Zero());  // Y turns to -X
  EXPECT_NEAR(cylinder["cylinder"]["b"][0].get<double>(), -0.2, 1e-12);
  EXPECT_NEAR(cylinder["cylinder"]["b"][1].get<double>(), 0.0, 1e-12);

  nlohmann::json plane = {{"plane", {{"point", {0.0, 0.5, 0.0}}, {"normal", {0.0, 1.0, 0.0}}}}};
  rotateObject(plane, EditorObject::Kind::Obstacle, 0, quarter, Vec3(0, 0.5, 0));  // Y turns to +Z
  EXPECT_NEAR(plane["plane"]["normal"][2].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(plane["plane"]["point"], nlohmann::json::array({0.0, 0.5, 0.0}));

  nlohmann::json sphere = {{"sphere", {{"center", {0.0, 0.0, 0.0}}, {"radius", 0.3}}}};
  const nlohmann::json before = sphere;
  rotateObject(sphere, EditorObject::Kind::Obstacle, 0, 1.0, Vec3::Zero());
  EXPECT_EQ(sphere, before);

  // A cloth's transform: every rest point x goes to Q (R x + t - c) + c.
  nlohmann::json cloth = {
      {"mesh",
       {{"grid", {{"size", {1, 1}}, {"resolution", {2, 2}}}},
        {"transform", {{"rotate_deg", {90, 0, 0}}, {"translate", {0, 1, 0}}}}}}};
  const Vec3 centre(0.1, 0.9, -0.2), x(0.3, 0.0, -0.4);
  rotateObject(cloth, EditorObject::Kind::Cloth, 1, 0.7, centre);
  RigidTransform before2, after;
  before2.rotateDeg = Vec3(90, 0, 0), before2.translate = Vec3(0, 1, 0);
  const auto& t = cloth["mesh"]["transform"];
  after.rotateDeg = Vec3(t["rotate_deg"][0], t["rotate_deg"][1], t["rotate_deg"][2]);
  after.translate = Vec3(t["translate"][0], t["translate"][1], t["translate"][2]);
  const Mat3 q = Eigen::AngleAxisd(0.7, Vec3::UnitY()).toRotationMatrix();
  EXPECT_LT((after.apply(x) - (q * (before2.apply(x) - centre) + centre)).norm(), 1e-12);
}

TEST(Placement, FindsWhatTheGizmoPlaces) {
  const nlohmann::json doc = {
      {"cloths",
       {{{"attachments",
          {{{"vertices", {0}}, {"kind", "fixed"}}, {{"vertices", {1}}, {"kind", "handle"}}}}}}},
      {"obstacles", {{{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}}}}};
  EditorObject o;
  EXPECT_EQ(findEditorObject(doc, "obstacles.0", o), "");
  EXPECT_EQ(o.kind, EditorObject::Kind::Obstacle);
  EXPECT_EQ(findEditorObject(doc, "cloths.0.attachments.1", o), "");
  EXPECT_EQ(o.kind, EditorObject::Kind::Handle);
  EXPECT_EQ(o.path(), "cloths.0.attachments.1");
  EXPECT_NE(findEditorObject(doc, "cloths.0.attachments.0", o).find("fixed attachment"),
            std::string::npos);
  EXPECT_NE(findEditorObject(doc, "obstacles.3", o).find("no such entry"), std::string::npos);
  EXPECT_NE(findEditorObject(doc, "wind", o).find("the gizmo places"), std::string::npos);
  EXPECT_EQ(o.path(), "cloths.0.attachments.1") << "a failed lookup leaves the object as it was";
  EXPECT_EQ(findEditorObject(doc, "", o), "");
  EXPECT_EQ(o.kind, EditorObject::Kind::None);
  EXPECT_FALSE(objectRotates(doc, {EditorObject::Kind::Obstacle, 0, -1}))
      << "a sphere does not turn";
}

TEST(Placement, KeysAreSetInTimeOrderReplacedAndDeleted) {
  nlohmann::json handle = newHandleAttachment({2, 3});
  ASSERT_EQ(handleKeys(handle).size(), 1u);
  EXPECT_EQ(handleKeys(handle)[0].offset, Vec3::Zero());
  setHandleKey(handle, 0.2, Vec3(0, 0.1, 0), 0.005);
  setHandleKey(handle, 0.1, Vec3(0.1, 0, 0), 0.005);
  std::vector<HandleKey> keys = handleKeys(handle);
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[1].time, 0.1);
  EXPECT_EQ(keys[2].time, 0.2);
  // Within the tolerance: the nearest key gets the new offset and keeps its time.
  setHandleKey(handle, 0.203, Vec3(0, 0.3, 0), 0.005);
  keys = handleKeys(handle);
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_EQ(keys[2].time, 0.2);
  EXPECT_EQ(keys[2].offset, Vec3(0, 0.3, 0));
  EXPECT_FALSE(deleteHandleKey(handle, 0.15, 0.005));
  EXPECT_TRUE(deleteHandleKey(handle, 0.1, 0.005));
  EXPECT_EQ(handleKeys(handle).size(), 2u);

  const nlohmann::json zero = {0, 0, 0};
  nlohmann::json hermite = {
      {"times", {0, 1}}, {"points", {zero, {0, 1, 0}}}, {"tangents", {zero, zero}}};
  nlohmann::json spline = {{"kind", "handle"}, {"trajectory", {{"hermite", hermite}}}};
  EXPECT_FALSE(hasKeyframes(spline));
  EXPECT_EQ(handleKeys(spline).size(), 2u) << "a spline's knots show as keys";
  EXPECT_THROW(setHandleKey(spline, 0.5, Vec3::Zero(), 0.01), std::invalid_argument);
}

// The session's side of a drag: every move of one drag merges into one undo step, and an object
// taken away mid-drag (an undo, a removal) turns the next move into an error, not a crash.
TEST(EditorSessionGizmo, OneUndoStepPerDragAndAnObjectGoneMidDrag) {
  EditorSession session("");
  nlohmann::json doc = EditorDocument::defaultSceneDocument();
  doc["obstacles"] = {
      {{"box", {{"center", {0.0, 0.0, 0.0}}, {"size", {0.4, 0.4, 0.4}}}}, {"friction", 0.3}}};
  session.newDocument(doc);
  EXPECT_NE(session.placement()
                .beginGizmoDrag(GizmoHandle::TranslateY, 0, 0, kWidth, kHeight)
                .find("nothing to move"),
            std::string::npos);
  ASSERT_EQ(session.placement().setActiveObject("obstacles.0"), "");
  session.camera() = frontCamera();
  const auto g = session.placement().gizmo(kWidth, kHeight);
  ASSERT_TRUE(g);
  const auto grab = g->grabPixel(GizmoHandle::TranslateY);
  ASSERT_TRUE(grab);
  ASSERT_EQ(session.placement().beginGizmoDrag(GizmoHandle::TranslateY, grab->x(), grab->y(),
                                               kWidth, kHeight),
            "");
  for (int k = 1; k <= 5; ++k)
    EXPECT_EQ(session.placement().dragGizmo(grab->x(), grab->y() - 5.0f * k), "");
  session.placement().endGizmoDrag();
  const nlohmann::json* centre = session.document().find("obstacles.0.box.center");
  ASSERT_TRUE(centre);
  EXPECT_NEAR((*centre)[1].get<double>(), 25.0 * g->metresPerPixel(), 1e-6);
  EXPECT_EQ((*centre)[0], 0.0);
  ASSERT_TRUE(session.document().undo());
  EXPECT_EQ(session.document().find("obstacles.0.box.center")->at(1), 0.0);
  EXPECT_FALSE(session.document().canUndo()) << "the five moves were one step";

  ASSERT_EQ(session.placement().beginGizmoDrag(GizmoHandle::TranslateY, grab->x(), grab->y(),
                                               kWidth, kHeight),
            "");
  ASSERT_EQ(session.document().removeValue("obstacles.0"), "");
  EXPECT_NE(
      session.placement().dragGizmo(grab->x(), grab->y() - 10.0f).find("no longer in the scene"),
      std::string::npos);
  session.tick(0.0);  // the next frame lets go of it
  EXPECT_EQ(session.placement().activeObject().kind, EditorObject::Kind::None);
  EXPECT_EQ(session.placement().draggedHandle(), GizmoHandle::None);
}

// A moving obstacle's gizmo sits where the viewport shows it at the timeline's time, and a drag
// there moves it by what was dragged: along the world axis while its motion only translates it,
// and the rest pose by R^T (the drag) once the motion has turned it.
TEST(EditorSessionGizmo, AMovingObstacleIsMovedWhereItIsShown) {
  EditorSession session("");
  nlohmann::json doc = EditorDocument::defaultSceneDocument();  // dt 0.01
  doc["obstacles"] =
      nlohmann::json::parse(R"([{"box": {"center": [0, 0, 0], "size": [0.4, 0.4, 0.4]},
      "friction": 0.3, "motion": {"keyframes": [{"time": 0.0, "offset": [0, 0, 0]},
                                               {"time": 0.4, "offset": [0.4, 0, 0]}]}}])");
  session.newDocument(doc);
  ASSERT_EQ(session.placement().setActiveObject("obstacles.0"), "");
  session.camera() = frontCamera();
  session.playback().scrub(20, session.timeline().frames());  // t = 0.2 s: offset (0.2, 0, 0)
  const auto g = session.placement().gizmo(kWidth, kHeight);
  ASSERT_TRUE(g);
  EXPECT_NEAR(g->origin().x(), 0.2f, 1e-6f);
  EXPECT_NEAR(g->origin().y(), 0.0f, 1e-6f);
  const auto grab = g->grabPixel(GizmoHandle::TranslateY);
  ASSERT_TRUE(grab);
  ASSERT_EQ(session.placement().beginGizmoDrag(GizmoHandle::TranslateY, grab->x(), grab->y(),
                                               kWidth, kHeight),
            "");
  ASSERT_EQ(session.placement().dragGizmo(grab->x(), grab->y() - 20.0f), "");
  session.placement().endGizmoDrag();
  const nlohmann::json* centre = session.document().find("obstacles.0.box.center");
  ASSERT_TRUE(centre);
  EXPECT_NEAR((*centre)[1].get<double>(), 20.0 * g->metresPerPixel(), 1e-6);
  EXPECT_EQ((*centre)[0], 0.0) << "the rest pose moves by the drag, not to where it is shown";

  // Turning about y at 90 degrees per second: at t = 1 s (frame 100) R is a quarter turn, so a
  // drag along world +x moves the rest pose along R^T x = +z.
  doc["obstacles"][0]["motion"] = nlohmann::json::parse(
      R"({"rotate": {"center": [0, 0, 0], "axis": [0, 1, 0], "degrees_per_second": 90.0}})");
  session.newDocument(doc);
  ASSERT_EQ(session.placement().setActiveObject("obstacles.0"), "");
  session.camera() = frontCamera();
  session.playback().scrub(100, session.timeline().frames());
  const auto turned = session.placement().gizmo(kWidth, kHeight);
  ASSERT_TRUE(turned);
  const auto grabX = turned->grabPixel(GizmoHandle::TranslateX);
  ASSERT_TRUE(grabX);
  ASSERT_EQ(session.placement().beginGizmoDrag(GizmoHandle::TranslateX, grabX->x(), grabX->y(),
                                               kWidth, kHeight),
            "");
  ASSERT_EQ(session.placement().dragGizmo(grabX->x() + 20.0f, grabX->y()), "");
  session.placement().endGizmoDrag();
  centre = session.document().find("obstacles.0.box.center");
  ASSERT_TRUE(centre);
  const double moved = 20.0 * turned->metresPerPixel();
  EXPECT_NEAR((*centre)[0].get<double>(), 0.0, 1e-9 * moved);
  EXPECT_NEAR((*centre)[2].get<double>(), moved, 1e-6) << "R^T x = z for a quarter turn about y";
  // A turn about a world axis is refused while the motion has it turned, and nothing changes.
  const nlohmann::json before = session.document().document();
  const auto ring = turned->grabPixel(GizmoHandle::RotateZ);
  ASSERT_TRUE(ring);
  ASSERT_EQ(session.placement().beginGizmoDrag(GizmoHandle::RotateZ, ring->x(), ring->y(), kWidth,
                                               kHeight),
            "");
  EXPECT_NE(session.placement()
                .dragGizmo(ring->x() + 15.0f, ring->y() + 15.0f)
                .find("its motion has turned it"),
            std::string::npos);
  session.placement().endGizmoDrag();
  EXPECT_EQ(session.document().document(), before);
}

}  // namespace
}  // namespace weft::editor
