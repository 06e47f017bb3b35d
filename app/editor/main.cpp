// weft-editor: the Dear ImGui + GLFW editor, or the same UI driven headless by a script.
//
//   weft-editor [SCENE]                                   a window (needs a display)
//   weft-editor [SCENE] --script FILE                     a window, driven by the script
//   weft-editor [SCENE] --headless --script FILE [--size WxH] [--backend auto|osmesa|egl]
//   weft-editor [SCENE] --bench [--bench-frames N] [--bench-grid Q] [--bench-steps S]
//               [--bench-out DIR] [--size WxH] [--backend ...]   UI frame times, headless
//
// Exit codes follow the `weft` contract: 0 success, 2 bad input or a failing script action,
// 3 a simulation that failed numerically.

#include "../process/PassiveOpenMpWait.h"
#include "EditorApp.h"
#include "EditorBenchmark.h"
#include "EditorSession.h"
#include "ScriptRunner.h"

#include <weft/core/Error.h>
#include <weft/render/GlfwContext.h>
#include <weft/render/HeadlessContext.h>

#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cfloat>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

namespace {

using namespace weft;
using namespace weft::editor;

struct Options {
  std::string scene, script, recentStore, recoveryDir;
  bool headless = false, recentGiven = false, recoveryGiven = false, bench = false;
  double autosaveSeconds = 5.0;
  EditorBenchmarkOptions benchOptions;
  int width = 1280, height = 720;
  render::HeadlessBackend backend = render::HeadlessBackend::Auto;
};

void usage(std::ostream& out) {
  out << "usage: weft-editor [SCENE] [--headless] [--script FILE] [--size WxH]\n"
         "                   [--backend auto|osmesa|egl] [--recent-files FILE]\n"
         "                   [--recovery-dir DIR] [--autosave-seconds S]\n"
         "       weft-editor [SCENE] --bench [--bench-frames N] [--bench-grid Q] [--bench-steps "
         "S]\n"
         "                   [--bench-out DIR] [--size WxH] [--backend auto|osmesa|egl]\n";
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError("-", a, "needs a value");
      return argv[++i];
    };
    if (a == "--headless") {
      o.headless = true;
    } else if (a == "--script") {
      o.script = value();
    } else if (a == "--size") {
      const std::string v = value();
      if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 320 ||
          o.height < 240)
        throw InputError("-", "--size", "expects WxH of at least 320x240, got " + v);
    } else if (a == "--backend") {
      const std::string v = value();
      if (!render::parseHeadlessBackend(v, o.backend))
        throw InputError("-", "--backend", "expects auto, osmesa or egl, got " + v);
    } else if (a == "--bench") {
      o.bench = true;
    } else if (a == "--bench-frames" || a == "--bench-grid" || a == "--bench-steps") {
      const std::string v = value();
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < 1 || n > 100000)
        throw InputError("-", a, "expects a positive whole number, got " + v);
      (a == "--bench-frames" ? o.benchOptions.frames
       : a == "--bench-grid" ? o.benchOptions.grid
                             : o.benchOptions.steps) = static_cast<int>(n);
    } else if (a == "--bench-out") {
      o.benchOptions.out = value();
    } else if (a == "--recent-files") {
      o.recentStore = value();
      o.recentGiven = true;
    } else if (a == "--recovery-dir") {
      o.recoveryDir = value();
      o.recoveryGiven = true;
    } else if (a == "--autosave-seconds") {
      const std::string v = value();
      char* end = nullptr;
      const double s = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(s >= 0.0) || s > 86400.0)
        throw InputError("-", a, "expects seconds between 0 and 86400, got " + v);
      o.autosaveSeconds = s;
    } else if (a == "--help" || a == "-h") {
      usage(std::cout);
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw InputError("-", a, "unknown option");
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw InputError("-", a, "only one scene file may be given");
    }
  }
  if (o.bench && !o.script.empty())
    throw InputError("-", "--bench", "cannot be combined with --script");
  if (o.headless && o.script.empty() && !o.bench)
    throw InputError("-", "--headless", "needs --script FILE (there is nobody to click)");
  return o;
}

// Runs UI frames until the script ends (or, without a script, until the window closes).
int loop(EditorSession& session, EditorApp& app, std::optional<ScriptRunner>& script,
         const std::function<bool()>& beginFrame, const std::function<void()>& endFrame) {
  auto last = std::chrono::steady_clock::now();
  while (true) {
    if (!beginFrame()) {
      // The UI confirmed a close (Quit, the window's close button, a script's close action).
      if (script) std::cout << "weft-editor: closed at actions." << script->nextAction() << "\n";
      return 0;
    }
    const auto t = std::chrono::steady_clock::now();
    ImGui::GetIO().DeltaTime = std::max(1e-4f, std::chrono::duration<float>(t - last).count());
    last = t;
    app.frame();
    endFrame();
    if (script) {
      const ScriptRunner::State state = script->update(session, app);
      if (state == ScriptRunner::State::Failed) {
        std::cerr << "error: " << script->error() << "\n";
        return script->exitCode();
      }
      if (state == ScriptRunner::State::Finished) {
        std::cout << "weft-editor: script done: " << session.document().displayName() << ", "
                  << session.cache().frameCount() << " cached states, "
                  << session.selection().nodes().size() << " selected vertices\n";
        return 0;
      }
    }
    // Leave the cores to the simulation while it runs.
    if (session.cache().running()) std::this_thread::sleep_for(std::chrono::milliseconds(8));
  }
}

int runHeadless(const Options& o, EditorSession& session, std::optional<ScriptRunner>& script) {
  std::unique_ptr<render::RenderContext> context =
      render::createHeadlessContext(o.width, o.height, o.backend, &std::cerr);
  int code = 0;
  {
    EditorApp app(session, *context);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(o.width), float(o.height));
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    // The headless platform: the script's mouse and keys, with GLFW's key codes as in a window.
    ScriptedInput::installKeyMap(io);
    code = loop(
        session, app, script,
        [&] {
          if (app.closeConfirmed()) return false;
          if (script) script->input().apply(io);
          return true;
        },
        [] {});
  }
  context.reset();  // before Mesa's exit handlers
  return code;
}

// Idle costs nothing: with nothing animating (EditorSession::animating) the window sleeps in
// glfwWaitEventsTimeout until input arrives, instead of drawing frames nobody needs. Any input
// event (these callbacks, installed before ImGui's GLFW backend, which calls them on) buys a few
// frames: ImGui acts on a click in one frame and draws its result in the next, and hover and
// popups settle over a frame or two more. The timeout only bounds how stale a picture can get.
constexpr int kFramesAfterInput = 4;
constexpr double kIdleTimeoutSeconds = 1.0;
int framesAfterInput = kFramesAfterInput;

void noteInput() {
  framesAfterInput = kFramesAfterInput;
}
void installInputWake(GLFWwindow* window) {
  glfwSetCursorPosCallback(window, [](GLFWwindow*, double, double) { noteInput(); });
  glfwSetMouseButtonCallback(window, [](GLFWwindow*, int, int, int) { noteInput(); });
  glfwSetScrollCallback(window, [](GLFWwindow*, double, double) { noteInput(); });
  glfwSetKeyCallback(window, [](GLFWwindow*, int, int, int, int) { noteInput(); });
  glfwSetCharCallback(window, [](GLFWwindow*, unsigned) { noteInput(); });
  glfwSetWindowFocusCallback(window, [](GLFWwindow*, int) { noteInput(); });
  glfwSetCursorEnterCallback(window, [](GLFWwindow*, int) { noteInput(); });
  glfwSetWindowSizeCallback(window, [](GLFWwindow*, int, int) { noteInput(); });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow*, int, int) { noteInput(); });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow*) { noteInput(); });
  glfwSetWindowIconifyCallback(window, [](GLFWwindow*, int) { noteInput(); });
  glfwSetWindowCloseCallback(window, [](GLFWwindow*) { noteInput(); });
}

int runWindow(const Options& o, EditorSession& session, std::optional<ScriptRunner>& script) {
  render::GlfwContext context("Weft editor", o.width, o.height);
  glfwSwapInterval(1);
  int code = 0;
  {
    EditorApp app(session, context);
    installInputWake(context.window());
    bool wasAnimating = true;
    ImGui_ImplGlfw_InitForOpenGL(context.window(), true);
    code = loop(
        session, app, script,
        [&] {
          if (glfwWindowShouldClose(context.window())) {
            glfwSetWindowShouldClose(context.window(), GLFW_FALSE);
            app.requestClose();
          }
          if (app.closeConfirmed()) return false;
          // A script drives every frame itself: it never waits. Once animation stops (a run
          // ends) one more frame shows where it stopped.
          const bool animating = session.animating();
          if (!script && !animating && !wasAnimating && framesAfterInput <= 0)
            glfwWaitEventsTimeout(kIdleTimeoutSeconds);
          else
            glfwPollEvents();
          wasAnimating = animating;
          if (framesAfterInput > 0) --framesAfterInput;
          ImGui_ImplGlfw_NewFrame();
          // Once a script plays raw input, it overrides the window's mouse and the keys it holds.
          if (script && script->input().used()) script->input().apply(ImGui::GetIO());
          return true;
        },
        [&] { context.present(); });
    ImGui_ImplGlfw_Shutdown();
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  weft::process::preferPassiveOpenMpWait(argv);
  try {
    Options o = parse(argc, argv);
    if (o.bench) {
      o.benchOptions.scene = o.scene;
      o.benchOptions.width = o.width;
      o.benchOptions.height = o.height;
      o.benchOptions.backend = o.backend;
      return runEditorBenchmark(o.benchOptions, std::cout);
    }
    std::optional<ScriptRunner> script;
    if (!o.script.empty()) script.emplace(o.script);
    // Scripted runs keep the recent-files list in memory unless told where it lives, so tests
    // never touch the user's list.
    const std::string store = o.recentGiven ? o.recentStore
                              : script      ? std::string()
                                            : RecentFiles::defaultStoreFile();
    EditorSession session(store);
    // Autosave likewise: on in a window, off for scripts unless given a folder.
    const std::string recovery = o.recoveryGiven ? o.recoveryDir
                                 : script        ? std::string()
                                                 : Autosave::defaultFolder();
    session.setAutosave(Autosave(recovery, o.autosaveSeconds));
    if (!o.scene.empty()) session.open(o.scene);
    return o.headless ? runHeadless(o, session, script) : runWindow(o, session, script);
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  }
}
