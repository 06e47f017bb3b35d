#pragma once
// One script action as the command that runs it sees it (ScriptCommands.h): the action's JSON,
// the editor it acts on, the state kept across the UI frames an action may take, and how a
// command ends the script (fail) or reports an edit the editor may refuse (checkOutcome).

#include "ScriptedInput.h"

#include <weft/core/Types.h>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace weft::editor {

class EditorApp;
class EditorSession;

// What an action running over several frames keeps between them (a simulation or optimiser
// being waited for, a gizmo drag, queued raw input). The runner clears waitFrames and
// waitingForSimulation once an action is done.
struct ScriptProgress {
  int waitFrames = 0;
  bool waitingForSimulation = false;
  bool waitingForOptimizer = false;
  bool waitingForGradient = false;
  int optimizerTarget = 0;  // evaluations an optimize_step waits for
  int gizmoStep = 0;        // mouse moves of a gizmo_drag done so far (0: not started)
  Eigen::Vector2f gizmoFrom = Eigen::Vector2f::Zero(), gizmoBy = Eigen::Vector2f::Zero();
  std::deque<std::function<void(ScriptedInput&)>> inputSteps;
  bool inputQueued = false;
  double waitStarted = 0.0;
  double timeout = 300.0;
};

class ScriptCall {
 public:
  ScriptCall(const nlohmann::json& action, std::string kind, EditorSession& session, EditorApp& app,
             ScriptProgress& progress, ScriptedInput& input)
      : action(action),
        kind(std::move(kind)),
        session(session),
        app(app),
        progress(progress),
        input(input) {}

  const nlohmann::json& action;
  const std::string kind;  // the action's name ("open", "simulate", ...)
  EditorSession& session;
  EditorApp& app;
  ScriptProgress& progress;
  ScriptedInput& input;  // the mouse and keyboard raw-input actions set

  // Stops the script: `what` goes after "<script>: actions.N (kind): ", `code` is the exit code
  // (2 a failing action, 3 a failed simulation or optimisation).
  void fail(const std::string& what, int code = 2);
  bool failed() const { return failed_; }
  const std::string& failure() const { return failure_; }
  int exitCode() const { return exitCode_; }

  // What an action's `error` means given its optional expect_error (read from `options`, the
  // action or its value): a value to return from the command (pass or fail), or nullopt to go
  // on. An action that expects an error passes when the error names it; any other error fails
  // the script. `succeeded` ends the failure when no error came ("but <succeeded>").
  std::optional<bool> checkOutcome(const nlohmann::json& options, const std::string& error,
                                   const std::string& succeeded);
  // An edit the editor may refuse: the refusal (or `done`) is the UI's message, and fails the
  // action unless the script expects it. The command's return value.
  bool reportOutcome(const std::string& error, const std::string& done);

  // The viewport's aspect ratio as the last frame laid it out.
  float aspect() const;

 private:
  bool failed_ = false;
  std::string failure_;
  int exitCode_ = 0;
};

// Seconds on a steady clock: timeouts of actions that wait.
double scriptClock();
// [x, y, z] of an action (`what` names it in the error).
Vec3 vec3Of(const nlohmann::json& j, const char* what);
// A whole number in int's range (a vertex, a frame, a count), or a list of them; anything else
// throws std::invalid_argument, which fails the action. (json::get<int> of 5e32 would be an
// undefined conversion: found by the editor_script fuzzer.)
int intOf(const nlohmann::json& j);
std::vector<int> intsOf(const nlohmann::json& j);
nlohmann::json jsonOf(const Vec3& v);
// A file a script writes (a screenshot, a state): its folder is made first, as `weft render
// --out` makes its own, so a script can write into a fresh out/.
std::string outputFile(const nlohmann::json& j);

}  // namespace weft::editor
