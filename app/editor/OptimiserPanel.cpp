#include "OptimiserPanel.h"

#include "EditorApp.h"
#include "EditorSession.h"

#include <weft/diff/SceneParameter.h>
#include <weft/optim/ParameterSpace.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/scene/JsonPath.h>

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace weft::editor {
namespace {

// The bounds a run would use for `path`: the parameter kind's default box, replaced by an
// explicit task.bounds entry. False when the path is not an optimisable parameter.
bool effectiveBounds(const Scene& scene, const std::string& path, double& lower, double& upper,
                     std::string& error) {
  try {
    SceneParameter p = resolveSceneParameter(scene, path, "task.parameters");
    applyDefaultBounds(p);
    lower = p.lower, upper = p.upper;
    for (const Task::Bound& b : scene.task->bounds)
      if (b.path == path) lower = b.lower, upper = b.upper;
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

nlohmann::json bound(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

void plotHistory(const char* id, const std::vector<float>& values, const char* overlay,
                 float height) {
  ImGui::PlotLines(id, values.empty() ? nullptr : values.data(), int(values.size()), 0, overlay,
                   FLT_MAX, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, height));
}

}  // namespace

void OptimiserPanel::draw(EditorSession& session, EditorApp& app) {
  EditorDocument& doc = session.document();
  OptimizerRun& run = session.optimisation().optimizer();
  // Held for the frame: a bounds edit below replaces the document's scene while its parameter
  // list is still being walked.
  const std::shared_ptr<const Scene> heldScene = doc.sharedScene();
  const Scene* scene = heldScene.get();
  const bool active = run.active();

  // Parameters and bounds.
  std::vector<std::string> chosen;
  if (!scene) {
    ImGui::TextDisabled("The scene does not validate.");
  } else if (!scene->task) {
    ImGui::TextWrapped(
        "The scene has no task yet: give it a loss first (Targets tab: targets or a target "
        "motion), then choose the parameters here.");
  } else {
    if (scene->task->parameters.empty())
      ImGui::TextWrapped(
          "The task names no parameters yet: add the ones the optimiser may change.");
    else
      ImGui::TextUnformatted("Parameters (task.parameters) and bounds:");
    ImGui::BeginDisabled(active);
    std::string removed;
    for (const std::string& path : scene->task->parameters) {
      ImGui::PushID(path.c_str());
      if (ImGui::SmallButton("x")) removed = path;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Remove %s from the task", path.c_str());
      ImGui::SameLine();
      bool on = !excluded_[path];
      if (ImGui::Checkbox(path.c_str(), &on)) excluded_[path] = !on;
      if (on) chosen.push_back(path);
      const nlohmann::json* value = doc.find(path);
      ImGui::SameLine();
      ImGui::TextDisabled("= %.6g", value && value->is_number() ? value->get<double>() : 0.0);
      double lower = 0, upper = 0;
      std::string error;
      if (effectiveBounds(*scene, path, lower, upper, error)) {
        double b[2] = {lower, upper};
        ImGui::SetNextItemWidth(220.0f);
        ImGui::Indent();
        if (ImGui::InputScalarN("bounds", ImGuiDataType_Double, b, 2, nullptr, nullptr, "%.4g",
                                ImGuiInputTextFlags_EnterReturnsTrue)) {
          const std::string e = doc.edit("Set bounds of " + path, [&](nlohmann::json& d) {
            d["task"]["bounds"][path] = {bound(b[0]), bound(b[1])};
          });
          if (!e.empty()) app.report(e, true);
        }
        ImGui::Unindent();
      } else {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.30f, 1.0f));
        ImGui::TextWrapped("%s", error.c_str());
        ImGui::PopStyleColor();
      }
      ImGui::PopID();
    }
    // The scene's other differentiable numbers, by JSON path (the same list `weft gradcheck
    // --param` and task.parameters accept).
    std::string added;
    if (ImGui::BeginCombo("add parameter", "choose...")) {
      const std::vector<std::string>& list = scene->task->parameters;
      for (const std::string& path : differentiableParameterPaths(*scene))
        if (std::find(list.begin(), list.end(), path) == list.end() &&
            ImGui::Selectable(path.c_str()))
          added = path;
      ImGui::EndCombo();
    }
    ImGui::EndDisabled();
    // Edited after drawing: an edit validates the document again and replaces `scene`.
    if (!added.empty() || !removed.empty()) {
      const std::string error = added.empty() ? session.optimisation().removeParameter(removed)
                                              : session.optimisation().addParameter(added);
      app.report(error.empty() ? (added.empty() ? "removed " + removed : "added " + added) : error,
                 !error.empty());
      scene = doc.scene();
    }
  }

  // Method and settings.
  const std::vector<std::string> methods = OptimizerRun::methods();
  method_ = std::clamp(method_, 0, std::max(int(methods.size()) - 1, 0));
  ImGui::BeginDisabled(active);
  if (!methods.empty() && ImGui::BeginCombo("method", methods[std::size_t(method_)].c_str())) {
    for (int i = 0; i < int(methods.size()); ++i)
      if (ImGui::Selectable(methods[std::size_t(i)].c_str(), i == method_)) method_ = i;
    ImGui::EndCombo();
  }
  ImGui::InputInt("max evaluations", &maxEvaluations_);
  maxEvaluations_ = std::max(maxEvaluations_, 1);
  if (!methods.empty() && methods[std::size_t(method_)] == "adam")
    ImGui::InputDouble("learning rate", &learningRate_, 0.0, 0.0, "%.4g");
  ImGui::InputInt("seed", &seed_);
  ImGui::EndDisabled();

  auto start = [&](bool paused) {
    OptimizerRun::Setup setup;
    setup.method = methods.empty() ? "" : methods[std::size_t(method_)];
    setup.parameters = chosen;
    setup.settings.maxEvaluations = maxEvaluations_;
    setup.settings.learningRate = learningRate_;
    setup.settings.seed = static_cast<unsigned>(std::max(seed_, 0));
    const std::string error = session.optimisation().start(setup, paused);
    if (!error.empty())
      app.report(error, true);
    else if (paused)
      run.step(1);
  };
  // Controls.
  ImGui::BeginDisabled(!scene || chosen.empty() || active);
  if (ImGui::Button("Run")) start(false);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (active) {
    const bool paused = run.status() == OptimizerRun::Status::Paused;
    if (ImGui::Button(paused ? "Resume" : "Pause")) paused ? run.resume() : run.pause();
    ImGui::SameLine();
    if (ImGui::Button("Step")) run.step(1);
    ImGui::SameLine();
    // Stops within the step under way (the run checks between steps), so the wait is short.
    if (ImGui::Button("Cancel")) run.cancel();
    app.noteLastItem("optimiser:cancel");
  } else {
    ImGui::BeginDisabled(!scene || chosen.empty());
    if (ImGui::Button("Step")) start(true);  // a new run, paused after its first evaluation
    ImGui::EndDisabled();
  }
  ImGui::TextDisabled("Step: one more evaluation (forward + adjoint).");

  // Status and history.
  const std::vector<OptimizerRun::Sample> samples = run.samples();
  ImGui::Text("%s: %s, %zu evaluations", run.method().empty() ? "optimiser" : run.method().c_str(),
              OptimizerRun::statusName(run.status()), samples.size());
  // Inside the evaluation under way: which pass, which step (a 1,400-vertex garment's evaluation
  // takes most of a minute).
  if (const OptimizerRun::Progress p = run.progress(); p.active && p.total > 0) {
    char overlay[96];
    if (p.phase == PassPhase::Forward)
      std::snprintf(overlay, sizeof overlay, "evaluation %d: forward step %d / %d", p.evaluation,
                    p.done, p.total);
    else
      std::snprintf(overlay, sizeof overlay, "evaluation %d: backward pass %d, step %d / %d",
                    p.evaluation, p.pass, p.done, p.total);
    ImGui::ProgressBar(static_cast<float>(p.done) / static_cast<float>(p.total), ImVec2(-1, 0),
                       overlay);
  }
  if (!run.stopReason().empty()) ImGui::TextDisabled("stopped: %s", run.stopReason().c_str());
  if (!run.error().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.30f, 1.0f));
    ImGui::TextWrapped("%s", run.error().c_str());
    ImGui::PopStyleColor();
  }
  if (const int unconverged = run.unconvergedForwardSteps(); unconverged > 0) {
    // The CLI's warning (weft optimize, gradcheck), without its "warning: " prefix.
    std::string warning = unconvergedGradientWarning(unconverged);
    warning = warning.substr(std::string("warning: ").size());
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.65f, 0.20f, 1.0f));
    ImGui::TextWrapped("%s", warning.c_str());
    ImGui::PopStyleColor();
  }
  if (samples.empty()) return;
  // The gradients' error estimates (diff/GradientErrorControl.h): the last one, the largest, and
  // a warning when any missed the scene's solver.backward.accuracy.
  for (auto s = samples.rbegin(); s != samples.rend(); ++s) {
    if (!s->hasGradient) continue;
    ImGui::TextDisabled("gradient error: last %.1e, largest %.1e (relative, estimated)",
                        s->gradientError, run.largestGradientError());
    break;
  }
  if (const int missing = run.gradientsMissingAccuracy(); missing > 0) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.65f, 0.20f, 1.0f));
    ImGui::TextWrapped(
        "%d gradients missed solver.backward.accuracy: the adjoint's growth amplifies round-off "
        "beyond it even with the direct solve",
        missing);
    ImGui::PopStyleColor();
  }
  std::vector<float> loss;
  for (const auto& s : samples) loss.push_back(float(std::log10(std::max(s.loss, 1e-300))));
  const auto best = run.best();
  char text[128];
  std::snprintf(text, sizeof text, "log10 loss; best %.4g (evaluation %d)", best ? best->loss : 0.0,
                best ? best->evaluation : 0);
  plotHistory("##loss", loss, text, 70.0f);
  const std::vector<std::string>& paths = run.parameters();
  // Every evaluation: its loss, the gradient's estimated error, the forward steps that missed
  // the tolerance, and the parameter values; the newest first.
  const int columns = 4 + static_cast<int>(paths.size());
  if (ImGui::BeginTable("##evaluations", columns,
                        ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders | ImGuiTableFlags_ScrollY |
                            ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit,
                        ImVec2(0.0f, 110.0f))) {
    ImGui::TableSetupScrollFreeze(1, 1);
    ImGui::TableSetupColumn("#");
    ImGui::TableSetupColumn("loss");
    ImGui::TableSetupColumn("grad. error");
    ImGui::TableSetupColumn("unconv.");
    for (const std::string& path : paths) ImGui::TableSetupColumn(path.c_str());
    ImGui::TableHeadersRow();
    for (auto s = samples.rbegin(); s != samples.rend(); ++s) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d", s->evaluation);
      ImGui::TableNextColumn();
      ImGui::Text("%.5g", s->loss);
      ImGui::TableNextColumn();
      if (s->hasGradient)
        ImGui::Text("%.1e", s->gradientError);
      else
        ImGui::TextDisabled("-");
      ImGui::TableNextColumn();
      if (s->unconvergedSteps > 0)
        ImGui::TextColored(ImVec4(0.95f, 0.65f, 0.20f, 1.0f), "%d", s->unconvergedSteps);
      else
        ImGui::TextDisabled("0");
      for (double v : s->values) {
        ImGui::TableNextColumn();
        ImGui::Text("%.6g", v);
      }
    }
    ImGui::EndTable();
  }
  for (std::size_t p = 0; p < paths.size(); ++p) {
    std::vector<float> values;
    for (const auto& s : samples) values.push_back(float(s.values[p]));
    std::snprintf(text, sizeof text, "%s: %.6g -> %.6g", paths[p].c_str(), run.initialValues()[p],
                  best ? best->values[p] : 0.0);
    ImGui::PushID(int(p));
    plotHistory("##parameter", values, text, 40.0f);
    ImGui::PopID();
  }

  // Into the document.
  // Applying mid-run is fine: the run works on its own copy of the scene.
  ImGui::BeginDisabled(!best);
  if (ImGui::Button("Apply best")) {
    const std::string error = session.optimisation().applyResult();
    app.report(error.empty() ? "applied the optimised parameters (Ctrl+Z undoes)" : error,
               !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Revert to start values")) {
    const std::string error = session.optimisation().revertToStart();
    app.report(error.empty() ? "reverted to the values the run started from" : error,
               !error.empty());
  }
  ImGui::EndDisabled();
  // Other edits since the start (the parameters themselves aside) make the result stale.
  nlohmann::json started = simulatedPart(run.startDocument());
  for (const std::string& path : paths)
    if (const nlohmann::json* now = doc.find(path)) setJsonPath(started, path, *now);
  if (started != simulatedPart(doc.document()))
    ImGui::TextDisabled("The scene changed since the run started.");
}

}  // namespace weft::editor
