// Script commands that check or dump the editor's state: expect (values the state must have)
// and write_state (the whole state as JSON), both reading the same snapshot.
#include "EditorApp.h"
#include "EditorSession.h"
#include "PinGroups.h"
#include "ScriptCommands.h"

#include <weft/render/ColorMap.h>

#include <fstream>

namespace weft::editor {
namespace {

nlohmann::json inspectorState(const EditorSession& session) {
  const auto r = session.inspect();
  if (!r) return nullptr;
  nlohmann::json contacts = nlohmann::json::array();
  for (const VertexContact& c : r->contacts)
    contacts.push_back({{"obstacle", c.obstacle},
                        {"partner", c.partner},
                        {"branch", static_cast<int>(c.branch)},
                        {"normal", jsonOf(c.normal)},
                        {"impulse", jsonOf(c.impulse)},
                        {"force", jsonOf(c.force)},
                        {"velocity", jsonOf(c.velocity)},
                        {"friction", c.friction}});
  return {{"node", r->node},
          {"state", r->state},
          {"cloth", r->cloth},
          {"local_vertex", r->localVertex},
          {"position", jsonOf(r->position)},
          {"velocity", jsonOf(r->velocity)},
          {"branch", static_cast<int>(r->branch)},
          {"contact_force", jsonOf(r->contactForce)},
          {"contact_impulse", jsonOf(r->contactImpulse)},
          {"gradient",
           [&] {
             const auto g = session.gradients().at(r->node, r->state);
             return g ? jsonOf(*g) : nlohmann::json(nullptr);
           }()},
          {"contacts", contacts}};
}

nlohmann::json optimizerState(const EditorSession& session) {
  const OptimizerRun& run = session.optimisation().optimizer();
  nlohmann::json losses = nlohmann::json::array(), history = nlohmann::json::array(),
                 unconverged = nlohmann::json::array();
  for (const auto& s : run.samples()) {
    losses.push_back(s.loss);
    history.push_back(s.values);
    unconverged.push_back(s.unconvergedSteps);
  }
  const OptimizerRun::Progress p = run.progress();
  const nlohmann::json progress =
      p.active ? nlohmann::json{{"evaluation", p.evaluation},
                                {"phase", p.phase == PassPhase::Forward ? "forward" : "backward"},
                                {"pass", p.pass},
                                {"done", p.done},
                                {"total", p.total}}
               : nlohmann::json(nullptr);
  const auto best = run.best();
  return {{"status", OptimizerRun::statusName(run.status())},
          {"method", run.method()},
          {"parameters", run.parameters()},
          {"evaluations", losses.size()},
          {"losses", losses},
          {"values", history},
          {"initial_values", run.initialValues()},
          {"best_loss", best ? nlohmann::json(best->loss) : nlohmann::json(nullptr)},
          {"best_values", best ? nlohmann::json(best->values) : nlohmann::json(nullptr)},
          {"stop_reason", run.stopReason()},
          {"unconverged_forward_steps", run.unconvergedForwardSteps()},
          {"unconverged_steps", unconverged},
          {"progress", progress},
          {"error", run.error()}};
}

nlohmann::json stateOf(EditorSession& session, const EditorApp& app) {
  const EditorDocument& doc = session.document();
  nlohmann::json targets = nlohmann::json::object();
  for (const FinalTarget& t : session.targets().all())
    targets[std::to_string(t.node)] = jsonOf(t.position);
  const LossValue& loss = session.targets().liveLoss();
  nlohmann::json terms = nlohmann::json::object();
  for (const auto& [name, value] : loss.terms) terms[name] = value;
  const char* tabs[] = {"scene", "inspect", "targets", "optimise"};
  nlohmann::json gizmo = nullptr;
  if (const auto g = session.placement().gizmo(app.viewportWidth(), app.viewportHeight()))
    gizmo = {{"origin", jsonOf(g->origin().cast<double>())},
             {"rotates", g->rotates()},
             {"dragging", gizmoHandleName(session.placement().draggedHandle())}};
  nlohmann::json keys = nlohmann::json::array();
  for (const HandleKey& k : session.placement().keys())
    keys.push_back({{"time", k.time}, {"offset", jsonOf(k.offset)}});
  const auto offset = session.placement().handleOffset();
  const render::Camera& camera = session.camera();
  nlohmann::json dialog = nullptr;
  float rect[4] = {0, 0, 0, 0};
  if (const std::string title = app.modalDialog(rect); !title.empty())
    dialog = {{"title", title}, {"rect", {rect[0], rect[1], rect[2], rect[3]}}};
  nlohmann::json browser = nullptr;
  if (const FileBrowser* b = app.openBrowser()) {
    nlohmann::json entries = nlohmann::json::array();
    for (const FileEntry& e : b->entries()) entries.push_back(e.folder ? e.name + "/" : e.name);
    browser = {{"folder", b->folder().string()}, {"entries", entries}, {"error", b->error()}};
  }
  const ConvergenceReport convergence = session.cache().convergence();
  nlohmann::json pins = nlohmann::json::array();
  if (const Scene* scene = doc.scene())
    for (const PinGroup& g : pinGroups(*scene)) {
      const render::Rgb rgb = render::pinGroupColor(g.group, app.style());
      pins.push_back({{"cloth", g.cloth},
                      {"attachment", g.attachment},
                      {"name", g.name},
                      {"nodes", g.nodes},
                      {"color", {rgb.x(), rgb.y(), rgb.z()}}});
    }
  return {{"file", doc.file()},
          {"dirty", doc.dirty()},
          {"valid", doc.valid()},
          {"validation_error", doc.validationError()},
          {"cache_frames", session.cache().frameCount()},
          {"cache_status", SimulationCache::statusName(session.cache().status())},
          {"cache_stale", session.timeline().cacheStale()},
          {"cache_restored", session.cache().restored()},
          {"pin_groups", pins},
          {"saved_run_note", session.savedRunNote()},
          {"cache_unconverged_steps", convergence.unconverged},
          {"cache_max_depth", convergence.maxDepth},
          {"solver_banner", app.solverBanner().empty() ? nlohmann::json(nullptr)
                                                       : nlohmann::json(app.solverBanner())},
          {"unconverged_ticks", app.unconvergedTicks()},
          {"frame", session.playback().frame()},
          {"selected", session.selection().nodes()},
          {"can_undo", doc.canUndo()},
          {"can_redo", doc.canRedo()},
          {"focus", session.selection().focus()},
          {"inspector", inspectorState(session)},
          {"targets", targets},
          {"loss", loss.available ? nlohmann::json(loss.total) : nlohmann::json(nullptr)},
          {"loss_terms", terms},
          {"loss_note", loss.note},
          {"optimizer", optimizerState(session)},
          {"plotted_steps", session.stepSeries().size()},
          {"message", app.message()},
          {"message_is_error", app.messageIsError()},
          {"panel", tabs[static_cast<int>(app.tab())]},
          {"viewport", {app.viewportWidth(), app.viewportHeight()}},
          {"timeline_frames", session.timeline().frames()},
          {"time", session.timeline().time()},
          {"active_object", session.placement().activeObject().path()},
          {"gizmo", gizmo},
          {"keys", keys},
          {"handle_offset", offset ? jsonOf(*offset) : nlohmann::json(nullptr)},
          {"key_pending", session.placement().handleOffsetPending()},
          {"camera",
           {{"yaw", camera.yawDeg},
            {"pitch", camera.pitchDeg},
            {"distance", camera.distance},
            {"target", jsonOf(camera.target.cast<double>())}}},
          {"playing", session.playback().playing()},
          {"loop", session.playback().loop()},
          {"animating", session.animating()},
          {"dialog", dialog},
          {"browser", browser},
          {"close_prompt", app.closePromptOpen()},
          {"unsaved_prompt", app.unsavedPrompt().empty() ? nlohmann::json(nullptr)
                                                         : nlohmann::json(app.unsavedPrompt())},
          {"close_confirmed", app.closeConfirmed()},
          {"imgui_assertions", app.recoveredAssertions()},
          {"items", app.itemPoints()},
          {"document", doc.document()}};
}

bool expect(ScriptCall& call) {
  const nlohmann::json state = stateOf(call.session, call.app);
  for (const auto& [key, expected] : call.action.at("expect").items()) {
    if (key == "value") {
      const std::string path = expected.at("path").get<std::string>();
      const nlohmann::json* actual = call.session.document().find(path);
      if (!actual || *actual != expected.at("equals")) {
        call.fail(path + " is " + (actual ? actual->dump() : "absent") + ", expected " +
                  expected.at("equals").dump());
        return false;
      }
    } else if (!state.contains(key)) {
      call.fail("unknown expectation \"" + key + "\"");
      return false;
    } else if (state[key] != expected) {
      call.fail(key + " is " + state[key].dump() + ", expected " + expected.dump());
      return false;
    }
  }
  return true;
}

bool writeState(ScriptCall& call) {
  std::ofstream out(outputFile(call.action.at("write_state")));
  out << stateOf(call.session, call.app).dump(2) << "\n";
  if (!out)
    throw std::runtime_error("cannot write " + call.action["write_state"].get<std::string>());
  return true;
}

// The recovery check (EditorApp::provokeAssertion): the next frame breaks ImGui's contract.
bool provokeImGuiAssertion(ScriptCall& call) {
  call.app.provokeAssertion();
  return true;
}

}  // namespace

void addStateCommands(ScriptCommandTable& table) {
  table["expect"] = expect;
  table["write_state"] = writeState;
  table["provoke_imgui_assertion"] = provokeImGuiAssertion;
}

}  // namespace weft::editor
