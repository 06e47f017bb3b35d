// Script commands on the simulation and the timeline: simulate (and wait for it), cancel, scrub,
// step, play, pause, and letting UI frames pass.
#include "EditorSession.h"
#include "ScriptCommands.h"

#include <algorithm>

namespace weft::editor {
namespace {

bool simulate(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  ScriptProgress& progress = call.progress;
  SimulationCache& cache = call.session.cache();
  if (!progress.waitingForSimulation) {
    const nlohmann::json& s = a.at("simulate");
    const int steps = s.is_number_integer() ? intOf(s) : -1;
    const std::string error = call.session.timeline().simulate(steps);
    if (!error.empty()) {
      call.fail(error);
      return false;
    }
    if (!a.value("wait", true)) return true;
    progress.waitingForSimulation = true;
    progress.waitStarted = scriptClock();
    progress.timeout = a.value("timeout_seconds", 300.0);
    return false;  // at least one UI frame while it runs
  }
  if (cache.running()) {
    if (scriptClock() - progress.waitStarted > progress.timeout) {
      cache.cancel();
      call.fail("the simulation did not finish within " + std::to_string(progress.timeout) + " s");
    }
    return false;
  }
  if (cache.status() == SimulationCache::Status::Failed) {
    call.fail("simulation failed: " + cache.error(), 3);
    return false;
  }
  return true;
}

// Lets UI frames pass until the simulation running (one the Simulate button started) ends;
// done at once when none runs. Fails after "timeout_seconds" (default 300).
bool waitSimulation(ScriptCall& call) {
  ScriptProgress& progress = call.progress;
  SimulationCache& cache = call.session.cache();
  if (!progress.waitingForSimulation) {
    progress.waitingForSimulation = true;
    progress.waitStarted = scriptClock();
    progress.timeout = call.action.value("timeout_seconds", 300.0);
  }
  if (cache.running()) {
    if (scriptClock() - progress.waitStarted > progress.timeout) {
      cache.cancel();
      call.fail("the simulation did not finish within " + std::to_string(progress.timeout) + " s");
    }
    return false;
  }
  return true;
}

bool cancel(ScriptCall& call) {
  call.session.cache().cancel();
  return true;
}

bool scrub(ScriptCall& call) {
  call.session.playback().scrub(intOf(call.action.at("scrub")), call.session.timeline().frames());
  return true;
}

bool step(ScriptCall& call) {
  call.session.playback().step(intOf(call.action.at("step")), call.session.timeline().frames());
  return true;
}

bool play(ScriptCall& call) {
  call.session.playback().play();
  return true;
}

bool pause(ScriptCall& call) {
  call.session.playback().pause();
  return true;
}

bool frames(ScriptCall& call) {
  int& wait = call.progress.waitFrames;
  if (wait == 0) wait = std::max(1, intOf(call.action.at("frames")));
  return --wait == 0;
}

}  // namespace

void addPlaybackCommands(ScriptCommandTable& table) {
  table["simulate"] = simulate;
  table["wait_simulation"] = waitSimulation;
  table["cancel"] = cancel;
  table["scrub"] = scrub;
  table["step"] = step;
  table["play"] = play;
  table["pause"] = pause;
  table["frames"] = frames;
}

}  // namespace weft::editor
