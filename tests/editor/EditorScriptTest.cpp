// The editor as a person would use it, driven by automation scripts through the real binary:
// headless through OSMesa (open, edit, select, pin, simulate, scrub, save, save as elsewhere,
// screenshot), the error contract of a failing action, one viewport screenshot against a golden
// image, and one smoke test of a real window under Xvfb.

#include "../render/GoldenImage.h"
#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <weft/render/Image.h>
#include <weft/scene/SceneLoader.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

namespace weft::test {
namespace {

namespace fs = std::filesystem;

// Pin groups in the Scene tab: named (a document edit), each in its own marker colour, selected
// and removed by their buttons.
TEST(EditorScript, PinGroupsAreNamedColouredSelectedAndRemoved) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hanging.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  const std::string second = "cloths.0.attachments.1";
  const ProcessResult r = runEditor(dir,
                                    {{{"open", scene}},
                                     {{"select", {20, 24}}},
                                     {{"pin", true}},
                                     {{"set", second + ".name"}, {"value", "hem"}},
                                     {{"frames", 2}},
                                     {{"write_state", dir.file("named.json")}},
                                     {{"select", nlohmann::json::array()}},
                                     {{"mouse_click", item("pins:select:" + second)}},
                                     {{"frames", 1}},
                                     {{"write_state", dir.file("selected.json")}},
                                     {{"mouse_click", item("pins:remove:cloths.0.attachments.0")}},
                                     {{"frames", 1}},
                                     {{"write_state", dir.file("removed.json")}}},
                                    "1280x1000");
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;

  const nlohmann::json named = readJson(dir.file("named.json"))["pin_groups"];
  ASSERT_EQ(named.size(), 2u) << named;
  EXPECT_EQ(named[0]["name"], "");
  EXPECT_EQ(named[0]["nodes"], nlohmann::json::array({0, 4}));
  EXPECT_EQ(named[1]["name"], "hem");
  EXPECT_EQ(named[1]["nodes"], nlohmann::json::array({20, 24}));
  EXPECT_NE(named[0]["color"], named[1]["color"]) << "each group its own colour";
  EXPECT_EQ(readJson(dir.file("selected.json"))["selected"], nlohmann::json::array({20, 24}));
  const nlohmann::json removed = readJson(dir.file("removed.json"))["pin_groups"];
  ASSERT_EQ(removed.size(), 1u) << removed;
  EXPECT_EQ(removed[0]["name"], "hem");
  EXPECT_EQ(removed[0]["attachment"], 0);
}

// A designer looking at one moment re-simulates after an edit and still looks at that moment
// (of the new run); a shorter run puts the frame at its last state.
TEST(EditorScript, ResimulatingKeepsThePlaybackFrame) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hanging.json"), hangingClothScene(1.0, 6, 0.01, 10, 500.0));
  const ProcessResult r =
      runEditor(dir, {{{"open", scene}},
                      {{"simulate", true}},
                      {{"scrub", 7}},
                      {{"set", "cloths.0.material.stretch"}, {"value", 900.0}},
                      {{"expect", {{"cache_stale", true}, {"frame", 7}}}},
                      {{"simulate", true}},
                      {{"expect", {{"cache_stale", false}, {"cache_frames", 11}, {"frame", 7}}}},
                      {{"set", "time.steps"}, {"value", 4}},
                      {{"simulate", true}},
                      {{"expect", {{"cache_frames", 5}, {"frame", 4}}}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("script done"), std::string::npos) << r.out;
}

TEST(EditorScript, SessionEditsPinsSimulatesScrubsAndSaves) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hanging.json"), hangingClothScene(1.0, 8, 0.01, 30, 500.0));
  const nlohmann::json actions = {
      {{"open", scene}},
      {{"set", "cloths.0.material.stretch"}, {"value", 800.0}},
      {{"set", "time.steps"}, {"value", 10}},
      {{"camera", "front"}},
      {{"frames", 2}},
      // The centre of the front view lies on the hanging cloth.
      {{"click", {480, 290}}},
  };
  // The click's vertex is whatever lies under the centre: recorded, then checked below.
  nlohmann::json script = actions;
  script.push_back({{"write_state", dir.file("after-click.json")}});
  script.push_back({{"select", {3, 5}}});
  script.push_back({{"select_add", {6}}});
  script.push_back({{"pin", true}});
  script.push_back({{"simulate", true}});
  script.push_back({{"scrub", 7}});
  script.push_back({{"step", 1}});
  script.push_back({{"expect", {{"cache_frames", 11}, {"frame", 8}, {"cache_stale", false}}}});
  script.push_back({{"save", dir.file("saved.json")}});
  script.push_back({{"expect", {{"dirty", false}}}});
  script.push_back({{"write_state", dir.file("state.json")}});
  const ProcessResult r = runEditor(dir, script);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("script done"), std::string::npos) << r.out;

  const nlohmann::json clicked = readJson(dir.file("after-click.json"));
  ASSERT_EQ(clicked["selected"].size(), 1u) << "the click at the centre picks one cloth vertex";
  const int picked = clicked["selected"][0];
  EXPECT_GE(picked, 0);
  EXPECT_LT(picked, 81);

  const nlohmann::json state = readJson(dir.file("state.json"));
  EXPECT_EQ(state["cache_frames"], 11);
  EXPECT_EQ(state["frame"], 8);
  EXPECT_EQ(state["selected"], nlohmann::json::array({3, 5, 6}));
  EXPECT_EQ(state["cache_status"], "done");

  const nlohmann::json saved = readJson(dir.file("saved.json"));
  EXPECT_EQ(saved["cloths"][0]["material"]["stretch"], 800.0);
  EXPECT_EQ(saved["time"]["steps"], 10);
  const nlohmann::json& attachments = saved["cloths"][0]["attachments"];
  ASSERT_EQ(attachments.size(), 2u) << "the scene's own pins and the new one";
  EXPECT_EQ(attachments[1]["vertices"], nlohmann::json::array({3, 5, 6}));
  EXPECT_EQ(attachments[1]["kind"], "fixed");
  // The original file is untouched (save as), and no temporary files are left.
  EXPECT_EQ(readJson(scene)["cloths"][0]["material"]["stretch"], 500.0);
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(EditorScript, UndoRedoAndBoxSelect) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hanging.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  const ProcessResult r = runEditor(
      dir,
      {{{"open", scene}},
       {{"set", "cloths.0.material.bend"}, {"value", 0.01}},
       {{"undo", true}},
       {{"expect", {{"dirty", false}, {"can_redo", true}}}},
       {{"redo", true}},
       {{"expect",
         {{"dirty", true}, {"value", {{"path", "cloths.0.material.bend"}, {"equals", 0.01}}}}}},
       {{"camera", "front"}},
       {{"frames", 1}},
       {{"box_select", {0, 0, 960, 600}}},
       {{"write_state", dir.file("state.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readJson(dir.file("state.json"))["selected"].size(), 25u)
      << "the whole view selects every vertex";
}

// Save As into another folder (a relative path, as typed into the dialog): the garment the scene
// names relative to its folder is named from the new folder, and the engine loads the copy.
TEST(EditorScript, SaveAsIntoAnotherFolderKeepsTheGarmentFound) {
  TempDir dir;
  fs::create_directories(dir.file("project/meshes"));
  fs::create_directories(dir.file("copies"));
  dir.write("project/meshes/strip.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nf 1 3 4\nf 1 4 2\n");
  nlohmann::json doc = hangingClothScene(1.0, 4, 0.01, 3, 500.0);
  doc["cloths"].push_back(
      {{"mesh", {{"file", "meshes/strip.obj"}, {"transform", {{"translate", {0, 2, 0}}}}}},
       {"material", {{"density", 0.1}, {"stretch", 500.0}}}});
  writeScene(dir.file("project/scene.json"), doc);
  const ProcessResult r = runEditor(dir, {{{"open", "project/scene.json"}},
                                          {{"save", "copies/scene.json"}},
                                          {{"expect", {{"valid", true}, {"dirty", false}}}},
                                          {{"write_state", dir.file("state.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const nlohmann::json saved = readJson(dir.file("copies/scene.json"));
  EXPECT_EQ(saved["cloths"][1]["mesh"]["file"], "../project/meshes/strip.obj");
  EXPECT_EQ(readJson(dir.file("state.json"))["document"], saved)
      << "the document is what was saved";
  EXPECT_EQ(loadScene(dir.file("copies/scene.json")).cloths[1].mesh.vertexCount(), 4);
}

TEST(EditorScript, FailingActionExitsNonzeroNamingIt) {
  TempDir dir;
  const ProcessResult r =
      runEditor(dir, {{{"new", true}}, {{"set", "cloths.0.material.colour.red"}, {"value", 1}}});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("actions.1 (set)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cloths.0.material.colour.red"), std::string::npos) << r.err;

  const ProcessResult missing = runEditor(dir, {{{"open", dir.file("missing.json")}}});
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("missing.json"), std::string::npos) << missing.err;

  const ProcessResult unknown = runEditor(dir, {{{"fly", true}}});
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("unknown action"), std::string::npos) << unknown.err;

  const ProcessResult expectation = runEditor(dir, {{{"expect", {{"cache_frames", 3}}}}});
  EXPECT_EQ(expectation.exitCode, 2);
  EXPECT_NE(expectation.err.find("cache_frames is 0, expected 3"), std::string::npos)
      << expectation.err;
}

TEST(EditorScript, InvalidValueIsReportedByTheLoaderNotClamped) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir, {{{"new", true}},
            {{"set", "time.dt"}, {"value", -1.0}, {"expect_error", "time.dt"}},
            {{"expect", {{"valid", false}, {"value", {{"path", "time.dt"}, {"equals", -1.0}}}}}},
            {{"frames", 2}},
            {{"save", dir.file("invalid.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // Simulating an invalid document is a clear error, not a crash.
  const ProcessResult sim =
      runEditor(dir, {{{"new", true}},
                      {{"set", "time.dt"}, {"value", -1.0}, {"allow_invalid", true}},
                      {{"simulate", 3}}});
  EXPECT_EQ(sim.exitCode, 2);
  EXPECT_NE(sim.err.find("does not validate"), std::string::npos) << sim.err;
}

// The golden viewport: DiffCloth's sphere scene, coarsened to 12x12 quads, in its rest state
// with two corners pinned from the editor (the attachment markers), from a fixed camera at
// 320x240. The rest state keeps the golden independent of the solver (which is still being
// changed); simulation results are checked through state, not pixels. Tolerance: the render
// tests' default (a pixel may differ by 16/255 per channel, within 1 pixel; at most 0.25 % of
// the pixels beyond that). Regenerate on purpose with
// `weft_tests_editor --bless --gtest_filter=EditorScript.ViewportMatchesGolden` and look at it.
TEST(EditorScript, ViewportMatchesGolden) {
  TempDir dir;
  const ProcessResult r = runEditor(
      dir,
      {{{"open", std::string(WEFT_ASSET_DIR) + "/scenes/sphere.json"}},
       {{"set", "cloths.0.mesh.grid.resolution"}, {"value", {12, 12}}},
       {{"select", {0, 12}}},
       {{"pin", true}},
       {{"camera", {{"yaw", 25}, {"pitch", 30}, {"distance", 1.9}, {"target", {0.05, 0.1, 0.0}}}}},
       {{"frames", 1}},
       {{"screenshot", dir.file("viewport.png")}, {"size", {320, 240}}},
       {{"write_state", dir.file("state.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readJson(dir.file("state.json"))["cache_frames"], 0);
  const render::Image image = render::readPng(dir.file("viewport.png"));
  EXPECT_TRUE(matchesGolden("editor_viewport_sphere", image));
}

// The window at 1280x720 with each of the four tabs of the side panel, plus the timeline and
// the viewport: a hanging cloth (two pin groups, one named; a hemline loss over its stretch)
// simulated 20 steps, at state 12, vertex 24 inspected. Catches clipped controls, moved layout,
// lost labels and colours. The cloth hangs without contact and its solves converge tightly, so the
// numbers shown do not depend on solver details beyond the digits printed. Tolerance: the render
// tests' default (a pixel may differ by 16/255 per channel within 1 pixel; at most 0.25 % of the
// pixels beyond that). Regenerate on purpose with `weft_tests_editor --bless
// --gtest_filter=EditorScript.MainPanelsMatchGoldens` and look at them.
TEST(EditorScript, MainPanelsMatchGoldens) {
  TempDir dir;
  nlohmann::json scene = hangingClothScene(1.0, 6, 0.01, 20, 500.0);
  scene["cloths"][0]["attachments"].push_back({{"vertices", {3}}, {"name", "top middle"}});
  scene["task"] = {{"loss", {{"hemline", {{"vertices", {42, 45, 48}}, {"height", 0.2}}}}},
                   {"parameters", {"cloths.0.material.stretch"}}};
  const std::string file = writeScene(dir.file("hanging.json"), scene);
  const ProcessResult r = runEditor(dir,
                                    {{{"open", file}},
                                     {{"frames", 2}},
                                     {{"window_screenshot", dir.file("scene.png")}},
                                     {{"simulate", true}},
                                     {{"scrub", 12}},
                                     {{"select", {24}}},
                                     {{"panel", "inspect"}},
                                     {{"frames", 2}},
                                     {{"window_screenshot", dir.file("inspect.png")}},
                                     {{"panel", "targets"}},
                                     {{"frames", 2}},
                                     {{"window_screenshot", dir.file("targets.png")}},
                                     {{"panel", "optimise"}},
                                     {{"frames", 2}},
                                     {{"window_screenshot", dir.file("optimise.png")}}},
                                    "1280x720");
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  for (const char* panel : {"scene", "inspect", "targets", "optimise"}) {
    SCOPED_TRACE(panel);
    const render::Image image = render::readPng(dir.file(std::string(panel) + ".png"));
    EXPECT_EQ(image.width, 1280);
    EXPECT_EQ(image.height, 720);
    EXPECT_TRUE(matchesGolden(std::string("editor_panel_") + panel, image));
  }
}

std::string findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string all = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= all.size()) {
    const std::size_t end = all.find(':', start);
    const std::string dir =
        all.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!dir.empty() && fs::exists(dir + "/" + name)) return dir + "/" + name;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return "";
}

// A real GLFW window (not OSMesa) under Xvfb: a few UI frames, a short simulation, a
// screenshot of the whole window.
TEST(EditorWindow, SmokeUnderXvfb) {
  const std::string xvfbRun = findOnPath("xvfb-run");
  if (xvfbRun.empty() || findOnPath("Xvfb").empty())
    GTEST_SKIP()
        << "Xvfb is not installed (Debian package xvfb): the on-screen smoke test needs it";
  TempDir dir;
  const std::string script =
      dir.write("smoke.json", nlohmann::json{{"actions",
                                              {{{"frames", 3}},
                                               {{"set", "time.steps"}, {"value", 3}},
                                               {{"simulate", true}},
                                               {{"scrub", 3}},
                                               {{"frames", 2}},
                                               {{"expect", {{"cache_frames", 4}, {"frame", 3}}}},
                                               {{"window_screenshot", dir.file("window.png")}}}}}
                                  .dump());
  const ProcessResult r = runProcess({xvfbRun, "-a", "-s", "-screen 0 1280x800x24",
                                      WEFT_EDITOR_BINARY, "--script", script, "--size", "1024x640"},
                                     dir.path());
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const render::Image window = render::readPng(dir.file("window.png"));
  EXPECT_EQ(window.width, 1024);
  EXPECT_EQ(window.height, 640);
  std::set<std::uint32_t> colours;
  for (int y = 0; y < window.height; y += 7)
    for (int x = 0; x < window.width; x += 7) {
      const std::uint8_t* p = window.at(x, y);
      colours.insert(std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2]);
    }
  EXPECT_GT(colours.size(), 20u) << "the window shows panels and a viewport, not a blank frame";
}

}  // namespace
}  // namespace weft::test
