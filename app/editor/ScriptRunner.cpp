#include "ScriptRunner.h"

#include "ScriptCommands.h"

#include <weft/core/Error.h>

#include <fstream>

namespace weft::editor {

ScriptRunner::ScriptRunner(const std::string& file) : file_(file) {
  std::ifstream in(file);
  if (!in) throw InputError(file, "-", "cannot read the script");
  nlohmann::json script;
  try {
    script = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range (1e400).
    throw InputError(file, "-", std::string("not valid JSON: ") + e.what());
  }
  if (script.is_object() && script.contains("actions")) script = script["actions"];
  if (!script.is_array()) throw InputError(file, "actions", "must be a list of actions");
  actions_ = std::move(script);
}

ScriptRunner::State ScriptRunner::update(EditorSession& session, EditorApp& app) {
  if (state_ != State::Running) return state_;
  if (next_ >= actions_.size()) return state_ = State::Finished;
  const nlohmann::json& action = actions_[next_];
  const std::string kind = scriptActionKind(action);
  ScriptCall call(action, kind, session, app, progress_, input_);
  bool done = false;
  try {
    const ScriptCommandTable& commands = scriptCommands();
    if (!action.is_object())
      call.fail("an action must be an object such as {\"open\": \"scene.json\"}");
    else if (const auto command = commands.find(kind); command == commands.end())
      call.fail("unknown action \"" + kind + "\"");
    else
      done = command->second(call);
  } catch (const std::exception& e) {
    call.fail(e.what());
  }
  if (call.failed()) {
    error_ = file_ + ": actions." + std::to_string(next_) + " (" + kind + "): " + call.failure();
    exitCode_ = call.exitCode();
    state_ = State::Failed;
  }
  if (done) {
    ++next_;
    progress_.waitingForSimulation = false;
    progress_.waitFrames = 0;
  }
  return state_;
}

}  // namespace weft::editor
