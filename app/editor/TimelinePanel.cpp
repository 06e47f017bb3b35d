#include "TimelinePanel.h"

#include "EditorApp.h"
#include "EditorSession.h"
#include "PanelStyle.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <functional>

namespace weft::editor {

TimelinePanel::TimelinePanel(EditorSession& session, EditorApp& app)
    : session_(session), app_(app) {}

void TimelinePanel::draw(float left, float top, float width, float height) {
  banner_.clear();
  unconvergedTicks_ = 0;
  ImGui::SetNextWindowPos(ImVec2(left, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  ImGui::Begin("Timeline", nullptr, kFixedWindow);
  SimulationCache& cache = session_.cache();
  const EditorDocument& doc = session_.document();
  const int sceneSteps = doc.valid() ? doc.scene()->time.steps : 0;

  ImGui::BeginDisabled(!doc.valid() || cache.running());
  if (ImGui::Button("Simulate")) {
    const std::string error = session_.timeline().simulate();
    runMessage_ = error.empty() ? "simulating " + std::to_string(sceneSteps) + " steps" : "";
    app_.report(error.empty() ? runMessage_ : error, !error.empty());
  }
  // "simulating N steps" is true while the run lasts; the verdict line says how it ended. Any
  // other message reported since is left alone.
  if (!runMessage_.empty() && !cache.running()) {
    if (app_.message() == runMessage_) app_.report("", false);
    runMessage_.clear();
  }
  app_.noteLastItem("timeline:simulate");
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Text("%d steps (time.steps)", sceneSteps);
  ImGui::SameLine();
  ImGui::BeginDisabled(!cache.running());
  if (ImGui::Button("Cancel")) cache.cancel();
  ImGui::EndDisabled();
  ImGui::SameLine();
  const int available = cache.frameCount();
  // A run reopened with the scene (or one beside it that was not) says so where the status is.
  const std::string& note = session_.savedRunNote();
  const bool noted =
      !note.empty() && (cache.restored() || cache.status() == SimulationCache::Status::Empty);
  char progress[192];
  std::snprintf(progress, sizeof progress, "%d / %d states (%s)", available,
                cache.requestedFrames(),
                noted ? note.c_str() : SimulationCache::statusName(cache.status()));
  ImGui::ProgressBar(float(cache.progress()), ImVec2(-1, 0), progress);

  if (cache.status() == SimulationCache::Status::Failed) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("simulation failed: %s", cache.error().c_str());
    ImGui::PopStyleColor();
  } else if (session_.timeline().cacheStale()) {
    ImGui::TextColored(
        kWarningColour,
        "The scene changed since this simulation: the frames are stale. Simulate again.");
  } else {
    // The run's verdict: a step that stopped at the iteration limit is never shown as a result
    // without saying so (the same report as `weft simulate`'s). Unconverged steps get a banner
    // (red, the width of the panel, one line so that the panel keeps its height) with the worst
    // residual against the tolerance of the run's own settings, and a red tick each on the
    // slider below.
    const ConvergenceReport run = cache.convergence();
    const auto simulated = cache.scene();
    if (run.steps == 0) {
      ImGui::TextDisabled("solver: no steps simulated");
    } else if (run.unconverged > 0 && simulated) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "%d of %d steps unconverged at %d iterations: worst residual %.3g m/s^2, "
                    "tolerance %.3g (state %d)",
                    run.unconverged, run.steps, simulated->solver.pdIterations, run.worstResidual,
                    simulated->solver.pdTolerance, run.worstResidualStep);
      banner_ = text;
      const ImVec2 at = ImGui::GetCursorScreenPos();
      const float h = ImGui::GetTextLineHeight();
      ImGui::GetWindowDrawList()->AddRectFilled(
          ImVec2(at.x - 4.0f, at.y - 1.0f),
          ImVec2(at.x + ImGui::GetContentRegionAvail().x + 4.0f, at.y + h + 1.0f),
          ImGui::GetColorU32(kUnconvergedColour));
      ImGui::TextColored(ImVec4(1, 1, 1, 1), "%s", text);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "These steps stopped at solver.pd_iterations with the residual (the mass-weighted\n"
            "imbalance of the step's equations) above solver.pd_tolerance: their states are not\n"
            "solutions. Red ticks on the slider mark them; raise the iteration cap, loosen the\n"
            "tolerance or shorten dt.");
    } else if (run.maxDepth <= ConvergenceReport::kDepthTolerance) {
      ImGui::TextColored(kOkColour, "solver: all %d steps converged", run.steps);
    } else {
      ImGui::TextColored(kWarningColour,
                         "solver: all %d steps converged; deepest %.2f mm into an obstacle's skin "
                         "(state %d)",
                         run.steps, 1e3 * run.maxDepth, run.maxDepthStep);
    }
  }

  Playback& playback = session_.playback();
  // The timeline spans the scene's steps even before they are simulated (keys can be set
  // anywhere); beyond the cache the viewport keeps the last cached state.
  const int frames = session_.timeline().frames();
  ImGui::BeginDisabled(frames <= 1);
  if (ImGui::Button("|<")) session_.timeline().goToStart();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The first state (Home)");
  app_.noteLastItem("timeline:start");
  ImGui::SameLine();
  ImGui::BeginDisabled(available == 0);
  if (ImGui::Button(playback.playing() ? "Pause" : "Play")) session_.timeline().togglePlayback();
  app_.noteLastItem("timeline:play");
  ImGui::SameLine();
  bool loop = playback.loop();
  if (ImGui::Checkbox("Loop", &loop)) session_.playback().setLoop(loop);
  app_.noteLastItem("timeline:loop");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button(">|")) session_.timeline().goToEnd();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The last simulated state (End)");
  app_.noteLastItem("timeline:end");
  ImGui::SameLine();
  int k = playback.frame();
  ImGui::SetNextItemWidth(std::max(100.0f, ImGui::GetContentRegionAvail().x - 260.0f));
  if (ImGui::SliderInt("##frame", &k, 0, std::max(frames - 1, 0),
                       k < available ? "state %d" : "state %d (not simulated)"))
    playback.scrub(k, frames);
  if (!session_.timeline().cacheStale()) drawUnconvergedTicks(frames);
  drawKeyTicks(frames);
  ImGui::EndDisabled();
  ImGui::SameLine();
  const auto scene = cache.scene();
  const auto f = cache.frame(playback.frame());
  if (f && scene) {
    ImGui::Text("t = %.4f s", f->state * scene->time.dt);
    ImGui::Text("contacts: take-off %d, stick %d, slip %d   PD iterations %d, residual %.3g m/s^2",
                f->stats.takeoff, f->stats.stick, f->stats.slip, f->stats.pdIterations,
                f->stats.residual);
    // This step's verdict, on the same line so that the panel keeps its height.
    ImGui::SameLine();
    if (f->state > 0 && !f->stats.converged)
      ImGui::TextColored(kWarningColour, "  stopped at the iteration limit");
    else if (f->stats.depth > ConvergenceReport::kDepthTolerance)
      ImGui::TextColored(kWarningColour, "  a node %.2f mm into an obstacle's skin",
                         1e3 * f->stats.depth);
    else
      ImGui::TextUnformatted("");
  } else {
    ImGui::Text("t = %.4f s", session_.timeline().time());
    ImGui::TextDisabled(available == 0
                            ? "no frames: press Simulate"
                            : "not simulated this far: the view shows the last cached state");
  }
  if (session_.placement().activeObject().kind == EditorObject::Kind::Handle)
    keyControls();
  else
    ImGui::TextDisabled("Space: play/pause   Left/Right: step one state   Home/End: first/last");
  ImGui::End();
}

namespace {

// Where state `frame` of `frames` lies on the slider just drawn: where its grab's centre would
// stand (Dear ImGui 1.86 SliderBehaviorT: 2 px padding, a grab of max(width / (range + 1),
// GrabMinSize) whose centre travels the rest).
float sliderX(double frame, int frames) {
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  const float padding = 2.0f, width = high.x - low.x - 2.0f * padding;
  const float grab =
      std::min(std::max(width / float(frames), ImGui::GetStyle().GrabMinSize), width);
  return low.x + padding + 0.5f * grab + float(frame / double(frames - 1)) * (width - grab);
}

}  // namespace

void TimelinePanel::drawUnconvergedTicks(int frames) {
  // A red tick along the slider's top edge per state whose step stopped at the iteration limit.
  if (frames <= 1) return;
  const ImVec2 low = ImGui::GetItemRectMin();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (const int state : session_.stepSeries().unconvergedStates()) {
    if (state >= frames) break;
    const float x = sliderX(state, frames);
    draw->AddRectFilled(ImVec2(x - 1.0f, low.y), ImVec2(x + 1.0f, low.y + 7.0f),
                        ImGui::GetColorU32(kUnconvergedColour));
    ++unconvergedTicks_;
  }
}

void TimelinePanel::drawKeyTicks(int frames) {
  // The active handle's keys as ticks on the slider just drawn, where its grab would stand at
  // the key's frame.
  const std::vector<HandleKey> keys = session_.placement().keys();
  const EditorDocument& doc = session_.document();
  if (keys.empty() || frames <= 1 || !doc.valid()) return;
  const double dt = doc.scene()->time.dt;
  const ImVec2 low = ImGui::GetItemRectMin(), high = ImGui::GetItemRectMax();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (const HandleKey& key : keys) {
    const double frame = key.time / dt;
    if (frame < -0.5 || frame > frames - 0.5) continue;
    const float x = sliderX(frame, frames);
    draw->AddTriangleFilled(ImVec2(x, high.y - 6.0f), ImVec2(x - 4.0f, high.y + 1.0f),
                            ImVec2(x + 4.0f, high.y + 1.0f), IM_COL32(255, 200, 40, 255));
    draw->AddLine(ImVec2(x, low.y), ImVec2(x, high.y), IM_COL32(255, 200, 40, 160), 1.0f);
  }
}

void TimelinePanel::keyControls() {
  // The active handle at the playback frame: its offset (dragged with the gizmo or typed here),
  // and its keys.
  const auto offset = session_.placement().handleOffset();
  ImGui::AlignTextToFramePadding();
  ImGui::Text("%s", session_.placement().activeObject().path().c_str());
  ImGui::SameLine();
  double v[3] = {0, 0, 0};
  if (offset) v[0] = offset->x(), v[1] = offset->y(), v[2] = offset->z();
  ImGui::SetNextItemWidth(230.0f);
  // "###": one widget identity whatever the label says, so typing is not cut off when the first
  // keystroke makes the offset pending.
  if (ImGui::InputScalarN(session_.placement().handleOffsetPending()
                              ? "offset (m, not keyed)###offset"
                              : "offset (m)###offset",
                          ImGuiDataType_Double, v, 3, nullptr, nullptr, "%.4g")) {
    const std::string error = session_.placement().setHandleOffset(Vec3(v[0], v[1], v[2]));
    if (!error.empty()) app_.report(error, true);
  }
  auto action = [&](const char* label, const std::function<std::string()>& run, const char* done) {
    ImGui::SameLine();
    if (ImGui::SmallButton(label)) {
      const std::string error = run();
      app_.report(error.empty() ? done : error, !error.empty());
    }
  };
  action(
      "Set key (K)", [&] { return session_.placement().setKey(); }, "key set");
  action(
      "Delete key", [&] { return session_.placement().deleteKey(); }, "key deleted");
  action(
      "< key", [&] { return session_.placement().jumpToKey(-1); }, "previous key");
  action(
      "key >", [&] { return session_.placement().jumpToKey(1); }, "next key");
}

}  // namespace weft::editor
