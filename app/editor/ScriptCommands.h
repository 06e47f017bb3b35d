#pragma once
// The script's actions (ScriptRunner.h) as a table from action name to command. A command runs
// one action through the session and the app as a person would; it returns false while the
// action needs more UI frames (it is called again after the next one), true once done. Errors
// go through ScriptCall::fail, or are thrown (bad arguments: the runner fails the action with
// the exception's text).
//
// The commands, grouped by what they act on, live in ScriptDocumentCommands.cpp (files, edits
// by path, undo), ScriptSelectionCommands.cpp (vertices and objects picked),
// ScriptPlaybackCommands.cpp (simulation and timeline), ScriptViewCommands.cpp (camera, pictures,
// panels, overlays), ScriptStateCommands.cpp (expectations and state dumps),
// ScriptSceneCommands.cpp (garments and obstacles added), ScriptTargetCommands.cpp (targets, loss
// terms, loss gradient), ScriptOptimiserCommands.cpp, ScriptHandleCommands.cpp (the gizmo and
// handle keys) and ScriptInputCommands.cpp (raw mouse and keyboard input).

#include "ScriptCall.h"

#include <map>
#include <string>
#include <vector>

namespace weft::editor {

using ScriptCommand = bool (*)(ScriptCall&);
using ScriptCommandTable = std::map<std::string, ScriptCommand>;

// Every action name with its command.
const ScriptCommandTable& scriptCommands();

// The action's name: its key naming a command (when an object names several, the first in the
// order the script format lists them), else its first key ("?" for an empty or non-object).
std::string scriptActionKind(const nlohmann::json& action);

// Each group adds its commands to the table.
void addDocumentCommands(ScriptCommandTable& table);
void addSelectionCommands(ScriptCommandTable& table);
void addPlaybackCommands(ScriptCommandTable& table);
void addViewCommands(ScriptCommandTable& table);
void addStateCommands(ScriptCommandTable& table);
void addSceneCommands(ScriptCommandTable& table);
void addTargetCommands(ScriptCommandTable& table);
void addOptimiserCommands(ScriptCommandTable& table);
void addHandleCommands(ScriptCommandTable& table);
void addInputCommands(ScriptCommandTable& table);

}  // namespace weft::editor
