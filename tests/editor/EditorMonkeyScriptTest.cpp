// The monkey test (issue 39): random clicks, drags, scrolls, key presses and typed text over the
// whole window (panels, viewport, timeline, and whatever dialog they open) through the headless
// script harness, on several scenes, tab by tab. It passes when the editor neither crashes nor
// recovers from a single Dear ImGui assertion (ImGuiAssert.h) and finishes the script.
//
// The input is a pure function of the seed (fixed here: the budget in CI is fixed too); the
// editor's response also depends on how far a simulation got between frames, so a failure is
// not always replayed exactly. On failure the seed is printed and the script kept in the test
// output folder. WEFT_MONKEY_SEED and WEFT_MONKEY_EVENTS override the seed and the number of
// events, to run a longer or a different monkey by hand.

#include "EditorScriptRun.h"
#include "support/Process.h"
#include "support/SceneBuilder.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace weft::test {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 800, kHeight = 600;
constexpr int kMenuBar = 22;  // clicks stay below the menu bar: File > Quit would end the run

unsigned envOr(const char* name, unsigned fallback) {
  const char* v = std::getenv(name);
  return v && *v ? unsigned(std::strtoul(v, nullptr, 10)) : fallback;
}

// `events` random input actions; every `perTab` of them the left panel switches to the next
// tab, so that each tab gets its share.
nlohmann::json monkeyActions(unsigned seed, int events, int perTab) {
  std::mt19937 rng(seed);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  auto point = [&]() {
    return nlohmann::json{uniform(0, kWidth - 1), uniform(kMenuBar, kHeight - 1)};
  };
  // Ctrl+Q and the close action are left out (they end the run), the rest of the shortcuts in.
  static const char* keys[] = {"space",
                               "left",
                               "right",
                               "up",
                               "down",
                               "home",
                               "end",
                               "escape",
                               "enter",
                               "tab",
                               "backspace",
                               "delete",
                               "f",
                               "k",
                               "a",
                               "x",
                               "ctrl+z",
                               "ctrl+y",
                               "ctrl+shift+z",
                               "ctrl+i",
                               "ctrl+o",
                               "ctrl+s",
                               "ctrl+shift+s",
                               "ctrl+n",
                               "ctrl+a",
                               "shift+tab"};
  static const char* modifiers[] = {"shift", "ctrl", "alt"};
  static const char* buttons[] = {"left", "right", "middle"};
  static const char* tabs[] = {"scene", "inspect", "targets", "optimise"};
  const std::string typeable = "0123456789.-e";
  nlohmann::json actions = nlohmann::json::array();
  for (int i = 0; i < events; ++i) {
    if (i % perTab == 0) actions.push_back({{"panel", tabs[(i / perTab) % 4]}});
    const int kind = uniform(0, 99);
    if (kind < 40) {
      // Half the clicks aim at a named item of the last frame (document fields, tabs, timeline
      // buttons): a click anywhere seldom lands in a field's box, and typing follows clicks.
      nlohmann::json a = {{"mouse_click", uniform(0, 1)
                                              ? point()
                                              : nlohmann::json{{"item_index", uniform(0, 999)}}}};
      if (uniform(0, 9) == 0) a["modifiers"] = modifiers[uniform(0, 2)];
      actions.push_back(a);
    } else if (kind < 50) {
      actions.push_back({{"mouse_drag", buttons[uniform(0, 2)]},
                         {"from", point()},
                         {"to", point()},
                         {"steps", 3}});
    } else if (kind < 55) {
      actions.push_back({{"scroll", uniform(-3, 3)}, {"at", point()}});
    } else if (kind < 70) {
      actions.push_back({{"key", keys[uniform(0, int(std::size(keys)) - 1)]}});
    } else if (kind < 85) {
      std::string text;
      for (int n = uniform(1, 4); n > 0; --n) text += typeable[std::size_t(uniform(0, 12))];
      actions.push_back({{"type", text}});
    } else if (kind < 95) {
      actions.push_back({{"mouse_move", point()}});
    } else {
      actions.push_back({{"frames", uniform(1, 3)}});
    }
  }
  actions.push_back({{"frames", 2}});
  actions.push_back({{"write_state", "monkey-state.json"}});
  return actions;
}

void runMonkey(const std::string& name, const std::string& sceneFile, const TempDir& dir,
               unsigned defaultSeed) {
  const unsigned seed = envOr("WEFT_MONKEY_SEED", defaultSeed);
  const int events = int(envOr("WEFT_MONKEY_EVENTS", 250));
  nlohmann::json actions = monkeyActions(seed, events, 100);
  const nlohmann::json open = {{"open", sceneFile}};
  actions.insert(actions.begin(), open);
  const ProcessResult r =
      runEditor(dir, actions, std::to_string(kWidth) + "x" + std::to_string(kHeight));
  const std::string kept = std::string(WEFT_RENDER_TEST_OUTPUT) + "/monkey-" + name + "-" +
                           std::to_string(seed) + ".json";
  auto keep = [&] {
    fs::create_directories(WEFT_RENDER_TEST_OUTPUT);
    fs::copy_file(dir.file("script.json"), kept, fs::copy_options::overwrite_existing);
    return "monkey seed " + std::to_string(seed) + " (" + std::to_string(events) +
           " events; rerun with WEFT_MONKEY_SEED=" + std::to_string(seed) + "; script kept as " +
           kept + ")\n";
  };
  ASSERT_EQ(r.signal, 0) << keep() << r.err;
  ASSERT_EQ(r.exitCode, 0) << keep() << r.err << r.out;
  ASSERT_NE(r.out.find("script done"), std::string::npos) << keep() << r.out;
  EXPECT_EQ(r.err.find("recovered"), std::string::npos) << keep() << r.err;
  const nlohmann::json state = readJson(dir.file("monkey-state.json"));
  EXPECT_EQ(state["imgui_assertions"], 0) << keep();
}

TEST(EditorMonkey, HangingCloth) {
  TempDir dir;
  runMonkey("hanging",
            writeScene(dir.file("hang.json"), hangingClothScene(1.0, 4, 0.01, 20, 500.0)), dir, 39);
}

TEST(EditorMonkey, ClothOnASphereInWind) {
  TempDir dir;
  nlohmann::json scene = hangingClothScene(1.0, 6, 0.01, 20, 500.0);
  scene["obstacles"] = {
      {{"sphere", {{"center", {0.0, 0.6, 0.1}}, {"radius", 0.2}}}, {"friction", 0.3}}};
  scene["wind"] = {
      {"direction", {0.0, 0.0, 1.0}}, {"strength", 1.0}, {"frequency", 1.0}, {"phase", 0.0}};
  scene["cloths"][0]["self_collision"] = {{"radius", 0.004}, {"friction", 0.3}};
  runMonkey("sphere", writeScene(dir.file("sphere.json"), scene), dir, 40);
}

TEST(EditorMonkey, NapkinWithTargets) {
  // A shipped scene with a task and its target file, copied: the monkey may save.
  TempDir dir;
  const fs::path assets = fs::path(WEFT_ASSET_DIR) / "scenes";
  fs::create_directories(dir.file("targets"));
  fs::copy_file(assets / "targets" / "napkin_7x7.npy", dir.file("targets/napkin_7x7.npy"));
  fs::copy_file(assets / "napkin_7x7.json", dir.file("napkin.json"));
  runMonkey("napkin", dir.file("napkin.json"), dir, 41);
}

}  // namespace
}  // namespace weft::test
