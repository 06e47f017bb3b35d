// Fuzz target: the editor's script reader (ScriptRunner) and the actions it runs
// (ScriptCommands), against a live headless editor as `weft-editor --headless --script` runs
// them. An input is a script file; each is run on a fresh EditorSession and EditorApp (one
// OSMesa/EGL context for the process) with a small scene open, for at most kFrames UI frames.
//
// A bad script or action must end the script with its error (the editor's exit 2 or 3); an
// exception escaping a frame, a crash, a sanitizer report, or a Dear ImGui assertion the editor
// had to recover from (a UI contract broken; EditorApp::recoveredAssertions) is a finding,
// except after the action that provokes one on purpose.
//
// The process works in its own temporary folder. Scripts name files to open, import, save and
// write screenshots to; an input naming a path outside that folder (absolute, or with "..") is
// rejected unrun, so the fuzzer cannot write over anything.

#include "FuzzInput.h"

#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptRunner.h"
#include "ScriptedInput.h"

#include <weft/core/Error.h>
#include <weft/render/HeadlessContext.h>

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace {

constexpr int kFrames = 60;  // UI frames per input: every action takes at least one
constexpr int kWidth = 480, kHeight = 320;

// The scene each input starts with (also saved as scene.json, so "open" has a file to read):
// a 5x5-vertex cloth hanging over a sphere, small enough that a simulation or an optimiser
// evaluation a script starts finishes within a few frames.
const char* const kScene = R"({
  "name": "fuzz",
  "time": { "dt": 0.01, "steps": 4 },
  "gravity": [0, -9.8, 0],
  "cloths": [ {
    "mesh": { "grid": { "size": [0.4, 0.4], "resolution": [4, 4] },
              "transform": { "rotate_deg": [90, 0, 0], "translate": [0, 1, 0] } },
    "material": { "density": 0.1, "stretch": 300.0, "bend": 0.001 },
    "attachments": [ { "vertices": [0, 4], "kind": "fixed" } ]
  } ],
  "obstacles": [ { "sphere": { "center": [0, 0.7, 0.05], "radius": 0.1 }, "friction": 0.3 } ]
})";

// True when a string anywhere in `j` could name a file outside the working folder.
bool namesOutside(const nlohmann::json& j) {
  if (j.is_string()) {
    const std::string& s = j.get_ref<const std::string&>();
    return (!s.empty() && (s[0] == '/' || s[0] == '~')) || s.find("..") != std::string::npos;
  }
  if (j.is_structured())
    for (const auto& item : j.items())
      if (namesOutside(item.value()) || (j.is_object() && namesOutside(item.key()))) return true;
  return false;
}

bool provokes(const nlohmann::json& j) {
  if (j.is_object() && j.contains("provoke_imgui_assertion")) return true;
  if (j.is_structured())
    for (const auto& item : j)
      if (provokes(item)) return true;
  return false;
}

// The process's folder, made current, with scene.json in it; and its render context.
struct Sandbox {
  Sandbox() {
    std::filesystem::current_path(weft::fuzz::processFolder());
    weft::fuzz::writeInput("scene.json", reinterpret_cast<const std::uint8_t*>(kScene),
                           std::char_traits<char>::length(kScene));
    context = weft::render::createHeadlessContext(kWidth, kHeight);
  }
  std::unique_ptr<weft::render::RenderContext> context;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace weft::editor;
  static Sandbox sandbox;
  const nlohmann::json parsed =
      nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (!parsed.is_discarded() && namesOutside(parsed)) {
    if (std::getenv("WEFT_FUZZ_VERBOSE"))
      std::fprintf(stderr, "editor_script: names a path outside\n");
    return -1;  // not run, not kept
  }
  const std::string path = weft::fuzz::writeInput("script.json", data, size);

  std::optional<ScriptRunner> script;
  try {
    script.emplace(path);
  } catch (const weft::InputError& e) {
    if (std::getenv("WEFT_FUZZ_VERBOSE")) std::fprintf(stderr, "editor_script: %s\n", e.what());
    return 0;  // not a script: refused as the editor refuses it (exit 2)
  }
  EditorSession session("");  // recent files in memory only
  session.open("scene.json");
  int recovered = 0;
  {
    EditorApp app(session, *sandbox.context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(kWidth), float(kHeight));
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    ScriptedInput::installKeyMap(io);
    ScriptRunner::State state = ScriptRunner::State::Running;
    int frame = 0;
    for (; frame < kFrames && !app.closeConfirmed(); ++frame) {
      script->input().apply(io);
      io.DeltaTime = 1.0f / 60.0f;
      app.frame();
      if ((state = script->update(session, app)) != ScriptRunner::State::Running) break;
    }
    recovered = app.recoveredAssertions();
    // How far a seed gets, for whoever writes seeds: WEFT_FUZZ_VERBOSE=1.
    if (std::getenv("WEFT_FUZZ_VERBOSE"))
      std::fprintf(stderr, "editor_script: %d frames, %zu actions done, %s%s\n", frame,
                   script->nextAction(),
                   state == ScriptRunner::State::Failed     ? "failed: "
                   : state == ScriptRunner::State::Finished ? "finished"
                                                            : "stopped",
                   script->error().c_str());
  }
  if (recovered > 0 && !provokes(parsed)) {
    std::fprintf(stderr, "fuzz: the editor recovered from %d Dear ImGui assertion(s)\n", recovered);
    std::abort();
  }
  return 0;
}
