#include "StateGradients.h"

#include <weft/diff/Backpropagation.h>
#include <weft/diff/TaskLoss.h>

#include <algorithm>
#include <chrono>

namespace weft::editor {

StateGradients::StateGradients(const EditorDocument& document, const SimulationCache& cache,
                               TaskTargets& targets)
    : document_(document), cache_(cache), targets_(targets) {}

std::string StateGradients::compute() {
  if (job_.valid()) return "the loss gradient is being computed";
  const Scene* current = document_.scene();
  if (!current) return "the scene does not validate: " + document_.validationError();
  if (!current->task) return "the scene has no task: set targets or load a target motion first";
  const int frames = cache_.frameCount();
  if (cache_.status() != SimulationCache::Status::Done || frames != current->time.steps + 1 ||
      cache_.staleFor(document_.document()))
    return "simulate the scene (all time.steps) first: the gradient is of the cached run";
  if (cache_.restored())
    return "the reopened run holds no contact records for the backward pass: simulate again";
  auto trajectory = std::make_shared<const Trajectory>(cache_.trajectory());
  // The loss is built here, while the editor's targets are in their temporary file; the job
  // owns copies of everything it reads.
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const TaskLoss> loss;
  const std::string error = targets_.withHeldTargets([&](const Scene& s) {
    scene = std::make_shared<const Scene>(s);
    loss = std::make_shared<const TaskLoss>(*scene);
    return std::string();
  });
  if (!error.empty()) return error;
  error_.clear();
  jobRun_ = cache_.runId();
  jobRevision_ = document_.revision();
  job_ = std::async(std::launch::async, [scene, loss, trajectory] {
    // Per-vertex values show a solve's error more than a parameter's sum does: solve tightly.
    BackwardSettings settings = scene->solver.backward;
    settings.tolerance = std::min(settings.tolerance, 1e-8);
    return backpropagate(*trajectory, *loss, ParameterSet(), settings).dLdx;
  });
  return "";
}

void StateGradients::collect() {
  if (!job_.valid() || job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
  try {
    gradients_ = job_.get();
    gradientsRun_ = jobRun_;
    gradientsRevision_ = jobRevision_;
  } catch (const std::exception& e) {
    error_ = std::string("the backward pass failed: ") + e.what();
  }
}

std::optional<Vec3> StateGradients::at(int node, int state) const {
  if (gradientsRun_ != cache_.runId() || gradientsRevision_ != document_.revision())
    return std::nullopt;
  if (state < 0 || state >= int(gradients_.size()) || node < 0 ||
      node >= gradients_[std::size_t(state)].rows())
    return std::nullopt;
  return Vec3(gradients_[std::size_t(state)].row(node).transpose());
}

}  // namespace weft::editor
