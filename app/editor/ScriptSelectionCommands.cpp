// Script commands that pick: vertices (by number, click, box, border loop, band), the object the
// gizmo places (Ctrl+click), and pinning the selection.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

namespace weft::editor {
namespace {

bool select(ScriptCall& call) {
  const std::string error = call.session.selecting().selectNodes(intsOf(call.action.at(call.kind)),
                                                                 call.kind == "select_add");
  if (!error.empty()) {
    call.fail(error);
    return false;
  }
  return true;
}

bool selectRegion(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  std::string error;
  const bool add = a.value("add", false);
  if (call.kind == "select_loop") {
    error = call.session.selecting().selectBoundaryLoop(add);
  } else {
    const nlohmann::json& band = a.at(call.kind);
    const std::string axis = band.at("axis").get<std::string>();
    const int index = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
    error = call.session.selecting().selectBand(index, band.at("min").get<double>(),
                                                band.at("max").get<double>(), add);
  }
  return call.checkOutcome(a, error, "the selection changed").value_or(true);
}

bool clearSelection(ScriptCall& call) {
  call.session.selection().clear();
  return true;
}

bool click(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  const auto p = a.at("click").get<std::vector<float>>();
  if (p.size() != 2) throw std::invalid_argument("click takes [x, y] in viewport pixels");
  const auto vertex = call.session.selecting().clickSelect(
      p[0], p[1], call.app.viewportWidth(), call.app.viewportHeight(), a.value("add", false));
  if (!vertex && a.value("must_hit", true)) {
    call.fail("the click at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
              ") hits no cloth triangle");
    return false;
  }
  return true;
}

bool clickObject(ScriptCall& call) {
  // Ctrl+click: what the gizmo places becomes the obstacle or cloth under the pixel.
  const nlohmann::json& a = call.action;
  const auto p = a.at(call.kind).get<std::vector<float>>();
  if (p.size() != 2) throw std::invalid_argument("click_object takes [x, y] in viewport pixels");
  std::string error = call.session.placement().clickObject(p[0], p[1], call.app.viewportWidth(),
                                                           call.app.viewportHeight());
  const std::string picked = call.session.placement().activeObject().path();
  if (error.empty() && picked.empty() && a.value("must_hit", true))
    error = "the click at (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
            ") meets no obstacle or cloth";
  call.app.report(
      error.empty() ? (picked.empty() ? "nothing there: gizmo off" : "gizmo on " + picked) : error,
      !error.empty());
  return call.checkOutcome(a, error, "it succeeded").value_or(true);
}

bool boxSelect(ScriptCall& call) {
  const auto r = call.action.at("box_select").get<std::vector<float>>();
  if (r.size() != 4)
    throw std::invalid_argument("box_select takes [x0, y0, x1, y1] in viewport pixels");
  call.session.selecting().boxSelectPixels(r[0], r[1], r[2], r[3], call.app.viewportWidth(),
                                           call.app.viewportHeight(),
                                           call.action.value("add", false));
  return true;
}

bool pin(ScriptCall& call) {
  const std::string error = call.session.selecting().pinSelection();
  if (!error.empty()) {
    call.fail(error);
    return false;
  }
  return true;
}

}  // namespace

void addSelectionCommands(ScriptCommandTable& table) {
  table["select"] = select;
  table["select_add"] = select;
  table["select_loop"] = selectRegion;
  table["select_band"] = selectRegion;
  table["clear_selection"] = clearSelection;
  table["click"] = click;
  table["click_object"] = clickObject;
  table["box_select"] = boxSelect;
  table["pin"] = pin;
}

}  // namespace weft::editor
