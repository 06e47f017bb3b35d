#pragma once
// Headless automation: a JSON script of editor actions, run one action per UI frame through
// the same EditorSession and EditorApp a person uses (so every action is followed by at least
// one real UI frame). The format is documented in docs/editor.md ("Scripted, headless"); in short
//
//   { "actions": [ {"open": "scene.json"}, {"set": "time.steps", "value": 10},
//                  {"select": [0, 16]}, {"pin": true}, {"simulate": 10}, {"scrub": 5},
//                  {"save": "out.json"}, {"screenshot": "view.png", "size": [320, 240]} ] }
//
// A failing action stops the script with an error naming the script, the action's index and
// kind, and what went wrong. Each action is run by its command (ScriptCommands.h).

#include "ScriptCall.h"
#include "ScriptedInput.h"

#include <nlohmann/json.hpp>

#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class ScriptRunner {
 public:
  // Throws InputError when the file cannot be read or is not a script.
  explicit ScriptRunner(const std::string& file);

  enum class State { Running, Finished, Failed };
  // Runs the next action (or keeps waiting for one in progress). Call once per UI frame,
  // after the frame has been drawn.
  State update(EditorSession& session, EditorApp& app);

  const std::string& error() const { return error_; }  // "<script>: actions.N (kind): what"
  int exitCode() const { return exitCode_; }        // 0, 2 (failing action), 3 (simulation failed)
  std::size_t nextAction() const { return next_; }  // index of the action running or next

  // The mouse and keyboard the raw-input actions (mouse_move, mouse_drag, key...) set: the
  // platform writes it into ImGui's IO before each frame.
  ScriptedInput& input() { return input_; }

 private:
  std::string file_;
  nlohmann::json actions_;
  std::size_t next_ = 0;
  ScriptProgress progress_;  // of the action running
  ScriptedInput input_;
  std::string error_;
  int exitCode_ = 0;
  State state_ = State::Running;
};

}  // namespace weft::editor
