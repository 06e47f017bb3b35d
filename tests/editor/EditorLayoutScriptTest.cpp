// The panel stays where it is and the timeline's buttons do what they say (issue 39): the status
// area under the file name has a fixed height, |< and >| (and Home, End) go to the first and
// last state, Play at the end plays from the start, and "simulating N steps" goes once the run
// ends. Raw input on the real binary, headless; item positions come from the state ("items").

#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace weft::test {
namespace {

TEST(EditorLayout, StatusAreaKeepsThePanelInPlace) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 5, 500.0));
  // A valid scene with no message, then one that does not validate (the loader's message
  // wraps over several lines) with an error message of the UI as well.
  const ProcessResult r = runEditor(
      dir, {{{"open", scene}},
            {{"frames", 2}},
            {{"write_state", dir.file("valid.json")}},
            {{"set", "cloths.0.material.stretch"}, {"value", -1.0}, {"allow_invalid", true}},
            {{"mouse_click", item("time.dt")}},
            {{"type", "-0.5"}},
            {{"key", "enter"}},
            {{"frames", 2}},
            {{"write_state", dir.file("invalid.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json valid = readJson(dir.file("valid.json"));
  const nlohmann::json invalid = readJson(dir.file("invalid.json"));
  ASSERT_FALSE(invalid["valid"].get<bool>());
  ASSERT_GT(invalid["validation_error"].get<std::string>().size(), 60u) << "wraps in the panel";
  for (const char* name : {"tab:scene", "time.dt", "time.steps", "solver.pd_iterations"}) {
    ASSERT_TRUE(valid["items"].contains(name)) << name;
    ASSERT_TRUE(invalid["items"].contains(name)) << name;
    EXPECT_EQ(valid["items"][name], invalid["items"][name]) << name << " moved";
  }
}

TEST(EditorLayout, StartEndAndPlayAtTheEnd) {
  TempDir dir;
  // dt = 0.5 s: ten states take 5 s to play, far longer than the frames between a click and the
  // state written after it.
  const std::string scene =
      writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.5, 10, 500.0));
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"simulate", true}},
                                          {{"scrub", 5}},
                                          {{"frames", 1}},
                                          {{"mouse_click", item("timeline:start")}},
                                          {{"expect", {{"frame", 0}}}},
                                          {{"mouse_click", item("timeline:end")}},
                                          {{"expect", {{"frame", 10}, {"playing", false}}}},
                                          {{"key", "home"}},
                                          {{"expect", {{"frame", 0}}}},
                                          {{"key", "end"}},
                                          {{"expect", {{"frame", 10}}}},
                                          {{"mouse_click", item("timeline:play")}},
                                          {{"write_state", dir.file("play.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json play = readJson(dir.file("play.json"));
  EXPECT_TRUE(play["playing"].get<bool>()) << "Play at the last state plays";
  EXPECT_LT(play["frame"].get<int>(), 10) << "from the start";
}

TEST(EditorLayout, SimulatingMessageGoesWhenTheRunEnds) {
  TempDir dir;
  const std::string scene =
      writeScene(dir.file("hang.json"), hangingClothScene(1.0, 16, 0.01, 200, 500.0));
  const ProcessResult r = runEditor(dir, {{{"open", scene}},
                                          {{"frames", 2}},
                                          {{"mouse_click", item("timeline:simulate")}},
                                          {{"write_state", dir.file("running.json")}},
                                          {{"wait_simulation", true}},
                                          {{"frames", 2}},
                                          {{"write_state", dir.file("done.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json running = readJson(dir.file("running.json"));
  if (running["cache_status"] == "running") {
    EXPECT_EQ(running["message"], "simulating 200 steps");
  }
  const nlohmann::json done = readJson(dir.file("done.json"));
  EXPECT_EQ(done["cache_status"], "done");
  EXPECT_EQ(done["cache_frames"], 201);
  EXPECT_EQ(done["message"], "");
}

// The contact branches' swatches are labelled (the renderer draws the colours, the editor the
// words beside them, in the renderer's layout): none before a contact state is shown, then
// take-off above stick above slip, each left of its swatch in the viewport's lower right corner.
TEST(EditorLayout, ContactLegendIsLabelled) {
  TempDir dir;
  const ProcessResult r =
      runEditor(dir, {{{"open", std::string(WEFT_ASSET_DIR) + "/scenes/sphere.json"}},
                      {{"set", "time.steps"}, {"value", 30}},
                      {{"frames", 2}},
                      {{"write_state", dir.file("rest.json")}},
                      {{"simulate", true}},
                      {{"scrub", 30}},
                      {{"frames", 2}},
                      {{"write_state", dir.file("contact.json")}}});
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const nlohmann::json rest = readJson(dir.file("rest.json"));
  EXPECT_FALSE(rest["items"].contains("legend:slip")) << "no contact shown, no legend";
  const nlohmann::json contact = readJson(dir.file("contact.json"));
  const nlohmann::json& items = contact["items"];
  ASSERT_TRUE(items.contains("legend:take-off") && items.contains("legend:stick") &&
              items.contains("legend:slip"))
      << items;
  const double takeOff = items["legend:take-off"][1], stick = items["legend:stick"][1],
               slip = items["legend:slip"][1];
  EXPECT_LT(takeOff, stick);
  EXPECT_LT(stick, slip);
  // In the viewport's lower right quarter (window pixels; the viewport's size from the state).
  const double x = items["legend:slip"][0];
  EXPECT_GT(x, 0.5 * 960.0);
  EXPECT_GT(slip, 0.5 * 600.0);
}

}  // namespace
}  // namespace weft::test
