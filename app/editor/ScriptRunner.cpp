#include "ScriptRunner.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <weft/core/Error.h>
#include <weft/render/Image.h>
#include <weft/scene/JsonPath.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace weft::editor {
namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string kindOf(const nlohmann::json& action) {
  if (!action.is_object() || action.empty()) return "?";
  for (const char* k : {"open",
                        "new",
                        "set",
                        "remove",
                        "select",
                        "select_add",
                        "clear_selection",
                        "click",
                        "box_select",
                        "select_loop",
                        "select_band",
                        "pin",
                        "simulate",
                        "cancel",
                        "scrub",
                        "step",
                        "play",
                        "pause",
                        "undo",
                        "redo",
                        "save",
                        "camera",
                        "screenshot",
                        "window_screenshot",
                        "frames",
                        "expect",
                        "write_state",
                        "import_garment",
                        "add_obstacle",
                        "add_mesh_obstacle",
                        "panel",
                        "contact_colours",
                        "force_arrows",
                        "set_targets",
                        "target",
                        "move_targets",
                        "drag_targets",
                        "remove_targets",
                        "load_target_motion",
                        "remove_target_motion",
                        "load_target_mesh",
                        "set_hemline",
                        "remove_hemline",
                        "add_parameter",
                        "remove_parameter",
                        "compute_gradient",
                        "optimize",
                        "optimize_step",
                        "optimize_resume",
                        "optimize_pause",
                        "optimize_wait",
                        "optimize_cancel",
                        "optimize_apply",
                        "optimize_revert",
                        "gizmo",
                        "gizmo_drag",
                        "make_handle",
                        "handle_offset",
                        "set_key",
                        "delete_key",
                        "jump_key",
                        "click_object",
                        "mouse_move",
                        "mouse_press",
                        "mouse_release",
                        "mouse_click",
                        "mouse_drag",
                        "scroll",
                        "key",
                        "key_down",
                        "key_up",
                        "type",
                        "close"})
    if (action.contains(k)) return k;
  return action.begin().key();
}

nlohmann::json vec(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json inspectorState(const EditorSession& session) {
  const auto r = session.inspect();
  if (!r) return nullptr;
  nlohmann::json contacts = nlohmann::json::array();
  for (const VertexContact& c : r->contacts)
    contacts.push_back({{"obstacle", c.obstacle},
                        {"partner", c.partner},
                        {"branch", static_cast<int>(c.branch)},
                        {"normal", vec(c.normal)},
                        {"impulse", vec(c.impulse)},
                        {"force", vec(c.force)},
                        {"velocity", vec(c.velocity)},
                        {"friction", c.friction}});
  return {{"node", r->node},
          {"state", r->state},
          {"cloth", r->cloth},
          {"local_vertex", r->localVertex},
          {"position", vec(r->position)},
          {"velocity", vec(r->velocity)},
          {"branch", static_cast<int>(r->branch)},
          {"contact_force", vec(r->contactForce)},
          {"contact_impulse", vec(r->contactImpulse)},
          {"gradient",
           [&] {
             const auto g = session.stateGradient(r->node, r->state);
             return g ? vec(*g) : nlohmann::json(nullptr);
           }()},
          {"contacts", contacts}};
}

nlohmann::json optimizerState(const EditorSession& session) {
  const OptimizerRun& run = session.optimizer();
  nlohmann::json losses = nlohmann::json::array(), history = nlohmann::json::array();
  for (const auto& s : run.samples()) {
    losses.push_back(s.loss);
    history.push_back(s.values);
  }
  const auto best = run.best();
  return {{"status", OptimizerRun::statusName(run.status())},
          {"method", run.method()},
          {"parameters", run.parameters()},
          {"evaluations", losses.size()},
          {"losses", losses},
          {"values", history},
          {"initial_values", run.initialValues()},
          {"best_loss", best ? nlohmann::json(best->loss) : nlohmann::json(nullptr)},
          {"best_values", best ? nlohmann::json(best->values) : nlohmann::json(nullptr)},
          {"stop_reason", run.stopReason()},
          {"error", run.error()}};
}

nlohmann::json stateOf(EditorSession& session, const EditorApp& app) {
  const EditorDocument& doc = session.document();
  nlohmann::json targets = nlohmann::json::object();
  for (const FinalTarget& t : session.targets()) targets[std::to_string(t.node)] = vec(t.position);
  const LossValue& loss = session.liveLoss();
  nlohmann::json terms = nlohmann::json::object();
  for (const auto& [name, value] : loss.terms) terms[name] = value;
  const char* tabs[] = {"scene", "inspect", "targets", "optimise"};
  nlohmann::json gizmo = nullptr;
  if (const auto g = session.gizmo(app.viewportWidth(), app.viewportHeight()))
    gizmo = {{"origin", vec(g->origin().cast<double>())},
             {"rotates", g->rotates()},
             {"dragging", gizmoHandleName(session.draggedHandle())}};
  nlohmann::json keys = nlohmann::json::array();
  for (const HandleKey& k : session.keys())
    keys.push_back({{"time", k.time}, {"offset", vec(k.offset)}});
  const auto offset = session.handleOffset();
  const render::Camera& camera = session.camera();
  nlohmann::json dialog = nullptr;
  float rect[4] = {0, 0, 0, 0};
  if (const std::string title = app.modalDialog(rect); !title.empty())
    dialog = {{"title", title}, {"rect", {rect[0], rect[1], rect[2], rect[3]}}};
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
          {"can_redo", doc.canRedo()},
          {"focus", session.selection().focus()},
          {"inspector", inspectorState(session)},
          {"targets", targets},
          {"loss", loss.available ? nlohmann::json(loss.total) : nlohmann::json(nullptr)},
          {"loss_terms", terms},
          {"loss_note", loss.note},
          {"optimizer", optimizerState(session)},
          {"plotted_steps", session.stepSeries().size()},
          {"message", app.message()},
          {"message_is_error", app.messageIsError()},
          {"panel", tabs[static_cast<int>(app.tab())]},
          {"viewport", {app.viewportWidth(), app.viewportHeight()}},
          {"timeline_frames", session.timelineFrames()},
          {"time", session.timelineTime()},
          {"active_object", session.activeObject().path()},
          {"gizmo", gizmo},
          {"keys", keys},
          {"handle_offset", offset ? vec(*offset) : nlohmann::json(nullptr)},
          {"key_pending", session.handleOffsetPending()},
          {"camera",
           {{"yaw", camera.yawDeg},
            {"pitch", camera.pitchDeg},
            {"distance", camera.distance},
            {"target", vec(camera.target.cast<double>())}}},
          {"playing", session.playback().playing()},
          {"dialog", dialog},
          {"close_prompt", app.closePromptOpen()},
          {"unsaved_prompt", app.unsavedPrompt().empty() ? nlohmann::json(nullptr)
                                                         : nlohmann::json(app.unsavedPrompt())},
          {"close_confirmed", app.closeConfirmed()},
          {"document", doc.document()}};
}

Vec3 vec3Of(const nlohmann::json& j, const char* what) {
  if (!j.is_array() || j.size() != 3)
    throw std::invalid_argument(std::string(what) + " must be [x, y, z]");
  return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

// The import options an action names (every key but the file is optional).
MeshImportOptions importOptions(const nlohmann::json& a, const std::string& kind) {
  MeshImportOptions o;
  o.file = a.at(kind).get<std::string>();
  o.scale = a.value("scale", 1.0);
  if (a.contains("fit")) {
    o.fit = true;
    o.fitSize = a["fit"].get<double>();
  }
  if (a.contains("rotate_deg")) o.rotateDeg = vec3Of(a["rotate_deg"], "rotate_deg");
  if (a.contains("translate")) o.translate = vec3Of(a["translate"], "translate");
  o.repair = a.value("repair", false);
  o.smoothNormals = a.value("smooth_normals", true);
  return o;
}

// A file a script writes (a screenshot, a state): its folder is made first, as `weft render
// --out` makes its own, so a script can write into a fresh out/.
std::string outputFile(const nlohmann::json& j) {
  const std::string file = j.get<std::string>();
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  return file;
}

bool isRawInput(const std::string& kind) {
  for (const char* k : {"mouse_move", "mouse_press", "mouse_release", "mouse_click", "mouse_drag",
                        "scroll", "key", "key_down", "key_up", "type"})
    if (kind == k) return true;
  return false;
}

// A point of a raw-input action in window pixels (x right, y down from the window's top-left,
// what ImGui's io.MousePos takes): [x, y], or {"viewport": [x, y]} in the viewport pixels of
// click and box_select, placed where the last frame laid the viewport out.
Eigen::Vector2f pointOf(const nlohmann::json& j, const char* what, const EditorApp& app) {
  const bool inViewport = j.is_object() && j.contains("viewport");
  const nlohmann::json& p = inViewport ? j["viewport"] : j;
  if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
    throw std::invalid_argument(std::string(what) +
                                " takes [x, y] in window pixels or {\"viewport\": [x, y]}");
  Eigen::Vector2f at(p[0].get<float>(), p[1].get<float>());
  if (inViewport) at += Eigen::Vector2f(float(app.viewportX()), float(app.viewportY()));
  return at;
}

int buttonOf(const nlohmann::json& j) {
  int button = 0;
  if (!j.is_string() || !parseMouseButton(j.get<std::string>(), button))
    throw std::invalid_argument("a mouse button is \"left\", \"right\" or \"middle\"");
  return button;
}

KeyChord chordOf(const nlohmann::json& j, bool modifiersOnly) {
  KeyChord chord;
  if (!j.is_string() || !parseKeyChord(j.get<std::string>(), chord))
    throw std::invalid_argument("unknown key " + j.dump() +
                                " (keys are named like \"ctrl+shift+z\", \"space\", \"f\")");
  if (modifiersOnly && chord.key >= 0)
    throw std::invalid_argument("modifiers are ctrl, shift, alt, super joined by +, got " +
                                j.dump());
  return chord;
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

std::optional<bool> ScriptRunner::checkOutcome(const nlohmann::json& action,
                                               const std::string& error,
                                               const std::string& succeeded) {
  // An action that expects an error passes when the error names it; any other error fails the
  // script. Empty: carry on with the action.
  if (action.contains("expect_error")) {
    const std::string expected = action["expect_error"].get<std::string>();
    if (error.empty())
      fail("expected an error containing \"" + expected + "\", but " + succeeded);
    else if (error.find(expected) == std::string::npos)
      fail("expected an error containing \"" + expected + "\", got: " + error);
    return state_ == State::Running;
  }
  if (!error.empty()) {
    fail(error);
    return false;
  }
  return std::nullopt;
}

std::string ScriptRunner::startGizmoDrag(const nlohmann::json& a, EditorSession& session,
                                         EditorApp& app) {
  GizmoHandle handle;
  if (!parseGizmoHandle(a.at("gizmo_drag").get<std::string>(), handle))
    throw std::invalid_argument(
        "gizmo_drag takes translate_x, translate_y, translate_z, rotate_x, rotate_y or rotate_z");
  const auto by = a.at("by").get<std::vector<float>>();
  if (by.size() != 2) throw std::invalid_argument("by takes [dx, dy] in viewport pixels");
  gizmoBy_ = Eigen::Vector2f(by[0], by[1]);
  const int w = app.viewportWidth(), h = app.viewportHeight();
  const auto g = session.gizmo(w, h);
  if (!g)
    return session.activeObject().kind == EditorObject::Kind::None
               ? "nothing to move: choose an object with {\"gizmo\": PATH}"
               : "the gizmo is not shown (the scene does not validate)";
  if (!g->has(handle))
    return std::string("this object has no ") + gizmoHandleName(handle) + " handle";
  // The press: at a given pixel, at an offset from the gizmo's centre on screen, or where the
  // handle can be grabbed.
  bool inView = true;
  if (a.contains("from") || a.contains("from_centre")) {
    const std::string key = a.contains("from") ? "from" : "from_centre";
    const auto f = a[key].get<std::vector<float>>();
    if (f.size() != 2) throw std::invalid_argument(key + " takes [x, y] in viewport pixels");
    gizmoFrom_ = Eigen::Vector2f(f[0], f[1]);
    if (key == "from_centre") {
      const auto centre = projectToPixel(session.camera(), g->origin(), w, h);
      inView = centre.has_value();
      if (centre) gizmoFrom_ += *centre;
    }
  } else {
    const auto grab = g->grabPixel(handle);
    inView = grab.has_value();
    if (grab) gizmoFrom_ = *grab;
  }
  if (!inView) return std::string("the ") + gizmoHandleName(handle) + " handle is not in view";
  const GizmoHandle picked = g->pickPixel(gizmoFrom_.x(), gizmoFrom_.y());
  if (picked != handle)
    return "the press at (" + std::to_string(gizmoFrom_.x()) + ", " +
           std::to_string(gizmoFrom_.y()) + ") grabs " + gizmoHandleName(picked) + ", not " +
           gizmoHandleName(handle);
  return session.beginGizmoDrag(handle, gizmoFrom_.x(), gizmoFrom_.y(), w, h);
}

void ScriptRunner::queueInput(const nlohmann::json& a, const std::string& kind, EditorApp& app) {
  using Step = std::function<void(ScriptedInput&)>;
  auto& steps = inputSteps_;
  const KeyChord held = a.contains("modifiers") ? chordOf(a["modifiers"], true) : KeyChord();
  auto move = [](Eigen::Vector2f p) { return [p](ScriptedInput& in) { in.moveTo(p.x(), p.y()); }; };
  if (kind == "mouse_move") {
    steps.push_back(move(pointOf(a.at(kind), "mouse_move", app)));
  } else if (kind == "mouse_press" || kind == "mouse_release") {
    // With "at", the move and the button change fall in one frame (a quick move and click).
    const int button = buttonOf(a.at(kind));
    const bool down = kind == "mouse_press";
    const std::optional<Eigen::Vector2f> at =
        a.contains("at") ? std::optional(pointOf(a["at"], "at", app)) : std::nullopt;
    steps.push_back([=](ScriptedInput& in) {
      if (at) in.moveTo(at->x(), at->y());
      in.setButton(button, down);
    });
  } else if (kind == "mouse_click" || kind == "mouse_drag") {
    // Modifiers go down with the move to the start and up a frame after the release, since the
    // editor reads them on the release frame (Shift adds to a box, Ctrl picks an object).
    const int button =
        buttonOf(kind == "mouse_click" ? a.value("button", nlohmann::json("left")) : a.at(kind));
    const Eigen::Vector2f from =
        pointOf(kind == "mouse_click" ? a.at(kind) : a.at("from"), "from", app);
    steps.push_back([=](ScriptedInput& in) {
      in.setModifiers(held, true);
      in.moveTo(from.x(), from.y());
    });
    steps.push_back([=](ScriptedInput& in) { in.setButton(button, true); });
    if (kind == "mouse_drag") {
      const Eigen::Vector2f to = pointOf(a.at("to"), "to", app);
      const int n = a.value("steps", 8);
      if (n < 1) throw std::invalid_argument("steps must be at least 1");
      for (int i = 1; i <= n; ++i)
        steps.push_back(move(from + (to - from) * (float(i) / float(n))));
    }
    steps.push_back([=](ScriptedInput& in) { in.setButton(button, false); });
    steps.push_back([=](ScriptedInput& in) { in.setModifiers(held, false); });
  } else if (kind == "scroll") {
    const float notches = a.at(kind).get<float>();
    const std::optional<Eigen::Vector2f> at =
        a.contains("at") ? std::optional(pointOf(a["at"], "at", app)) : std::nullopt;
    steps.push_back([=](ScriptedInput& in) {
      if (at) in.moveTo(at->x(), at->y());
      in.scroll(notches);
    });
  } else if (kind == "key" || kind == "key_down" || kind == "key_up") {
    // A key press is down for one frame and up the next (ImGui sees a press on the first frame
    // a key is down); key_down and key_up hold and let go across actions.
    const KeyChord chord = chordOf(a.at(kind), false);
    const Step down = [=](ScriptedInput& in) {
      in.setModifiers(chord, true);
      in.setKey(chord.key, true);
    };
    const Step up = [=](ScriptedInput& in) {
      in.setKey(chord.key, false);
      in.setModifiers(chord, false);
    };
    if (kind != "key_up") steps.push_back(down);
    if (kind != "key_down") steps.push_back(up);
  } else if (kind == "type") {
    const std::string text = a.at(kind).get<std::string>();
    steps.push_back([=](ScriptedInput& in) { in.type(text); });
  }
}

bool ScriptRunner::playInput(const nlohmann::json& a, const std::string& kind, EditorApp& app) {
  if (!inputQueued_) {
    inputSteps_.clear();
    queueInput(a, kind, app);
    inputQueued_ = true;
  }
  if (!inputSteps_.empty()) {
    inputSteps_.front()(input_);
    inputSteps_.pop_front();
    return false;  // the next frame reads it
  }
  inputQueued_ = false;
  return true;
}

bool ScriptRunner::run(const nlohmann::json& a, EditorSession& session, EditorApp& app) {
  if (!a.is_object()) {
    fail("an action must be an object such as {\"open\": \"scene.json\"}");
    return false;
  }
  const std::string kind = kindOf(a);
  EditorDocument& doc = session.document();
  const float aspect = float(app.viewportWidth()) / float(std::max(app.viewportHeight(), 1));

  if (isRawInput(kind)) {
    return playInput(a, kind, app);
  } else if (kind == "close") {
    // What the window's close button does (main.cpp: glfwWindowShouldClose): a dirty document
    // asks first; a confirmed close ends the run.
    app.requestClose();
  } else if (kind == "open") {
    session.open(a.at("open").get<std::string>());
    session.frameCamera(aspect);
  } else if (kind == "new") {
    session.newDocument();
  } else if (kind == "set" || kind == "remove") {
    const std::string path = a.at(kind).get<std::string>();
    // As `weft simulate --set`: the parent must exist (no objects are created on the way).
    std::string error =
        kind == "set" ? doc.setValue(path, a.at("value"), false, false) : doc.removeValue(path);
    if (error.empty() && !doc.valid()) error = doc.validationError();
    if (a.contains("expect_error")) {
      const std::string expected = a["expect_error"].get<std::string>();
      if (error.empty())
        fail("expected an error containing \"" + expected + "\", but the scene is valid");
      else if (error.find(expected) == std::string::npos)
        fail("expected an error containing \"" + expected + "\", got: " + error);
      return state_ == State::Running;
    }
    if (!error.empty() && !a.value("allow_invalid", false)) {
      fail(error);
      return false;
    }
  } else if (kind == "select" || kind == "select_add") {
    const std::string error =
        session.selectNodes(a.at(kind).get<std::vector<int>>(), kind == "select_add");
    if (!error.empty()) {
      fail(error);
      return false;
    }
  } else if (kind == "select_loop" || kind == "select_band") {
    std::string error;
    const bool add = a.value("add", false);
    if (kind == "select_loop") {
      error = session.selectBoundaryLoop(add);
    } else {
      const nlohmann::json& band = a.at(kind);
      const std::string axis = band.at("axis").get<std::string>();
      const int index = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
      error = session.selectBand(index, band.at("min").get<double>(), band.at("max").get<double>(),
                                 add);
    }
    if (const std::optional<bool> next = checkOutcome(a, error, "the selection changed"))
      return *next;
  } else if (kind == "clear_selection") {
    session.selection().clear();
  } else if (kind == "click") {
    const auto p = a.at("click").get<std::vector<float>>();
    if (p.size() != 2) throw std::invalid_argument("click takes [x, y] in viewport pixels");
    const auto vertex = session.clickSelect(p[0], p[1], app.viewportWidth(), app.viewportHeight(),
                                            a.value("add", false));
    if (!vertex && a.value("must_hit", true)) {
      fail("the click at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
           ") hits no cloth triangle");
      return false;
    }
  } else if (kind == "click_object") {
    // Ctrl+click: what the gizmo places becomes the obstacle or cloth under the pixel.
    const auto p = a.at(kind).get<std::vector<float>>();
    if (p.size() != 2) throw std::invalid_argument("click_object takes [x, y] in viewport pixels");
    std::string error = session.clickObject(p[0], p[1], app.viewportWidth(), app.viewportHeight());
    const std::string picked = session.activeObject().path();
    if (error.empty() && picked.empty() && a.value("must_hit", true))
      error = "the click at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
              ") meets no obstacle or cloth";
    app.report(error.empty() ? (picked.empty() ? "nothing there: gizmo off" : "gizmo on " + picked)
                             : error,
               !error.empty());
    if (const std::optional<bool> next = checkOutcome(a, error, "it succeeded")) return *next;
  } else if (kind == "box_select") {
    const auto r = a.at("box_select").get<std::vector<float>>();
    if (r.size() != 4)
      throw std::invalid_argument("box_select takes [x0, y0, x1, y1] in viewport pixels");
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
    session.playback().scrub(a.at("scrub").get<int>(), session.timelineFrames());
  } else if (kind == "step") {
    session.playback().step(a.at("step").get<int>(), session.timelineFrames());
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
    const std::string warning =
        s.is_string() ? session.saveAs(s.get<std::string>()) : session.save();
    app.report(warning.empty() ? "saved " + session.document().file() : warning, !warning.empty());
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
  } else if (kind == "screenshot" && a.value("overlays", false)) {
    // The viewport as the window shows it, with what the editor draws over the picture (the
    // gizmo, the selection, target lines): cut from the last drawn window, so at its size.
    if (a.contains("size"))
      throw std::invalid_argument("a screenshot with overlays has the viewport's own size");
    const render::Image window = app.windowImage();
    render::Image image(app.viewportWidth(), app.viewportHeight());
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const int wx = std::min(app.viewportX() + x, window.width - 1),
                  wy = std::min(app.viewportY() + y, window.height - 1);
        std::copy(window.at(wx, wy), window.at(wx, wy) + 3, image.at(x, y));
      }
    render::writePng(outputFile(a.at("screenshot")), image);
  } else if (kind == "screenshot") {
    int w = app.viewportWidth(), h = app.viewportHeight();
    if (a.contains("size")) {
      const auto s = a["size"].get<std::vector<int>>();
      if (s.size() != 2 || s[0] <= 0 || s[1] <= 0)
        throw std::invalid_argument("size must be [width, height]");
      w = s[0], h = s[1];
    }
    render::writePng(outputFile(a.at("screenshot")), app.viewportImage(w, h));
  } else if (kind == "window_screenshot") {
    render::writePng(outputFile(a.at("window_screenshot")), app.windowImage());
  } else if (kind == "frames") {
    if (waitFrames_ == 0) waitFrames_ = std::max(1, a.at("frames").get<int>());
    return --waitFrames_ == 0;
  } else if (kind == "expect") {
    const nlohmann::json state = stateOf(session, app);
    for (const auto& [key, expected] : a.at("expect").items()) {
      if (key == "value") {
        const std::string path = expected.at("path").get<std::string>();
        const nlohmann::json* actual = doc.find(path);
        if (!actual || *actual != expected.at("equals")) {
          fail(path + " is " + (actual ? actual->dump() : "absent") + ", expected " +
               expected.at("equals").dump());
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
    std::ofstream out(outputFile(a.at("write_state")));
    out << stateOf(session, app).dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write " + a["write_state"].get<std::string>());
  } else if (kind == "import_garment" || kind == "add_mesh_obstacle" || kind == "add_obstacle" ||
             kind == "set_targets" || kind == "target" || kind == "move_targets" ||
             kind == "drag_targets" || kind == "remove_targets" || kind == "load_target_motion" ||
             kind == "remove_target_motion" || kind == "optimize_apply" ||
             kind == "optimize_revert") {
    // Edits that may be refused: the refusal is the UI's message, and fails the action unless
    // the script expects it ("expect_error": text it must contain).
    std::string error;
    if (kind == "import_garment")
      error = session.importGarment(importOptions(a, kind));
    else if (kind == "add_mesh_obstacle")
      error = session.importMeshObstacle(importOptions(a, kind));
    else if (kind == "add_obstacle")
      error = session.addObstacle(a.at(kind).get<std::string>());
    else if (kind == "set_targets")
      error = session.setTargetsFromSelection();
    else if (kind == "target")
      error = session.setTarget(a.at(kind).get<int>(), vec3Of(a.at("position"), "position"));
    else if (kind == "move_targets")
      error = session.moveTargets(session.selection().nodes(), vec3Of(a.at(kind), "move_targets"));
    else if (kind == "drag_targets") {
      const auto d = a.at(kind).get<std::vector<float>>();
      if (d.size() != 2)
        throw std::invalid_argument("drag_targets takes [dx, dy] in viewport pixels");
      error = session.dragTargets(session.selection().nodes(), d[0], d[1], app.viewportWidth(),
                                  app.viewportHeight());
    } else if (kind == "remove_targets")
      error = session.removeTargets(a.at(kind).is_array() ? a[kind].get<std::vector<int>>()
                                                          : std::vector<int>{});
    else if (kind == "load_target_motion")
      error = session.loadTargetMotion(a.at(kind).get<std::string>());
    else if (kind == "remove_target_motion")
      error = session.removeTargetMotion();
    else if (kind == "optimize_apply")
      error = session.applyOptimizerResult();
    else if (kind == "optimize_revert")
      error = session.revertToOptimizerStart();
    // The message the panel's own button would show.
    std::string done = kind + " done";
    if (kind == "import_garment")
      done = "imported " + a[kind].get<std::string>();
    else if (kind == "add_mesh_obstacle")
      done = "added mesh obstacle " + a[kind].get<std::string>();
    else if (kind == "optimize_apply")
      done = "applied the optimised parameters (Ctrl+Z undoes)";
    else if (kind == "optimize_revert")
      done = "reverted to the values the run started from";
    app.report(error.empty() ? done : error, !error.empty());
    if (const std::optional<bool> next = checkOutcome(a, error, "it succeeded")) return *next;
  } else if (kind == "gizmo" || kind == "make_handle" || kind == "handle_offset" ||
             kind == "set_key" || kind == "delete_key" || kind == "jump_key") {
    std::string error;
    if (kind == "gizmo")
      error = session.setActiveObject(a.at(kind).is_null() ? "" : a[kind].get<std::string>());
    else if (kind == "make_handle")
      error = session.makeHandle();
    else if (kind == "handle_offset")
      error = session.setHandleOffset(vec3Of(a.at(kind), "handle_offset"));
    else if (kind == "set_key")
      error = session.setKey();
    else if (kind == "delete_key")
      error = session.deleteKey();
    else
      error = session.jumpToKey(a.at(kind).get<int>());
    app.report(error.empty() ? kind + " done" : error, !error.empty());
    if (const std::optional<bool> next = checkOutcome(a, error, "it succeeded")) return *next;
  } else if (kind == "gizmo_drag") {
    // A mouse drag over several UI frames: pressed on the handle (found by the same ray pick as
    // a click), moved in `steps` equal moves to `by` pixels away, released.
    const int steps = std::max(1, a.value("steps", 4));
    if (gizmoStep_ == 0) {
      const std::string error = startGizmoDrag(a, session, app);
      if (!error.empty()) app.report(error, true);
      if (const std::optional<bool> next = checkOutcome(a, error, "the drag started")) return *next;
      gizmoStep_ = 1;
      return false;
    }
    const Eigen::Vector2f at = gizmoFrom_ + gizmoBy_ * (float(gizmoStep_) / float(steps));
    const std::string error = session.dragGizmo(at.x(), at.y());
    if (!error.empty()) {
      session.endGizmoDrag();
      gizmoStep_ = 0;
      fail(error);
      return false;
    }
    if (gizmoStep_ < steps) {
      ++gizmoStep_;
      return false;
    }
    session.endGizmoDrag();
    gizmoStep_ = 0;
  } else if (kind == "panel") {
    PanelTab tab;
    if (!parsePanelTab(a.at(kind).get<std::string>(), tab))
      throw std::invalid_argument("panel must be scene, inspect, targets or optimise");
    app.showTab(tab);
  } else if (kind == "contact_colours") {
    session.contactColours = a.at(kind).get<bool>();
  } else if (kind == "force_arrows") {
    session.forceArrows = a.at(kind).get<bool>();
  } else if (kind == "load_target_mesh" || kind == "set_hemline" || kind == "remove_hemline") {
    const std::string error = kind == "load_target_mesh"
                                  ? session.loadTargetMesh(a.at(kind).get<std::string>())
                              : kind == "set_hemline" ? session.setHemline(a.at(kind).get<double>())
                                                      : session.removeHemline();
    app.report(error.empty() ? kind + " done" : error, !error.empty());
    if (const std::optional<bool> next = checkOutcome(a, error, "it succeeded")) return *next;
  } else if (kind == "compute_gradient") {
    // Starts the backward pass off the UI thread, then waits for it one frame at a time, as a
    // person would watch the inspector.
    if (!waitingForGradient_) {
      const std::string error = session.computeStateGradients();
      if (!error.empty() || a.contains("expect_error")) {
        app.report(error.empty() ? "loss gradient started" : error, !error.empty());
        if (const std::optional<bool> next = checkOutcome(a, error, "it started")) return *next;
      }
      waitingForGradient_ = true;
      waitStarted_ = now();
      return false;
    }
    if (session.computingStateGradients()) {
      if (now() - waitStarted_ > a.value("timeout_seconds", 300.0)) {
        fail("the loss gradient did not arrive within the timeout");
        waitingForGradient_ = false;
      }
      return false;
    }
    waitingForGradient_ = false;
    if (!session.stateGradientError().empty()) {
      fail(session.stateGradientError(), 3);
      return false;
    }
    app.report("loss gradient computed", false);
  } else if (kind == "add_parameter" || kind == "remove_parameter") {
    const std::string path = a.at(kind).get<std::string>();
    const std::string error = kind == "add_parameter" ? session.addTaskParameter(path)
                                                      : session.removeTaskParameter(path);
    app.report(error.empty() ? (kind == "add_parameter" ? "added " : "removed ") + path : error,
               !error.empty());
    if (const std::optional<bool> next = checkOutcome(a, error, "the parameter changed"))
      return *next;
  } else if (kind == "optimize") {
    const nlohmann::json& o = a.at(kind);
    OptimizerRun::Setup setup;
    setup.method = o.value("method", std::string("lbfgsb"));
    if (o.contains("parameters")) {
      setup.parameters = o["parameters"].get<std::vector<std::string>>();
    } else if (const Scene* scene = session.document().scene(); scene && scene->task) {
      setup.parameters = scene->task->parameters;
    }
    setup.settings.maxEvaluations = o.value("max_evaluations", 0);
    setup.settings.learningRate = o.value("learning_rate", setup.settings.learningRate);
    setup.settings.seed = o.value("seed", 0u);
    const std::string error = session.startOptimizer(setup, o.value("paused", true));
    app.report(error.empty() ? "optimiser started" : error, !error.empty());
    if (const std::optional<bool> next = checkOutcome(o, error, "the optimiser started"))
      return *next;
  } else if (kind == "optimize_step" || kind == "optimize_wait") {
    // Waits, one UI frame at a time, until N more evaluations are logged (step) or the run has
    // ended (wait), so the optimiser runs off the UI thread exactly as when clicked.
    OptimizerRun& run = session.optimizer();
    if (!waitingForOptimizer_) {
      if (run.status() == OptimizerRun::Status::Idle) {
        fail("no optimiser run: start one with {\"optimize\": {...}}");
        return false;
      }
      optimizerTarget_ =
          run.evaluations() + (kind == "optimize_step" ? std::max(1, a.at(kind).get<int>()) : 0);
      if (kind == "optimize_step")
        run.step(optimizerTarget_ - run.evaluations());
      else
        run.resume();
      waitingForOptimizer_ = true;
      waitStarted_ = now();
      timeout_ = a.value("timeout_seconds", 300.0);
      return false;
    }
    const bool ended = !run.active();
    const bool reached = kind == "optimize_step" && run.evaluations() >= optimizerTarget_ &&
                         (run.status() == OptimizerRun::Status::Paused || ended);
    if (!ended && !reached) {
      if (now() - waitStarted_ > timeout_) {
        run.cancel();
        fail("the optimiser did not get there within " + std::to_string(timeout_) + " s");
      }
      return false;
    }
    waitingForOptimizer_ = false;
    if (run.status() == OptimizerRun::Status::Failed) {
      fail("optimisation failed: " + run.error(), 3);
      return false;
    }
  } else if (kind == "optimize_resume") {
    session.optimizer().resume();
  } else if (kind == "optimize_pause") {
    session.optimizer().pause();
  } else if (kind == "optimize_cancel") {
    session.optimizer().cancel();
  } else {
    fail("unknown action \"" + kind + "\"");
    return false;
  }
  return true;
}

}  // namespace weft::editor
