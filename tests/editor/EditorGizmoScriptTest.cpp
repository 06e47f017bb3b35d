// Placing things in the viewport, driven by scripts through the real binary (headless through
// OSMesa) and checked through state: the gizmo dragging an obstacle along one axis (one undo
// step, the cache going stale), moving a cloth by its transform and turning a box; Ctrl+click
// choosing the object at a pixel; the viewport with the gizmo against a golden image; and
// keyframing a handle on the timeline (the cached motion follows the keys; they are saved and
// read back).

#include <Selection.h>

#include "../render/GoldenImage.h"
#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/render/Camera.h>
#include <weft/render/Image.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <weft/scene/HandleTrajectory.h>

#include <cmath>
#include <fstream>

namespace weft::test {
namespace {

Vec3 vec(const nlohmann::json& j) {
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// The hanging cloth with a sphere beside it and a box under it.
nlohmann::json clothSphereBox() {
  nlohmann::json doc = hangingClothScene(1.0, 4, 0.01, 3, 500.0);
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.2, 0.3, 0.4}}, {"radius", 0.2}}}, {"friction", 0.3}},
      {{"box",
        {{"center", {0.0, -0.2, 0.0}}, {"size", {1.2, 0.2, 0.8}}, {"rotate_deg", {0.0, 0.0, 0.0}}}},
       {"friction", 0.3}}};
  return doc;
}

TEST(EditorGizmo, DragMovesAnObstacleAlongOneAxisAsOneUndoStep) {
  TempDir dir;
  const std::string scene = writeScene(dir.file("scene.json"), clothSphereBox());
  const float distance = 2.5f;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", scene}},
       {{"simulate", true}},
       {{"gizmo", "obstacles.0"}},
       // Looking along -Z at the sphere's centre: X is right on screen.
       {{"camera",
         {{"yaw", 0}, {"pitch", 0}, {"distance", distance}, {"target", {0.2, 0.3, 0.4}}}}},
       {{"frames", 1}},
       {{"write_state", dir.file("before.json")}},
       // 40 px right and 12 px down: only the motion along X's image counts.
       {{"gizmo_drag", "translate_x"}, {"by", {40, 12}}, {"steps", 4}},
       {{"write_state", dir.file("moved.json")}},
       {{"gizmo_drag", "rotate_x"}, {"by", {0, 10}}, {"expect_error", "no rotate_x handle"}},
       {{"undo", true}},
       {{"write_state", dir.file("undone.json")}},
       // The cloth moves by its mesh.transform; its gizmo sits at the centre of its bounds,
       // (0, 1, 0), here the camera's target.
       {{"gizmo", "cloths.0"}},
       {{"camera",
         {{"yaw", 0}, {"pitch", 0}, {"distance", distance}, {"target", {0.0, 1.0, 0.0}}}}},
       {{"frames", 1}},
       {{"gizmo_drag", "translate_y"}, {"by", {0, -20}}},
       {{"write_state", dir.file("cloth.json")}},
       // The box turns: from the top (-Z up on screen), a quarter turn counter-clockwise
       // about +Y, which points at the camera.
       {{"gizmo", "obstacles.1"}},
       {{"camera", {{"yaw", 0}, {"pitch", 90}, {"distance", 3.0}, {"target", {0.0, -0.2, 0.0}}}}},
       {{"frames", 1}},
       {{"gizmo_drag", "rotate_y"},
        {"from_centre", {70.71068, -70.71068}},
        {"by", {-141.42136, 0}},
        {"steps", 6}},
       {{"write_state", dir.file("turned.json")}},
       {{"gizmo", "cloths.0.attachments.0"}, {"expect_error", "fixed attachment"}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const nlohmann::json before = readJson(dir.file("before.json"));
  EXPECT_EQ(before["active_object"], "obstacles.0");
  EXPECT_FALSE(before["cache_stale"]);
  ASSERT_TRUE(before["gizmo"].is_object());
  EXPECT_FALSE(before["gizmo"]["rotates"]) << "a sphere has no rings";
  const int height = before["viewport"][1];
  // One pixel at the sphere centre's depth (the camera's target), in metres.
  const double metresPerPixel =
      2.0 * distance * std::tan(render::Camera().fovYDeg * M_PI / 360.0) / height;

  const nlohmann::json moved = readJson(dir.file("moved.json"));
  const Vec3 centre = vec(moved["document"]["obstacles"][0]["sphere"]["center"]);
  EXPECT_NEAR(centre.x(), 0.2 + 40 * metresPerPixel, 1e-5 * 40 * metresPerPixel);
  EXPECT_EQ(centre.y(), 0.3) << "along X only";
  EXPECT_EQ(centre.z(), 0.4) << "along X only";
  EXPECT_TRUE(moved["cache_stale"]) << "moving an obstacle changes the motion";
  EXPECT_EQ(moved["gizmo"]["dragging"], "none") << "released";
  EXPECT_EQ(vec(moved["gizmo"]["origin"]).x(), float(centre.x())) << "the gizmo follows the sphere";

  // One undo step takes the whole drag back, and the cache is current again.
  const nlohmann::json undone = readJson(dir.file("undone.json"));
  EXPECT_EQ(undone["document"]["obstacles"][0]["sphere"]["center"],
            nlohmann::json::array({0.2, 0.3, 0.4}));
  EXPECT_FALSE(undone["can_undo"]);
  EXPECT_FALSE(undone["dirty"]);
  EXPECT_FALSE(undone["cache_stale"]);

  const nlohmann::json cloth = readJson(dir.file("cloth.json"));
  EXPECT_TRUE(cloth["gizmo"]["rotates"]);
  const nlohmann::json& transform = cloth["document"]["cloths"][0]["mesh"]["transform"];
  EXPECT_EQ(transform["translate"][0], 0.0);
  EXPECT_NEAR(transform["translate"][1].get<double>(), 1.0 + 20 * metresPerPixel,
              1e-5 * 20 * metresPerPixel);
  EXPECT_EQ(transform["translate"][2], 0.0);
  EXPECT_EQ(transform["rotate_deg"], nlohmann::json::array({90.0, 0.0, 0.0}));

  const nlohmann::json turned = readJson(dir.file("turned.json"));
  const nlohmann::json& box = turned["document"]["obstacles"][1]["box"];
  EXPECT_EQ(box["center"], nlohmann::json::array({0.0, -0.2, 0.0}));
  EXPECT_NEAR(box["rotate_deg"][1].get<double>(), 90.0, 1e-3);
  EXPECT_EQ(box["rotate_deg"][0], 0.0);
  EXPECT_EQ(box["rotate_deg"][2], 0.0);
  EXPECT_TRUE(turned["gizmo"]["rotates"]);
}

// Ctrl+click ("click_object") on known pixels of a front view: the sphere, the cloth and the box
// each become what the gizmo places; a click on empty space takes the gizmo off (and fails the
// script unless "must_hit" is false). The pixels come from the camera the script sets, in the
// viewport whose size a first run reports.
TEST(EditorGizmo, CtrlClickPicksTheObjectUnderThePixel) {
  TempDir dir;
  const std::string scene = writeScene(dir.file("scene.json"), clothSphereBox());
  const nlohmann::json view = {
      {"yaw", 0}, {"pitch", 0}, {"distance", 4.0}, {"target", {0.0, 0.5, 0.0}}};
  const ProcessResult sized = runEditor(
      dir, {{{"open", scene}}, {{"frames", 1}}, {{"write_state", dir.file("size.json")}}});
  ASSERT_EQ(sized.exitCode, 0) << sized.err;
  const nlohmann::json viewport = readJson(dir.file("size.json"))["viewport"];
  const int width = viewport[0], height = viewport[1];
  render::Camera camera;
  camera.distance = 4.0f;
  camera.target = render::Vec3f(0.0f, 0.5f, 0.0f);
  auto pixel = [&](float x, float y, float z) {
    const auto p = editor::projectToPixel(camera, Eigen::Vector3f(x, y, z), width, height);
    EXPECT_TRUE(p.has_value());
    const Eigen::Vector2f at = p.value_or(Eigen::Vector2f::Zero());
    return nlohmann::json::array({at.x(), at.y()});
  };
  const ProcessResult r = runEditor(
      dir,
      {{{"open", scene}},
       {{"camera", view}},
       {{"frames", 1}},
       {{"click_object", pixel(0.2f, 0.3f, 0.4f)}},  // the sphere's centre
       {{"expect", {{"active_object", "obstacles.0"}}}},
       {{"click_object", pixel(-0.3f, 1.2f, 0.0f)}},
       {{"expect", {{"active_object", "cloths.0"}}}},
       {{"click_object", pixel(-0.4f, -0.2f, 0.4f)}},  // the box's front face
       {{"write_state", dir.file("box.json")}},
       {{"click_object", pixel(-1.2f, 1.6f, 0.0f)}, {"must_hit", false}},
       {{"write_state", dir.file("nothing.json")}},
       {{"gizmo", "cloths.0"}},
       {{"click_object", pixel(-1.2f, 1.6f, 0.0f)}, {"expect_error", "meets no obstacle or cloth"}},
       {{"expect", {{"active_object", ""}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json box = readJson(dir.file("box.json"));
  EXPECT_EQ(box["active_object"], "obstacles.1");
  ASSERT_TRUE(box["gizmo"].is_object());
  EXPECT_EQ(vec(box["gizmo"]["origin"]), Vec3(0.0, float(-0.2), 0.0)) << "at the box's centre";
  EXPECT_EQ(box["message"], "gizmo on obstacles.1");
  const nlohmann::json nothing = readJson(dir.file("nothing.json"));
  EXPECT_EQ(nothing["active_object"], "");
  EXPECT_TRUE(nothing["gizmo"].is_null());
  EXPECT_EQ(nothing["message"], "nothing there: gizmo off");
}

// The golden viewport with the gizmo: the hanging cloth, the sphere and the box, the box's
// gizmo (arrows and rings, drawn over the picture) after a drag of its Y arrow, from a fixed
// camera; the window is 700x420, so the viewport is 320 px wide. The screenshot is the window's
// viewport as drawn ("overlays"), which the plain viewport screenshot leaves out. Tolerance: the
// render tests' default (a pixel may differ by 16/255 per channel, within 1 pixel; at most
// 0.25 % of the pixels beyond that). Regenerate on purpose with
// `weft_tests_editor --bless --gtest_filter=EditorGizmo.ViewportMatchesGolden` and look at it.
TEST(EditorGizmo, ViewportMatchesGolden) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", writeScene(dir.file("scene.json"), clothSphereBox())}},
       {{"gizmo", "obstacles.1"}},
       {{"camera", {{"yaw", 35}, {"pitch", 20}, {"distance", 4.4}, {"target", {0.0, 0.4, 0.1}}}}},
       {{"frames", 1}},
       {{"gizmo_drag", "translate_y"}, {"by", {0, -20}}},
       {{"frames", 2}},
       {{"screenshot", dir.file("viewport.png")}, {"overlays", true}},
       {{"write_state", dir.file("state.json")}}},
      "700x420");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json state = readJson(dir.file("state.json"));
  EXPECT_GT(state["document"]["obstacles"][1]["box"]["center"][1].get<double>(), -0.2)
      << "the box went up";
  const render::Image image = render::readPng(dir.file("viewport.png"));
  EXPECT_EQ(image.width, state["viewport"][0].get<int>());
  EXPECT_EQ(image.height, state["viewport"][1].get<int>());
  EXPECT_TRUE(matchesGolden("editor_viewport_gizmo", image));
}

// A handle made from a selection, keyed at two frames (once dragged with the gizmo, once typed),
// simulated: the cached handle vertex follows the piecewise-linear path through the keys (within
// what its spring lets it lag). Key edits are undoable and make the cache stale; the keys are
// saved with the scene and come back when it is opened.
TEST(EditorKeys, HandleFollowsItsKeysAndTheyAreSaved) {
  TempDir dir;
  const nlohmann::json doc = hangingClothScene(1.0, 4, 0.01, 30, 500.0);
  const std::string scene = writeScene(dir.file("hang.json"), doc);
  const int node = 2;  // the middle of the top edge, at (0, 1.5, 0)
  const std::string handle = "cloths.0.attachments.1";
  const double distance = 3.0;
  nlohmann::json actions = {
      {{"open", scene}},
      {{"select", {node}}},
      {{"make_handle", true}},
      {{"expect", {{"active_object", handle}, {"timeline_frames", 31}}}},
      // Stiff enough that the vertex's lag behind the path (the cloth's pull over the spring's
      // stiffness) is far below the tolerance checked: at the default 1e4 N/m it is ~2 mm.
      {{"set", handle + ".stiffness"}, {"value", 1e6}},
      {{"camera", {{"yaw", 0}, {"pitch", 0}, {"distance", distance}, {"target", {0.0, 1.0, 0.0}}}}},
      // Keys can be set before anything is simulated.
      {{"scrub", 10}},
      {{"frames", 1}},
      {{"gizmo_drag", "translate_x"}, {"by", {30, 0}}},
      {{"write_state", dir.file("dragged.json")}},
      {{"set_key", true}},
      {{"scrub", 20}},
      {{"handle_offset", {0.1, 0.15, 0.0}}},
      {{"expect", {{"key_pending", true}}}},
      {{"set_key", true}},
      {{"expect", {{"key_pending", false}, {"dirty", true}}}},
      {{"jump_key", -1}},
      {{"expect", {{"frame", 10}}}},
      {{"jump_key", -1}},
      {{"expect", {{"frame", 0}}}},
      {{"jump_key", -1}, {"expect_error", "no key before"}},
      {{"jump_key", 1}},
      {{"expect", {{"frame", 10}}}},
      {{"simulate", true}},
  };
  for (int k : {5, 10, 15, 20, 25}) {
    actions.push_back({{"scrub", k}});
    actions.push_back({{"select", {node}}});  // the inspector shows the handle vertex
    actions.push_back({{"write_state", dir.file("state-" + std::to_string(k) + ".json")}});
  }
  for (const nlohmann::json& a : nlohmann::json::array({
           // A new key: undoable, and the cache goes stale until undone.
           {{"scrub", 25}},
           {{"handle_offset", {0.0, 0.0, 0.2}}},
           {{"set_key", true}},
           {{"write_state", dir.file("fourth.json")}},
           {{"undo", true}},
           {{"write_state", dir.file("undone.json")}},
           {{"delete_key", true}, {"expect_error", "no key at this frame"}},
           {{"scrub", 20}},
           {{"delete_key", true}},
           {{"write_state", dir.file("deleted.json")}},
           {{"undo", true}},
           {{"save", true}},
           {{"open", scene}},
           {{"expect", {{"active_object", ""}}}},
           {{"gizmo", handle}},
           {{"write_state", dir.file("reopened.json")}},
       }))
    actions.push_back(a);
  const ProcessResult r = runEditor(dir, actions);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  // The drag moved the offset along X only, by the pixels at the handle's depth.
  const nlohmann::json dragged = readJson(dir.file("dragged.json"));
  EXPECT_TRUE(dragged["key_pending"]);
  EXPECT_EQ(dragged["frame"], 10);
  EXPECT_EQ(dragged["keys"].size(), 1u) << "a drag is not a key yet";
  const double metresPerPixel = 2.0 * distance * std::tan(render::Camera().fovYDeg * M_PI / 360.0) /
                                dragged["viewport"][1].get<int>();
  const Vec3 dragOffset = vec(dragged["handle_offset"]);
  EXPECT_NEAR(dragOffset.x(), 30 * metresPerPixel, 1e-5 * 30 * metresPerPixel);
  EXPECT_EQ(dragOffset.y(), 0.0);
  EXPECT_EQ(dragOffset.z(), 0.0);

  // The keys as the editor wrote them: the creation key at 0, the dragged one, the typed one.
  HandleTrajectory path;
  path.kind = HandleTrajectory::Kind::Keyframes;
  path.times = {0.0, 0.1, 0.2};
  path.offsets = {Vec3::Zero(), dragOffset, Vec3(0.1, 0.15, 0.0)};
  const Vec3 rest = parse(doc).cloths[0].mesh.vertices.row(node).transpose();
  for (int k : {5, 10, 15, 20, 25}) {
    SCOPED_TRACE("state " + std::to_string(k));
    const nlohmann::json state = readJson(dir.file("state-" + std::to_string(k) + ".json"));
    EXPECT_FALSE(state["cache_stale"]);
    ASSERT_EQ(state["keys"].size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(state["keys"][i]["time"].get<double>(), path.times[i]);
      EXPECT_EQ(vec(state["keys"][i]["offset"]), path.offsets[i]);
    }
    ASSERT_TRUE(state["inspector"].is_object());
    EXPECT_EQ(state["inspector"]["state"], k);
    const Vec3 expected = rest + path.offset(k * 0.01);
    // The handle is a spring (1e6 N/m) pulling the vertex to the path: it lags by the cloth's
    // pull over the stiffness, tens of micrometres here.
    EXPECT_LT((vec(state["inspector"]["position"]) - expected).norm(), 1e-4)
        << vec(state["inspector"]["position"]).transpose() << " vs " << expected.transpose();
  }

  const nlohmann::json fourth = readJson(dir.file("fourth.json"));
  EXPECT_EQ(fourth["keys"].size(), 4u);
  EXPECT_TRUE(fourth["cache_stale"]) << "a key changes the motion";
  const nlohmann::json undone = readJson(dir.file("undone.json"));
  EXPECT_EQ(undone["keys"].size(), 3u);
  EXPECT_FALSE(undone["cache_stale"]);
  const nlohmann::json deleted = readJson(dir.file("deleted.json"));
  ASSERT_EQ(deleted["keys"].size(), 2u);
  EXPECT_EQ(deleted["keys"][1]["time"], 0.1);

  // Saved with the scene and read back.
  const nlohmann::json saved = readJson(scene);
  const nlohmann::json& attachment = saved["cloths"][0]["attachments"][1];
  EXPECT_EQ(attachment["kind"], "handle");
  EXPECT_EQ(attachment["vertices"], nlohmann::json::array({node}));
  ASSERT_EQ(attachment["trajectory"]["keyframes"].size(), 3u);
  EXPECT_EQ(attachment["trajectory"]["keyframes"][2]["offset"],
            nlohmann::json::array({0.1, 0.15, 0.0}));
  const nlohmann::json reopened = readJson(dir.file("reopened.json"));
  EXPECT_EQ(reopened["dirty"], false);
  EXPECT_EQ(reopened["keys"], readJson(dir.file("state-5.json"))["keys"]);
}

}  // namespace
}  // namespace weft::test
