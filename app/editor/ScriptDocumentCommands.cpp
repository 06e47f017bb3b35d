// Script commands on the document as a whole: open, new, close, save, edits of a value by its
// JSON path, undo and redo.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

namespace weft::editor {
namespace {

bool close(ScriptCall& call) {
  // What the window's close button does (main.cpp: glfwWindowShouldClose): a dirty document
  // asks first; a confirmed close ends the run.
  call.app.requestClose();
  return true;
}

bool open(ScriptCall& call) {
  call.session.open(call.action.at("open").get<std::string>());
  call.session.frameCamera(call.aspect());
  return true;
}

bool newDocument(ScriptCall& call) {
  call.session.newDocument();
  return true;
}

bool setOrRemove(ScriptCall& call) {
  EditorDocument& doc = call.session.document();
  const std::string path = call.action.at(call.kind).get<std::string>();
  // As `weft simulate --set`: the parent must exist (no objects are created on the way).
  std::string error = call.kind == "set" ? doc.setValue(path, call.action.at("value"), false, false)
                                         : doc.removeValue(path);
  if (error.empty() && !doc.valid()) error = doc.validationError();
  if (call.action.contains("expect_error"))
    return *call.checkOutcome(call.action, error, "the scene is valid");
  if (!error.empty() && !call.action.value("allow_invalid", false)) {
    call.fail(error);
    return false;
  }
  return true;
}

bool undoOrRedo(ScriptCall& call) {
  EditorDocument& doc = call.session.document();
  if (!(call.kind == "undo" ? doc.undo() : doc.redo())) {
    call.fail("nothing to " + call.kind);
    return false;
  }
  return true;
}

bool save(ScriptCall& call) {
  const nlohmann::json& s = call.action.at("save");
  const std::string warning =
      s.is_string() ? call.session.saveAs(s.get<std::string>()) : call.session.save();
  call.app.report(warning.empty() ? "saved " + call.session.document().file() : warning,
                  !warning.empty());
  return true;
}

}  // namespace

void addDocumentCommands(ScriptCommandTable& table) {
  table["close"] = close;
  table["open"] = open;
  table["new"] = newDocument;
  table["set"] = setOrRemove;
  table["remove"] = setOrRemove;
  table["undo"] = undoOrRedo;
  table["redo"] = undoOrRedo;
  table["save"] = save;
}

}  // namespace weft::editor
