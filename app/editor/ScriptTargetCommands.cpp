// Script commands on the task's loss: final-frame targets (set, typed, moved, dragged,
// removed, from a mesh), a recorded target motion, the hemline term, and the loss gradient of
// the cached run.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

namespace weft::editor {
namespace {

// The message the panel's own button would show.
bool done(ScriptCall& call, const std::string& error) {
  return call.reportOutcome(error, call.kind + " done");
}

bool setTargets(ScriptCall& call) {
  return done(call, call.session.targets().setTargetsFromSelection());
}

bool target(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  return done(call, call.session.targets().setTarget(intOf(a.at(call.kind)),
                                                     vec3Of(a.at("position"), "position")));
}

bool moveTargets(ScriptCall& call) {
  return done(
      call, call.session.targets().moveTargets(call.session.selection().nodes(),
                                               vec3Of(call.action.at(call.kind), "move_targets")));
}

bool dragTargets(ScriptCall& call) {
  const auto d = call.action.at(call.kind).get<std::vector<float>>();
  if (d.size() != 2) throw std::invalid_argument("drag_targets takes [dx, dy] in viewport pixels");
  return done(call, call.session.targets().dragTargets(call.session.selection().nodes(), d[0], d[1],
                                                       call.app.viewportWidth(),
                                                       call.app.viewportHeight()));
}

bool removeTargets(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  return done(call, call.session.targets().removeTargets(
                        a.at(call.kind).is_array() ? intsOf(a[call.kind]) : std::vector<int>{}));
}

bool loadTargetMotion(ScriptCall& call) {
  return done(
      call, call.session.targets().loadTargetMotion(call.action.at(call.kind).get<std::string>()));
}

bool removeTargetMotion(ScriptCall& call) {
  return done(call, call.session.targets().removeTargetMotion());
}

bool loadTargetMesh(ScriptCall& call) {
  return done(call,
              call.session.targets().loadTargetMesh(call.action.at(call.kind).get<std::string>()));
}

bool setHemline(ScriptCall& call) {
  return done(call, call.session.targets().setHemline(call.action.at(call.kind).get<double>()));
}

bool removeHemline(ScriptCall& call) {
  return done(call, call.session.targets().removeHemline());
}

bool computeGradient(ScriptCall& call) {
  // Starts the backward pass off the UI thread, then waits for it one frame at a time, as a
  // person would watch the inspector.
  const nlohmann::json& a = call.action;
  ScriptProgress& progress = call.progress;
  EditorSession& session = call.session;
  if (!progress.waitingForGradient) {
    const std::string error = session.gradients().compute();
    if (!error.empty() || a.contains("expect_error")) {
      call.app.report(error.empty() ? "loss gradient started" : error, !error.empty());
      if (const std::optional<bool> next = call.checkOutcome(a, error, "it started")) return *next;
    }
    progress.waitingForGradient = true;
    progress.waitStarted = scriptClock();
    return false;
  }
  if (session.gradients().computing()) {
    if (scriptClock() - progress.waitStarted > a.value("timeout_seconds", 300.0)) {
      call.fail("the loss gradient did not arrive within the timeout");
      progress.waitingForGradient = false;
    }
    return false;
  }
  progress.waitingForGradient = false;
  if (!session.gradients().error().empty()) {
    call.fail(session.gradients().error(), 3);
    return false;
  }
  call.app.report("loss gradient computed", false);
  return true;
}

}  // namespace

void addTargetCommands(ScriptCommandTable& table) {
  table["set_targets"] = setTargets;
  table["target"] = target;
  table["move_targets"] = moveTargets;
  table["drag_targets"] = dragTargets;
  table["remove_targets"] = removeTargets;
  table["load_target_motion"] = loadTargetMotion;
  table["remove_target_motion"] = removeTargetMotion;
  table["load_target_mesh"] = loadTargetMesh;
  table["set_hemline"] = setHemline;
  table["remove_hemline"] = removeHemline;
  table["compute_gradient"] = computeGradient;
}

}  // namespace weft::editor
