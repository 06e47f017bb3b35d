#include "ScriptRunner.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <weft/core/Error.h>
#include <weft/render/Image.h>
#include <weft/scene/JsonPath.h>

#include <chrono>
#include <fstream>

namespace weft::editor {
namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string kindOf(const nlohmann::json& action) {
  if (!action.is_object() || action.empty()) return "?";
  for (const char* k : {"open", "new", "set", "remove", "select", "select_add", "clear_selection", "click",
                        "box_select", "pin", "simulate", "cancel", "scrub", "step", "play", "pause",
                        "undo", "redo", "save", "camera", "screenshot", "window_screenshot", "frames",
                        "expect", "write_state"})
    if (action.contains(k)) return k;
  return action.begin().key();
}

nlohmann::json stateOf(EditorSession& session) {
  const EditorDocument& doc = session.document();
  return {{"file", doc.file()},
          {"dirty", doc.dirty()},
          {"valid", doc.valid()},
          {"validation_error", doc.validationError()},
          {"cache_frames", session.cache().frameCount()},
          {"cache_status", SimulationCache::statusName(session.cache().status())},
          {"cache_stale", session.cacheStale()},
          {"frame", session.playback().frame()},
          {"selected", session.selection().nodes()},
          {"can_undo", doc.canUndo()},
          {"can_redo", doc.canRedo()}};
}

}  // namespace

ScriptRunner::ScriptRunner(const std::string& file) : file_(file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "-", "cannot read the script");
  nlohmann::json script;
  try {
    script = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file, "-", std::string("not valid JSON: ") + e.what());
  }
  if (script.is_object() && script.contains("actions")) script = script["actions"];
  if (!script.is_array()) throw InputError(file, "actions", "must be a list of actions");
  actions_ = std::move(script);
}

void ScriptRunner::fail(const std::string& what, int code) {
  const nlohmann::json& action = actions_[next_];
  error_ = file_ + ": actions." + std::to_string(next_) + " (" + kindOf(action) + "): " + what;
  exitCode_ = code;
  state_ = State::Failed;
}

ScriptRunner::State ScriptRunner::update(EditorSession& session, EditorApp& app) {
  if (state_ != State::Running) return state_;
  if (next_ >= actions_.size()) return state_ = State::Finished;
  try {
    if (run(actions_[next_], session, app)) {
      ++next_;
      waitingForSimulation_ = false;
      waitFrames_ = 0;
    }
  } catch (const std::exception& e) {
    fail(e.what());
  }
  return state_;
}

bool ScriptRunner::run(const nlohmann::json& a, EditorSession& session, EditorApp& app) {
  if (!a.is_object()) {
    fail("an action must be an object such as {\"open\": \"scene.json\"}");
    return false;
  }
  const std::string kind = kindOf(a);
  EditorDocument& doc = session.document();
  const float aspect = float(app.viewportWidth()) / float(std::max(app.viewportHeight(), 1));

  if (kind == "open") {
    session.open(a.at("open").get<std::string>());
    session.frameCamera(aspect);
  } else if (kind == "new") {
    session.newDocument();
  } else if (kind == "set" || kind == "remove") {
    const std::string path = a.at(kind).get<std::string>();
    // As `weft simulate --set`: the parent must exist (no objects are created on the way).
    std::string error = kind == "set" ? doc.setValue(path, a.at("value"), false, false) : doc.removeValue(path);
    if (error.empty() && !doc.valid()) error = doc.validationError();
    if (a.contains("expect_error")) {
      const std::string expected = a["expect_error"].get<std::string>();
      if (error.empty()) fail("expected an error containing \"" + expected + "\", but the scene is valid");
      else if (error.find(expected) == std::string::npos)
        fail("expected an error containing \"" + expected + "\", got: " + error);
      return state_ == State::Running;
    }
    if (!error.empty() && !a.value("allow_invalid", false)) {
      fail(error);
      return false;
    }
  } else if (kind == "select" || kind == "select_add") {
    const std::string error = session.selectNodes(a.at(kind).get<std::vector<int>>(), kind == "select_add");
    if (!error.empty()) {
      fail(error);
      return false;
    }
  } else if (kind == "clear_selection") {
    session.selection().clear();
  } else if (kind == "click") {
    const auto p = a.at("click").get<std::vector<float>>();
    if (p.size() != 2) throw std::invalid_argument("click takes [x, y] in viewport pixels");
    const auto vertex = session.clickSelect(p[0], p[1], app.viewportWidth(), app.viewportHeight(),
                                            a.value("add", false));
    if (!vertex && a.value("must_hit", true)) {
      fail("the click at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ") hits no cloth triangle");
      return false;
    }
  } else if (kind == "box_select") {
    const auto r = a.at("box_select").get<std::vector<float>>();
    if (r.size() != 4) throw std::invalid_argument("box_select takes [x0, y0, x1, y1] in viewport pixels");
    session.boxSelectPixels(r[0], r[1], r[2], r[3], app.viewportWidth(), app.viewportHeight(),
                            a.value("add", false));
  } else if (kind == "pin") {
    const std::string error = session.pinSelection();
    if (!error.empty()) {
      fail(error);
      return false;
    }
  } else if (kind == "simulate") {
    if (!waitingForSimulation_) {
      const nlohmann::json& s = a.at("simulate");
      const int steps = s.is_number_integer() ? s.get<int>() : -1;
      const std::string error = session.simulate(steps);
      if (!error.empty()) {
        fail(error);
        return false;
      }
      if (!a.value("wait", true)) return true;
      waitingForSimulation_ = true;
      waitStarted_ = now();
      timeout_ = a.value("timeout_seconds", 300.0);
      return false;  // at least one UI frame while it runs
    }
    if (session.cache().running()) {
      if (now() - waitStarted_ > timeout_) {
        session.cache().cancel();
        fail("the simulation did not finish within " + std::to_string(timeout_) + " s");
      }
      return false;
    }
    if (session.cache().status() == SimulationCache::Status::Failed) {
      fail("simulation failed: " + session.cache().error(), 3);
      return false;
    }
  } else if (kind == "cancel") {
    session.cache().cancel();
  } else if (kind == "scrub") {
    session.playback().scrub(a.at("scrub").get<int>(), session.availableFrames());
  } else if (kind == "step") {
    session.playback().step(a.at("step").get<int>(), session.availableFrames());
  } else if (kind == "play") {
    session.playback().play();
  } else if (kind == "pause") {
    session.playback().pause();
  } else if (kind == "undo" || kind == "redo") {
    if (!(kind == "undo" ? doc.undo() : doc.redo())) {
      fail("nothing to " + kind);
      return false;
    }
  } else if (kind == "save") {
    const nlohmann::json& s = a.at("save");
    if (s.is_string())
      session.saveAs(s.get<std::string>());
    else
      session.save();
  } else if (kind == "camera") {
    const nlohmann::json& c = a.at("camera");
    if (c.is_string()) {
      render::NamedView view;
      if (!render::parseNamedView(c.get<std::string>(), view))
        throw std::invalid_argument("camera must be front, side, top, auto or an object");
      session.frameCamera(aspect, view);
    } else {
      render::Camera& cam = session.camera();
      cam.yawDeg = c.value("yaw", cam.yawDeg);
      cam.pitchDeg = c.value("pitch", cam.pitchDeg);
      cam.distance = c.value("distance", cam.distance);
      if (c.contains("target")) {
        const auto t = c["target"].get<std::vector<float>>();
        if (t.size() != 3) throw std::invalid_argument("camera target must be [x, y, z]");
        cam.target = render::Vec3f(t[0], t[1], t[2]);
      }
    }
  } else if (kind == "screenshot") {
    int w = app.viewportWidth(), h = app.viewportHeight();
    if (a.contains("size")) {
      const auto s = a["size"].get<std::vector<int>>();
      if (s.size() != 2 || s[0] <= 0 || s[1] <= 0) throw std::invalid_argument("size must be [width, height]");
      w = s[0], h = s[1];
    }
    render::writePng(a.at("screenshot").get<std::string>(), app.viewportImage(w, h));
  } else if (kind == "window_screenshot") {
    render::writePng(a.at("window_screenshot").get<std::string>(), app.windowImage());
  } else if (kind == "frames") {
    if (waitFrames_ == 0) waitFrames_ = std::max(1, a.at("frames").get<int>());
    return --waitFrames_ == 0;
  } else if (kind == "expect") {
    const nlohmann::json state = stateOf(session);
    for (const auto& [key, expected] : a.at("expect").items()) {
      if (key == "value") {
        const std::string path = expected.at("path").get<std::string>();
        const nlohmann::json* actual = doc.find(path);
        if (!actual || *actual != expected.at("equals")) {
          fail(path + " is " + (actual ? actual->dump() : "absent") + ", expected " + expected.at("equals").dump());
          return false;
        }
      } else if (!state.contains(key)) {
        fail("unknown expectation \"" + key + "\"");
        return false;
      } else if (state[key] != expected) {
        fail(key + " is " + state[key].dump() + ", expected " + expected.dump());
        return false;
      }
    }
  } else if (kind == "write_state") {
    std::ofstream out(a.at("write_state").get<std::string>());
    out << stateOf(session).dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + a["write_state"].get<std::string>());
  } else {
    fail("unknown action \"" + kind + "\"");
    return false;
  }
  return true;
}

}  // namespace weft::editor
