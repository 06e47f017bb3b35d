#pragma once
// Headless automation: a JSON script of editor actions, run one action per UI frame through
// the same EditorSession and EditorApp a person uses (so every action is followed by at least
// one real UI frame). The format is documented in README ("Editor"); in short
//
//   { "actions": [ {"open": "scene.json"}, {"set": "time.steps", "value": 10},
//                  {"select": [0, 16]}, {"pin": true}, {"simulate": 10}, {"scrub": 5},
//                  {"save": "out.json"}, {"screenshot": "view.png", "size": [320, 240]} ] }
//
// A failing action stops the script with an error naming the script, the action's index and
// kind, and what went wrong.

#include "ScriptedInput.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <deque>
#include <functional>
#include <optional>
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
  bool run(const nlohmann::json& action, EditorSession& session, EditorApp& app);  // false: wait
  void fail(const std::string& what, int code = 2);
  // Presses the mouse on the gizmo handle a gizmo_drag action names; error text or "".
  std::string startGizmoDrag(const nlohmann::json& action, EditorSession& session, EditorApp& app);
  // What an action's `error` means given its optional expect_error: a value to return from the
  // step (pass or fail), or nullopt to go on.
  // A raw-input action: queued as one change of the input per frame, then played a step per
  // update (each step read by the following frame). True when all steps have been read.
  bool playInput(const nlohmann::json& action, const std::string& kind, EditorApp& app);
  void queueInput(const nlohmann::json& action, const std::string& kind, EditorApp& app);
  std::optional<bool> checkOutcome(const nlohmann::json& action, const std::string& error,
                                   const std::string& succeeded);

  std::string file_;
  nlohmann::json actions_;
  std::size_t next_ = 0;
  int waitFrames_ = 0;
  bool waitingForSimulation_ = false;
  bool waitingForOptimizer_ = false;
  bool waitingForGradient_ = false;
  int optimizerTarget_ = 0;  // evaluations an optimize_step waits for
  int gizmoStep_ = 0;        // mouse moves of a gizmo_drag done so far (0: not started)
  Eigen::Vector2f gizmoFrom_ = Eigen::Vector2f::Zero(), gizmoBy_ = Eigen::Vector2f::Zero();
  ScriptedInput input_;
  std::deque<std::function<void(ScriptedInput&)>> inputSteps_;
  bool inputQueued_ = false;
  double waitStarted_ = 0.0;
  double timeout_ = 300.0;
  std::string error_;
  int exitCode_ = 0;
  State state_ = State::Running;
};

}  // namespace weft::editor
