// The editor's mouse and keyboard handling, driven by scripted raw input (mouse_move,
// mouse_drag, mouse_click, scroll, key, type...) through Dear ImGui in the real binary, headless
// through OSMesa: EditorApp's own input code runs, not the session methods behind it. Each test
// compares what the input did with what the matching script action (which calls the session
// directly) does, or with the numbers EditorApp's handling is written to produce.

#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/render/Camera.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace weft::test {
namespace {

namespace fs = std::filesystem;

// 800x600: the viewport is the 420 px right of the 380 px panel, between the menu bar and the
// 150 px timeline.
ProcessResult runInput(const TempDir& dir, const nlohmann::json& actions) {
  return runEditor(dir, actions, "800x600");
}

// A point in viewport pixels, as raw-input actions take it.
nlohmann::json inView(double x, double y) {
  return {{"viewport", {x, y}}};
}

Eigen::Vector3f vec3f(const nlohmann::json& j) {
  return Eigen::Vector3f(j[0].get<float>(), j[1].get<float>(), j[2].get<float>());
}

// The hanging cloth (1 m, 4x4 quads, top edge pinned at y = 1.5) seen from the front.
const nlohmann::json kFront = {
    {"yaw", 0}, {"pitch", 0}, {"distance", 3.0}, {"target", {0.0, 1.0, 0.0}}};

std::string hangingScene(const TempDir& dir, int steps = 5) {
  return writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, steps, 500.0));
}

TEST(EditorInput, RightDragOrbitsMiddleDragPansWheelZooms) {
  TempDir dir;
  const ProcessResult r = runInput(
      dir,
      {{{"open", hangingScene(dir)}},
       {{"camera", {{"yaw", 10}, {"pitch", 20}, {"distance", 3.0}, {"target", {0.0, 1.0, 0.0}}}}},
       {{"frames", 1}},
       // 80 px right and 30 px up, in 8 moves: each past ImGui's 6 px drag threshold.
       {{"mouse_drag", "right"},
        {"from", inView(200, 200)},
        {"to", inView(280, 170)},
        {"steps", 8}},
       {{"write_state", dir.file("orbit.json")}},
       {{"camera", {{"yaw", 0}, {"pitch", 0}}}},
       {{"frames", 1}},
       {{"mouse_drag", "middle"},
        {"from", inView(200, 200)},
        {"to", inView(240, 180)},
        {"steps", 4}},
       {{"write_state", dir.file("pan.json")}},
       {{"scroll", 2}, {"at", inView(210, 200)}},
       {{"write_state", dir.file("zoom-in.json")}},
       {{"scroll", -1}},
       {{"write_state", dir.file("zoom-out.json")}},
       // Over the left panel the wheel scrolls the panel, not the view.
       {{"scroll", 3}, {"at", {100, 300}}},
       {{"write_state", dir.file("panel.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  // EditorApp: orbit(-dx * 0.4, dy * 0.4) degrees.
  const nlohmann::json orbit = readJson(dir.file("orbit.json"))["camera"];
  EXPECT_NEAR(orbit["yaw"].get<double>(), 10.0 - 80 * 0.4, 1e-4);
  EXPECT_NEAR(orbit["pitch"].get<double>(), 20.0 - 30 * 0.4, 1e-4);
  EXPECT_EQ(orbit["distance"], 3.0) << "an orbit keeps the distance";

  // Pan: the target moves against the mouse by the pixel's size at the target's depth, so the
  // scene follows the mouse.
  const nlohmann::json pan = readJson(dir.file("pan.json"));
  const int height = pan["viewport"][1];
  render::Camera camera;  // yaw 0, pitch 0: right is +X, up is +Y
  const float metresPerPixel =
      3.0f * 2.0f * std::tan(camera.fovYDeg * 3.14159265f / 360.0f) / float(height);
  const Eigen::Vector3f target = vec3f(pan["camera"]["target"]);
  EXPECT_NEAR(target.x(), -40 * metresPerPixel, 1e-5);
  EXPECT_NEAR(target.y(), 1.0 - 20 * metresPerPixel, 1e-5);
  EXPECT_NEAR(target.z(), 0.0, 1e-6);
  EXPECT_EQ(pan["camera"]["yaw"], 0.0) << "a pan does not turn the camera";

  // The wheel: distance times 0.9 per notch towards the scene.
  const double zoomIn = readJson(dir.file("zoom-in.json"))["camera"]["distance"];
  EXPECT_NEAR(zoomIn, 3.0 * 0.9 * 0.9, 1e-5);
  const double zoomOut = readJson(dir.file("zoom-out.json"))["camera"]["distance"];
  EXPECT_NEAR(zoomOut, zoomIn / 0.9, 1e-5);
  EXPECT_EQ(readJson(dir.file("panel.json"))["camera"]["distance"], zoomOut);
}

// A slow drag (a pixel a frame) turns and pans as far as a fast one: the camera follows from the
// first pixel. It used to wait for ImGui's 6 px drag threshold and drop the motion before it.
TEST(EditorInput, SlowDragsOrbitAndPanFromTheFirstPixel) {
  TempDir dir;
  const ProcessResult r =
      runInput(dir, {{{"open", hangingScene(dir)}},
                     {{"camera", kFront}},
                     {{"frames", 1}},
                     {{"mouse_drag", "right"},
                      {"from", inView(200, 200)},
                      {"to", inView(220, 200)},
                      {"steps", 20}},
                     {{"write_state", dir.file("orbit.json")}},
                     {{"camera", kFront}},
                     {{"frames", 1}},
                     {{"mouse_drag", "middle"},
                      {"from", inView(200, 200)},
                      {"to", inView(200, 210)},
                      {"steps", 10}},
                     {{"write_state", dir.file("pan.json")}},
                     // A move and a press in one frame, then the release: no drag, so no turn.
                     {{"camera", kFront}},
                     {{"mouse_move", inView(60, 300)}},
                     {{"mouse_press", "right"}, {"at", inView(200, 200)}},
                     {{"mouse_release", "right"}},
                     {{"write_state", dir.file("press.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NEAR(readJson(dir.file("orbit.json"))["camera"]["yaw"].get<double>(), -20 * 0.4, 1e-4);
  const nlohmann::json pan = readJson(dir.file("pan.json"));
  const float metresPerPixel = 3.0f * 2.0f *
                               std::tan(render::Camera().fovYDeg * 3.14159265f / 360.0f) /
                               pan["viewport"][1].get<float>();
  EXPECT_NEAR(pan["camera"]["target"][1].get<double>(), 1.0 + 10 * metresPerPixel, 1e-5);
  EXPECT_EQ(readJson(dir.file("press.json"))["camera"]["yaw"], 0.0);
}

TEST(EditorInput, ClickAndBoxDragSelectWhatTheActionsSelect) {
  TempDir dir;
  const ProcessResult r =
      runInput(dir, {{{"open", hangingScene(dir)}},
                     {{"camera", kFront}},
                     {{"frames", 1}},
                     {{"click", {200, 180}}},
                     {{"write_state", dir.file("click-action.json")}},
                     {{"clear_selection", true}},
                     {{"mouse_click", inView(200, 180)}},
                     {{"write_state", dir.file("click-mouse.json")}},
                     // Shift adds the vertex under a second click.
                     {{"mouse_click", inView(250, 120)}, {"modifiers", "shift"}},
                     {{"write_state", dir.file("shift-click.json")}},
                     {{"clear_selection", true}},
                     {{"box_select", {150, 60, 320, 220}}},
                     {{"write_state", dir.file("box-action.json")}},
                     {{"clear_selection", true}},
                     {{"mouse_drag", "left"}, {"from", inView(150, 60)}, {"to", inView(320, 220)}},
                     {{"write_state", dir.file("box-mouse.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const nlohmann::json byAction = readJson(dir.file("click-action.json"));
  const nlohmann::json byMouse = readJson(dir.file("click-mouse.json"));
  ASSERT_EQ(byAction["selected"].size(), 1u) << "the pixel lies on the cloth";
  EXPECT_EQ(byMouse["selected"], byAction["selected"]);
  EXPECT_EQ(byMouse["focus"], byAction["focus"]) << "the clicked vertex is the inspected one";

  const nlohmann::json added = readJson(dir.file("shift-click.json"));
  ASSERT_EQ(added["selected"].size(), 2u);
  EXPECT_TRUE(added["selected"][0] == byAction["selected"][0] ||
              added["selected"][1] == byAction["selected"][0])
      << "Shift keeps the first vertex: " << added["selected"];
  EXPECT_EQ(added["focus"], added["selected"][0] == byAction["selected"][0] ? added["selected"][1]
                                                                            : added["selected"][0])
      << "the added vertex is the inspected one";

  const nlohmann::json boxAction = readJson(dir.file("box-action.json"));
  const nlohmann::json boxMouse = readJson(dir.file("box-mouse.json"));
  EXPECT_GT(boxAction["selected"].size(), 1u);
  EXPECT_LT(boxAction["selected"].size(), 25u) << "the box holds part of the cloth";
  EXPECT_EQ(boxMouse["selected"], boxAction["selected"]);
}

// The hanging cloth with a sphere beside it.
std::string clothAndSphere(const TempDir& dir) {
  nlohmann::json doc = hangingClothScene(1.0, 4, 0.01, 3, 500.0);
  doc["obstacles"] = {
      {{"sphere", {{"center", {0.2, 0.3, 0.4}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  return writeScene(dir.file("sphere.json"), doc);
}

TEST(EditorInput, GizmoPressAndDragMovesTheObjectAsGizmoDragDoes) {
  TempDir dir;
  // Looking at the sphere's centre: the gizmo's centre is the viewport's, X's arrow points right.
  const nlohmann::json view = {
      {"yaw", 0}, {"pitch", 0}, {"distance", 2.5}, {"target", {0.2, 0.3, 0.4}}};
  const ProcessResult sized =
      runInput(dir, {{{"frames", 1}}, {{"write_state", dir.file("size.json")}}});
  ASSERT_EQ(sized.exitCode, 0) << sized.err;
  const nlohmann::json viewport = readJson(dir.file("size.json"))["viewport"];
  const double cx = viewport[0].get<int>() / 2.0, cy = viewport[1].get<int>() / 2.0;
  const ProcessResult r = runInput(
      dir,
      {{{"open", clothAndSphere(dir)}},
       {{"gizmo", "obstacles.0"}},
       {{"camera", view}},
       {{"frames", 1}},
       {{"gizmo_drag", "translate_x"}, {"from_centre", {50, 0}}, {"by", {40, 12}}, {"steps", 4}},
       {{"write_state", dir.file("action.json")}},
       {{"undo", true}},
       {{"mouse_drag", "left"},
        {"from", inView(cx + 50, cy)},
        {"to", inView(cx + 90, cy + 12)},
        {"steps", 4}},
       {{"write_state", dir.file("mouse.json")}},
       {{"key", "ctrl+z"}},
       {{"write_state", dir.file("undone.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json byAction = readJson(dir.file("action.json"));
  const nlohmann::json byMouse = readJson(dir.file("mouse.json"));
  const Eigen::Vector3f expected = vec3f(byAction["document"]["obstacles"][0]["sphere"]["center"]);
  const Eigen::Vector3f moved = vec3f(byMouse["document"]["obstacles"][0]["sphere"]["center"]);
  EXPECT_GT(expected.x(), 0.25f) << "the action moved the sphere along X";
  EXPECT_NEAR((moved - expected).norm(), 0.0f, 1e-6f)
      << moved.transpose() << " vs " << expected.transpose();
  EXPECT_EQ(byMouse["gizmo"]["dragging"], "none") << "released";
  EXPECT_TRUE(byMouse["cache_stale"].is_boolean());
  // The whole mouse drag is one undo step.
  const nlohmann::json undone = readJson(dir.file("undone.json"));
  EXPECT_EQ(undone["document"]["obstacles"][0]["sphere"]["center"],
            nlohmann::json::array({0.2, 0.3, 0.4}));
  EXPECT_FALSE(undone["can_undo"]);
}

// Ctrl+click picks the object under the mouse for the gizmo, as click_object does; Ctrl+click on
// empty space takes the gizmo off.
TEST(EditorInput, CtrlClickPicksTheObjectForTheGizmo) {
  TempDir dir;
  const nlohmann::json view = {
      {"yaw", 0}, {"pitch", 0}, {"distance", 2.5}, {"target", {0.2, 0.3, 0.4}}};
  const ProcessResult r = runInput(dir, {{{"open", clothAndSphere(dir)}},
                                         {{"camera", view}},
                                         {{"frames", 1}},
                                         {{"write_state", dir.file("size.json")}},
                                         {{"mouse_click", inView(210, 215)}, {"modifiers", "ctrl"}},
                                         {{"write_state", dir.file("sphere.json")}},
                                         {{"mouse_click", inView(10, 420)}, {"modifiers", "ctrl"}},
                                         {{"write_state", dir.file("nothing.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  // The sphere's centre is the viewport's centre; the click lands within a few pixels of it.
  const nlohmann::json viewport = readJson(dir.file("size.json"))["viewport"];
  ASSERT_LT(std::abs(viewport[0].get<int>() / 2 - 210), 20);
  ASSERT_LT(std::abs(viewport[1].get<int>() / 2 - 215), 20);
  const nlohmann::json sphere = readJson(dir.file("sphere.json"));
  EXPECT_EQ(sphere["active_object"], "obstacles.0");
  EXPECT_TRUE(sphere["selected"].empty()) << "Ctrl+click picks an object, not a vertex";
  const nlohmann::json nothing = readJson(dir.file("nothing.json"));
  EXPECT_EQ(nothing["active_object"], "");
  EXPECT_EQ(nothing["message"], "nothing there: gizmo off");
}

// Targets at two vertices, dragged in the view plane with Alt + left drag: as far as the
// drag_targets action moves them for the same pixels, and one undo step.
TEST(EditorInput, AltDragMovesTargetsAsDragTargetsDoes) {
  TempDir dir;
  const ProcessResult r = runInput(
      dir, {{{"open", hangingScene(dir)}},
            {{"camera", kFront}},
            {{"select", {6, 7}}},
            {{"set_targets", true}},
            {{"frames", 1}},
            {{"drag_targets", {30, -20}}},
            {{"write_state", dir.file("action.json")}},
            {{"undo", true}},
            {{"write_state", dir.file("before.json")}},
            // Pressed away from the cloth: with Alt held, anywhere in the viewport drags targets.
            {{"mouse_drag", "left"},
             {"from", inView(60, 300)},
             {"to", inView(90, 280)},
             {"steps", 5},
             {"modifiers", "alt"}},
            {{"write_state", dir.file("mouse.json")}},
            {{"key", "ctrl+z"}},
            {{"write_state", dir.file("undone.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json before = readJson(dir.file("before.json"))["targets"];
  const nlohmann::json byAction = readJson(dir.file("action.json"))["targets"];
  const nlohmann::json byMouse = readJson(dir.file("mouse.json"));
  ASSERT_EQ(byAction.size(), 2u);
  for (const char* node : {"6", "7"}) {
    const Eigen::Vector3f from = vec3f(before[node]), expected = vec3f(byAction[node]),
                          moved = vec3f(byMouse["targets"][node]);
    EXPECT_GT((expected - from).norm(), 0.05f) << "the action moved target " << node;
    EXPECT_NEAR((moved - expected).norm(), 0.0f, 1e-5f) << "target " << node;
  }
  EXPECT_EQ(byMouse["selected"], nlohmann::json::array({6, 7}))
      << "an Alt drag does not box-select";
  EXPECT_EQ(readJson(dir.file("undone.json"))["targets"], before) << "one undo step";
}

// The drag starts where the button went down: a move that reaches the viewport in the same
// frame as the press (a quick move and click) is not part of it. It used to be, through that
// frame's mouse delta, so Alt+click moved the targets by the way the mouse came.
TEST(EditorInput, AltClickWithoutDraggingLeavesTargetsAlone) {
  TempDir dir;
  const ProcessResult r = runInput(dir, {{{"open", hangingScene(dir)}},
                                         {{"camera", kFront}},
                                         {{"select", {6, 7}}},
                                         {{"set_targets", true}},
                                         {{"write_state", dir.file("before.json")}},
                                         {{"key_down", "alt"}},
                                         {{"mouse_move", inView(60, 300)}},
                                         {{"mouse_press", "left"}, {"at", inView(120, 250)}},
                                         {{"mouse_release", "left"}},
                                         {{"key_up", "alt"}},
                                         {{"write_state", dir.file("after.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json before = readJson(dir.file("before.json"));
  const nlohmann::json after = readJson(dir.file("after.json"));
  EXPECT_EQ(after["targets"], before["targets"]);
  EXPECT_EQ(after["document"], before["document"]);
}

TEST(EditorInput, UndoRedoAndSaveShortcutsDoWhatTheMenuDoes) {
  TempDir dir;
  const std::string scene = hangingScene(dir);
  const ProcessResult r = runInput(
      dir,
      {{{"open", scene}},
       {{"set", "cloths.0.material.stretch"}, {"value", 800.0}},
       {{"key", "ctrl+z"}},
       {{"expect",
         {{"can_redo", true},
          {"dirty", false},
          {"value", {{"path", "cloths.0.material.stretch"}, {"equals", 500.0}}}}}},
       {{"key", "ctrl+shift+z"}},
       {{"expect",
         {{"dirty", true}, {"value", {{"path", "cloths.0.material.stretch"}, {"equals", 800.0}}}}}},
       {{"key", "ctrl+z"}},
       {{"key", "ctrl+y"}},
       {{"expect",
         {{"can_redo", false},
          {"value", {{"path", "cloths.0.material.stretch"}, {"equals", 800.0}}}}}},
       // Z without Ctrl does nothing.
       {{"key", "z"}},
       {{"expect", {{"dirty", true}, {"can_redo", false}}}},
       {{"key", "ctrl+s"}},
       {{"write_state", dir.file("saved.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json state = readJson(dir.file("saved.json"));
  EXPECT_FALSE(state["dirty"]);
  EXPECT_EQ(state["message"], "saved " + scene);
  EXPECT_EQ(readJson(scene)["cloths"][0]["material"]["stretch"], 800.0) << "Ctrl+S wrote the file";
}

TEST(EditorInput, PlaybackShortcutsStepAndPlay) {
  TempDir dir;
  // 400 states of 10 ms: four seconds of playback, far longer than the frames below take.
  const ProcessResult r = runInput(dir, {{{"open", hangingScene(dir, 400)}},
                                         {{"simulate", true}},
                                         {{"scrub", 10}},
                                         {{"key", "right"}},
                                         {{"key", "right"}},
                                         {{"expect", {{"frame", 12}, {"playing", false}}}},
                                         {{"key", "left"}},
                                         {{"expect", {{"frame", 11}}}},
                                         {{"key", "space"}},
                                         {{"expect", {{"playing", true}}}},
                                         {{"key", "space"}},
                                         {{"write_state", dir.file("paused.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json paused = readJson(dir.file("paused.json"));
  EXPECT_FALSE(paused["playing"]);
  EXPECT_GE(paused["frame"].get<int>(), 11);
}

// At the last state Space plays from the first again, as the Play button does (it used to set
// playing, and playback stopped at once at the end).
TEST(EditorInput, SpaceAtTheLastStatePlaysFromTheStart) {
  TempDir dir;
  // 400 states of 10 ms: four seconds of playback, far longer than the frames below take.
  const ProcessResult r = runInput(dir, {{{"open", hangingScene(dir, 400)}},
                                         {{"simulate", true}},
                                         {{"scrub", 400}},
                                         {{"key", "space"}},
                                         {{"write_state", dir.file("replay.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json replay = readJson(dir.file("replay.json"));
  EXPECT_TRUE(replay["playing"]);
  EXPECT_LT(replay["frame"].get<int>(), 400) << "started again from state 0";
}

TEST(EditorInput, ViewAndGizmoShortcuts) {
  TempDir dir;
  const ProcessResult r = runInput(
      dir,
      {{{"open", clothAndSphere(dir)}},
       {{"camera", "auto"}},
       {{"write_state", dir.file("auto.json")}},
       {{"camera", {{"yaw", 70}, {"pitch", -30}, {"distance", 9.0}, {"target", {1.0, 2.0, 3.0}}}}},
       {{"key", "f"}},
       {{"write_state", dir.file("framed.json")}},
       {{"gizmo", "obstacles.0"}},
       {{"key", "escape"}},
       {{"expect", {{"active_object", ""}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  // F frames the scene as the "auto" view does.
  const nlohmann::json framed = readJson(dir.file("framed.json"))["camera"];
  const nlohmann::json automatic = readJson(dir.file("auto.json"))["camera"];
  EXPECT_NE(automatic["yaw"], 70.0);
  EXPECT_EQ(framed, automatic);
}

// The file dialogs from their shortcuts, typed into: Save As writes the file named, Open reads
// it back; Ctrl+I opens the import dialog. The path field takes the typing as the dialog opens
// (it used to need a click first: typing and Enter went nowhere).
TEST(EditorInput, FileDialogsTakeATypedPath) {
  TempDir dir;
  const std::string copy = dir.file("copy.json");
  const ProcessResult r =
      runInput(dir, {{{"open", hangingScene(dir)}},
                     {{"set", "time.steps"}, {"value", 9}},
                     {{"key", "ctrl+shift+s"}},
                     {{"write_state", dir.file("save-as.json")}},
                     {{"key", "ctrl+a"}},  // the current file's path is filled in: replace it
                     {{"type", copy}},
                     {{"key", "enter"}},
                     {{"expect", {{"file", copy}, {"dirty", false}, {"dialog", nullptr}}}},
                     {{"new", true}},
                     {{"key", "ctrl+o"}},
                     {{"key", "ctrl+a"}},
                     {{"type", copy}},
                     {{"key", "enter"}},
                     {{"expect",
                       {{"file", copy},
                        {"dialog", nullptr},
                        {"value", {{"path", "time.steps"}, {"equals", 9}}}}}},
                     {{"key", "ctrl+i"}},
                     {{"write_state", dir.file("import.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(readJson(dir.file("save-as.json"))["dialog"]["title"], "Save scene as");
  EXPECT_EQ(readJson(copy)["time"]["steps"], 9);
  EXPECT_TRUE(readJson(dir.file("import.json"))["dialog"].is_object());
}

// Centres of the close prompt's buttons (Save, Discard, Cancel) from its rectangle: one row at
// the bottom, laid out with Dear ImGui's default style and font (7 px per character, 4 px frame
// padding, 8 px between items and around the window).
nlohmann::json promptButton(const nlohmann::json& rect, int index) {
  const char* labels[] = {"Save", "Discard", "Cancel"};
  double x = rect[0].get<double>() + 8.0;
  for (int i = 0; i < index; ++i) x += 7.0 * std::strlen(labels[i]) + 8.0 + 8.0;
  const double width = 7.0 * std::strlen(labels[index]) + 8.0;
  const double y = rect[1].get<double>() + rect[3].get<double>() - 8.0 - 19.0 / 2.0;
  return {x + width / 2.0, y};
}

TEST(EditorInput, ClosingWithUnsavedChangesAsksFirst) {
  TempDir dir;
  const std::string scene = hangingScene(dir);
  // A first run finds where the prompt opens (it is centred, so the same in the second run).
  const ProcessResult probe = runInput(dir, {{{"open", scene}},
                                             {{"set", "time.steps"}, {"value", 7}},
                                             {{"close", true}},
                                             {{"frames", 1}},
                                             {{"write_state", dir.file("prompt.json")}}});
  ASSERT_EQ(probe.exitCode, 0) << probe.err << probe.out;
  const nlohmann::json prompt = readJson(dir.file("prompt.json"));
  EXPECT_TRUE(prompt["close_prompt"]);
  EXPECT_FALSE(prompt["close_confirmed"]) << "a dirty document does not close at once";
  ASSERT_TRUE(prompt["dialog"].is_object()) << "the prompt is a modal dialog";
  EXPECT_EQ(prompt["dialog"]["title"], "Unsaved changes");
  const nlohmann::json rect = prompt["dialog"]["rect"];

  const ProcessResult r =
      runInput(dir, {{{"open", scene}},
                     {{"set", "time.steps"}, {"value", 7}},
                     {{"close", true}},
                     {{"frames", 1}},
                     {{"mouse_click", promptButton(rect, 2)}},  // Cancel
                     {{"expect",
                       {{"close_prompt", false},
                        {"dialog", nullptr},
                        {"dirty", true},
                        {"close_confirmed", false}}}},
                     {{"key", "ctrl+q"}},  // Quit asks the same
                     {{"expect", {{"close_prompt", true}}}},
                     {{"mouse_click", promptButton(rect, 1)}},  // Discard: the editor closes
                     {{"write_state", dir.file("never.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("closed at actions.8"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir.file("never.json"))) << "nothing runs after the close";
  EXPECT_EQ(readJson(scene)["time"]["steps"], 5) << "discarded, not saved";

  // Save in the prompt saves, then closes.
  const ProcessResult saved = runInput(dir, {{{"open", scene}},
                                             {{"set", "time.steps"}, {"value", 7}},
                                             {{"key", "ctrl+q"}},
                                             {{"frames", 1}},
                                             {{"mouse_click", promptButton(rect, 0)}},
                                             {{"write_state", dir.file("never.json")}}});
  ASSERT_EQ(saved.exitCode, 0) << saved.err << saved.out;
  EXPECT_NE(saved.out.find("closed at actions.4"), std::string::npos) << saved.out;
  EXPECT_EQ(readJson(scene)["time"]["steps"], 7);
}

// A modal dialog blocks the menus, and so their shortcuts: with the close prompt open, Ctrl+Z,
// Ctrl+N and the arrow keys leave the document and the timeline alone (they used to undo the
// edit being asked about, or replace the document behind the prompt).
TEST(EditorInput, ShortcutsWaitWhileADialogIsOpen) {
  TempDir dir;
  const ProcessResult r = runInput(dir, {{{"open", hangingScene(dir)}},
                                         {{"simulate", true}},
                                         {{"scrub", 2}},
                                         {{"set", "cloths.0.material.stretch"}, {"value", 800.0}},
                                         {{"close", true}},
                                         {{"frames", 1}},
                                         {{"key", "ctrl+z"}},
                                         {{"key", "ctrl+n"}},
                                         {{"key", "right"}},
                                         {{"write_state", dir.file("state.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json state = readJson(dir.file("state.json"));
  EXPECT_EQ(state["dialog"]["title"], "Unsaved changes");
  EXPECT_EQ(state["document"]["cloths"][0]["material"]["stretch"], 800.0) << "not undone";
  EXPECT_TRUE(state["dirty"]);
  EXPECT_NE(state["file"], "") << "not replaced by a new document";
  EXPECT_EQ(state["frame"], 2);
}

// New and Open drop the document as closing does, so a dirty one asks first too. Enter is Save,
// Esc is Cancel; Save on a document without a file goes through Save As, then on with the action.
TEST(EditorInput, NewAndOpenWithUnsavedChangesAskFirst) {
  TempDir dir;
  const std::string scene = hangingScene(dir);
  const std::string copy = dir.file("untitled-saved.json");
  const ProcessResult r = runInput(
      dir,
      {{{"open", scene}},
       {{"set", "time.steps"}, {"value", 7}},
       {{"key", "ctrl+n"}},
       {{"frames", 1}},
       {{"expect", {{"unsaved_prompt", "new"}, {"close_prompt", false}, {"file", scene}}}},
       {{"write_state", dir.file("new-prompt.json")}},
       {{"key", "escape"}},  // Cancel: nothing happens
       {{"expect",
         {{"unsaved_prompt", nullptr}, {"dialog", nullptr}, {"file", scene}, {"dirty", true}}}},
       {{"key", "ctrl+n"}},
       {{"frames", 1}},
       {{"key", "enter"}},  // Save, then the new document
       {{"expect", {{"unsaved_prompt", nullptr}, {"file", ""}, {"dirty", false}}}},
       // An untitled document with changes, then Open: Save goes through Save As first.
       {{"set", "time.steps"}, {"value", 11}},
       {{"key", "ctrl+o"}},
       {{"key", "ctrl+a"}},
       {{"type", scene}},
       {{"key", "enter"}},
       {{"frames", 1}},
       {{"expect", {{"unsaved_prompt", "open"}, {"file", ""}}}},
       {{"key", "enter"}},
       {{"frames", 1}},
       {{"expect", {{"unsaved_prompt", nullptr}, {"file", ""}}}},
       {{"write_state", dir.file("save-as.json")}},
       {{"type", copy}},
       {{"key", "enter"}},
       {{"frames", 1}},
       {{"expect", {{"dialog", nullptr}, {"file", scene}, {"dirty", false}}}},
       {{"expect", {{"value", {{"path", "time.steps"}, {"equals", 7}}}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(readJson(dir.file("new-prompt.json"))["dialog"]["title"], "Unsaved changes");
  EXPECT_EQ(readJson(dir.file("save-as.json"))["dialog"]["title"], "Save scene as");
  EXPECT_EQ(readJson(scene)["time"]["steps"], 7) << "saved by the first prompt's Enter";
  EXPECT_EQ(readJson(copy)["time"]["steps"], 11) << "the untitled document, saved through Save As";

  // Discard (clicked) drops the changes and goes on: New replaces the document, unsaved.
  const nlohmann::json rect = readJson(dir.file("new-prompt.json"))["dialog"]["rect"];
  const ProcessResult discard =
      runInput(dir, {{{"open", scene}},
                     {{"set", "time.steps"}, {"value", 9}},
                     {{"key", "ctrl+n"}},
                     {{"frames", 1}},
                     {{"mouse_click", promptButton(rect, 1)}},
                     {{"expect", {{"unsaved_prompt", nullptr}, {"file", ""}, {"dirty", false}}}}});
  ASSERT_EQ(discard.exitCode, 0) << discard.err << discard.out;
  EXPECT_EQ(readJson(scene)["time"]["steps"], 7) << "discarded, not saved";
}

// Alt is the target-drag modifier; a chord with Alt held is not the chord without it.
TEST(EditorInput, AltChordsAreNotTheShortcutsWithoutAlt) {
  TempDir dir;
  const ProcessResult r = runInput(
      dir, {{{"open", hangingScene(dir)}},
            {{"set", "time.steps"}, {"value", 8}},
            {{"key", "ctrl+alt+z"}},
            {{"expect", {{"value", {{"path", "time.steps"}, {"equals", 8}}}, {"can_undo", true}}}},
            {{"key", "ctrl+z"}},
            {{"expect", {{"value", {{"path", "time.steps"}, {"equals", 5}}}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
}

TEST(EditorInput, QuitWithNothingUnsavedClosesAtOnce) {
  TempDir dir;
  const ProcessResult r = runInput(dir, {{{"open", hangingScene(dir)}},
                                         {{"key", "ctrl+q"}},
                                         {{"write_state", dir.file("never.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("closed at actions.1"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("script done"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir.file("never.json")));
}

}  // namespace
}  // namespace weft::test
