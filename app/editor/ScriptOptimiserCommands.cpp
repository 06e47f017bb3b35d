// Script commands on the task's parameters and the optimiser: choosing parameters, starting a
// run, stepping or waiting for it, pausing, cancelling, and writing its result into the scene.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

#include <algorithm>

namespace weft::editor {
namespace {

bool changeParameter(ScriptCall& call) {
  const std::string path = call.action.at(call.kind).get<std::string>();
  const bool add = call.kind == "add_parameter";
  const std::string error = add ? call.session.optimisation().addParameter(path)
                                : call.session.optimisation().removeParameter(path);
  call.app.report(error.empty() ? (add ? "added " : "removed ") + path : error, !error.empty());
  return call.checkOutcome(call.action, error, "the parameter changed").value_or(true);
}

bool optimize(ScriptCall& call) {
  const nlohmann::json& o = call.action.at(call.kind);
  OptimizerRun::Setup setup;
  setup.method = o.value("method", std::string("lbfgsb"));
  if (o.contains("parameters")) {
    setup.parameters = o["parameters"].get<std::vector<std::string>>();
  } else if (const Scene* scene = call.session.document().scene(); scene && scene->task) {
    setup.parameters = scene->task->parameters;
  }
  setup.settings.maxEvaluations = o.value("max_evaluations", 0);
  setup.settings.learningRate = o.value("learning_rate", setup.settings.learningRate);
  setup.settings.seed = o.value("seed", 0u);
  const std::string error = call.session.optimisation().start(setup, o.value("paused", true));
  call.app.report(error.empty() ? "optimiser started" : error, !error.empty());
  // expect_error sits in the optimize object, with the run's settings.
  return call.checkOutcome(o, error, "the optimiser started").value_or(true);
}

bool stepOrWait(ScriptCall& call) {
  // Waits, one UI frame at a time, until N more evaluations are logged (step) or the run has
  // ended (wait), so the optimiser runs off the UI thread exactly as when clicked.
  OptimizerRun& run = call.session.optimisation().optimizer();
  ScriptProgress& progress = call.progress;
  const bool step = call.kind == "optimize_step";
  if (!progress.waitingForOptimizer) {
    if (run.status() == OptimizerRun::Status::Idle) {
      call.fail("no optimiser run: start one with {\"optimize\": {...}}");
      return false;
    }
    progress.optimizerTarget =
        run.evaluations() + (step ? std::max(1, intOf(call.action.at(call.kind))) : 0);
    if (step)
      run.step(progress.optimizerTarget - run.evaluations());
    else
      run.resume();
    progress.waitingForOptimizer = true;
    progress.waitStarted = scriptClock();
    progress.timeout = call.action.value("timeout_seconds", 300.0);
    return false;
  }
  const bool ended = !run.active();
  const bool reached = step && run.evaluations() >= progress.optimizerTarget &&
                       (run.status() == OptimizerRun::Status::Paused || ended);
  if (!ended && !reached) {
    if (scriptClock() - progress.waitStarted > progress.timeout) {
      run.cancel();
      call.fail("the optimiser did not get there within " + std::to_string(progress.timeout) +
                " s");
    }
    return false;
  }
  progress.waitingForOptimizer = false;
  if (run.status() == OptimizerRun::Status::Failed) {
    call.fail("optimisation failed: " + run.error(), 3);
    return false;
  }
  return true;
}

bool resume(ScriptCall& call) {
  call.session.optimisation().optimizer().resume();
  return true;
}

bool pause(ScriptCall& call) {
  call.session.optimisation().optimizer().pause();
  return true;
}

bool cancel(ScriptCall& call) {
  call.session.optimisation().optimizer().cancel();
  return true;
}

bool apply(ScriptCall& call) {
  return call.reportOutcome(call.session.optimisation().applyResult(),
                            "applied the optimised parameters (Ctrl+Z undoes)");
}

bool revert(ScriptCall& call) {
  return call.reportOutcome(call.session.optimisation().revertToStart(),
                            "reverted to the values the run started from");
}

}  // namespace

void addOptimiserCommands(ScriptCommandTable& table) {
  table["add_parameter"] = changeParameter;
  table["remove_parameter"] = changeParameter;
  table["optimize"] = optimize;
  table["optimize_step"] = stepOrWait;
  table["optimize_wait"] = stepOrWait;
  table["optimize_resume"] = resume;
  table["optimize_pause"] = pause;
  table["optimize_cancel"] = cancel;
  table["optimize_apply"] = apply;
  table["optimize_revert"] = revert;
}

}  // namespace weft::editor
