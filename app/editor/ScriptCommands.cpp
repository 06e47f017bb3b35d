#include "ScriptCommands.h"

namespace weft::editor {

const ScriptCommandTable& scriptCommands() {
  static const ScriptCommandTable table = [] {
    ScriptCommandTable t;
    addDocumentCommands(t);
    addSelectionCommands(t);
    addPlaybackCommands(t);
    addViewCommands(t);
    addStateCommands(t);
    addSceneCommands(t);
    addTargetCommands(t);
    addOptimiserCommands(t);
    addHandleCommands(t);
    addInputCommands(t);
    return t;
  }();
  return table;
}

std::string scriptActionKind(const nlohmann::json& action) {
  if (!action.is_object() || action.empty()) return "?";
  // An action object naming two commands runs the one listed first here (the order of the
  // script format's documentation); every name here has a command in the table.
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
                        "wait_simulation",
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
                        "see_through",
                        "obstacles_in_front",
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
                        "close",
                        "provoke_imgui_assertion"})
    if (action.contains(k)) return k;
  return action.begin().key();
}

}  // namespace weft::editor
