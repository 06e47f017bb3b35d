// Script commands on the transform gizmo and handles: the object it places, a drag of one of its
// handles over several frames, making a handle of the selection, and its keys.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

#include <algorithm>

namespace weft::editor {
namespace {

bool done(ScriptCall& call, const std::string& error) {
  return call.reportOutcome(error, call.kind + " done");
}

bool gizmo(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  return done(call, call.session.placement().setActiveObject(
                        a.at(call.kind).is_null() ? "" : a[call.kind].get<std::string>()));
}

bool makeHandle(ScriptCall& call) {
  return done(call, call.session.selecting().makeHandle());
}

bool handleOffset(ScriptCall& call) {
  return done(call, call.session.placement().setHandleOffset(
                        vec3Of(call.action.at(call.kind), "handle_offset")));
}

bool setKey(ScriptCall& call) {
  return done(call, call.session.placement().setKey());
}

bool deleteKey(ScriptCall& call) {
  return done(call, call.session.placement().deleteKey());
}

bool jumpKey(ScriptCall& call) {
  return done(call, call.session.placement().jumpToKey(intOf(call.action.at(call.kind))));
}

// Presses the mouse on the gizmo handle a gizmo_drag action names; error text or "".
std::string startGizmoDrag(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  EditorSession& session = call.session;
  ScriptProgress& progress = call.progress;
  GizmoHandle handle;
  if (!parseGizmoHandle(a.at("gizmo_drag").get<std::string>(), handle))
    throw std::invalid_argument(
        "gizmo_drag takes translate_x, translate_y, translate_z, rotate_x, rotate_y or rotate_z");
  const auto by = a.at("by").get<std::vector<float>>();
  if (by.size() != 2) throw std::invalid_argument("by takes [dx, dy] in viewport pixels");
  progress.gizmoBy = Eigen::Vector2f(by[0], by[1]);
  const int w = call.app.viewportWidth(), h = call.app.viewportHeight();
  const auto g = session.placement().gizmo(w, h);
  if (!g)
    return session.placement().activeObject().kind == EditorObject::Kind::None
               ? "nothing to move: choose an object with {\"gizmo\": PATH}"
               : "the gizmo is not shown (the scene does not validate)";
  if (!g->has(handle))
    return std::string("this object has no ") + gizmoHandleName(handle) + " handle";
  // The press: at a given pixel, at an offset from the gizmo's centre on screen, or where the
  // handle can be grabbed.
  Eigen::Vector2f& from = progress.gizmoFrom;
  bool inView = true;
  if (a.contains("from") || a.contains("from_centre")) {
    const std::string key = a.contains("from") ? "from" : "from_centre";
    const auto f = a[key].get<std::vector<float>>();
    if (f.size() != 2) throw std::invalid_argument(key + " takes [x, y] in viewport pixels");
    from = Eigen::Vector2f(f[0], f[1]);
    if (key == "from_centre") {
      const auto centre = projectToPixel(session.camera(), g->origin(), w, h);
      inView = centre.has_value();
      if (centre) from += *centre;
    }
  } else {
    const auto grab = g->grabPixel(handle);
    inView = grab.has_value();
    if (grab) from = *grab;
  }
  if (!inView) return std::string("the ") + gizmoHandleName(handle) + " handle is not in view";
  const GizmoHandle picked = g->pickPixel(from.x(), from.y());
  if (picked != handle)
    return "the press at (" + std::to_string(from.x()) + ", " + std::to_string(from.y()) +
           ") grabs " + gizmoHandleName(picked) + ", not " + gizmoHandleName(handle);
  return session.placement().beginGizmoDrag(handle, from.x(), from.y(), w, h);
}

bool gizmoDrag(ScriptCall& call) {
  // A mouse drag over several UI frames: pressed on the handle (found by the same ray pick as
  // a click), moved in `steps` equal moves to `by` pixels away, released.
  ScriptProgress& progress = call.progress;
  const int steps = std::max(1, call.action.value("steps", 4));
  if (progress.gizmoStep == 0) {
    const std::string error = startGizmoDrag(call);
    if (!error.empty()) call.app.report(error, true);
    if (const std::optional<bool> next = call.checkOutcome(call.action, error, "the drag started"))
      return *next;
    progress.gizmoStep = 1;
    return false;
  }
  const Eigen::Vector2f at =
      progress.gizmoFrom + progress.gizmoBy * (float(progress.gizmoStep) / float(steps));
  const std::string error = call.session.placement().dragGizmo(at.x(), at.y());
  if (!error.empty()) {
    call.session.placement().endGizmoDrag();
    progress.gizmoStep = 0;
    call.fail(error);
    return false;
  }
  if (progress.gizmoStep < steps) {
    ++progress.gizmoStep;
    return false;
  }
  call.session.placement().endGizmoDrag();
  progress.gizmoStep = 0;
  return true;
}

}  // namespace

void addHandleCommands(ScriptCommandTable& table) {
  table["gizmo"] = gizmo;
  table["gizmo_drag"] = gizmoDrag;
  table["make_handle"] = makeHandle;
  table["handle_offset"] = handleOffset;
  table["set_key"] = setKey;
  table["delete_key"] = deleteKey;
  table["jump_key"] = jumpKey;
}

}  // namespace weft::editor
