#include "LiveLoss.h"

#include "FinalTargets.h"

#include <weft/diff/FinalFrameLoss.h>
#include <weft/model/ClothModel.h>

namespace weft::editor {

const LossValue& LiveLoss::evaluate(const EditorDocument& document, const SimulationCache& cache) {
  const int frames = cache.frameCount();
  if (document.revision() == revision_ && cache.runId() == runId_ && frames == frames_)
    return value_;
  revision_ = document.revision();
  frames_ = frames;
  value_ = LossValue();

  const Scene* scene = document.scene();
  if (!scene) {
    value_.note = "the scene does not validate";
    return value_;
  }
  if (!scene->task) {
    value_.note = "the scene has no task: set targets or load a target motion";
    return value_;
  }
  if (cache.status() != SimulationCache::Status::Done || frames != scene->time.steps + 1 ||
      cache.staleFor(document.document())) {
    value_.note = "simulate the scene (all time.steps) to see the loss of the run";
    return value_;
  }
  if (cache.runId() != runId_) {
    runId_ = cache.runId();
    trajectory_ = cache.trajectory();
  }

  try {
    const std::vector<FinalTarget> targets = finalTargets(document.sidecar());
    // Terms read from files: everything except a final term whose targets the editor holds.
    Scene fileScene = *scene;
    if (!targets.empty()) fileScene.task->loss.erase("final");
    const std::string key = fileScene.task->loss.dump() + "\n" + scene->directory;
    if (key != fileTermsKey_) {
      fileTerms_.reset();
      fileTermsKey_.clear();
      if (!fileScene.task->loss.empty()) fileTerms_ = std::make_unique<TaskLoss>(fileScene);
      fileTermsKey_ = key;
    }
    if (fileTerms_)
      for (const auto& term : fileTerms_->terms()) {
        const double v = term->value(trajectory_);
        value_.terms.emplace_back(term->name(), v);
        value_.total += v;
      }
    if (fileTerms_ && fileTerms_->clearance()) {
      const double v = fileTerms_->clearance()->value(*scene);
      value_.terms.emplace_back(fileTerms_->clearance()->name(), v);
      value_.total += v;
    }
    if (!targets.empty()) {
      const nlohmann::json& term = scene->task->loss.at("final");
      std::vector<int> vertices;
      for (const FinalTarget& t : targets) vertices.push_back(t.node);
      const FinalFrameLoss loss(finalTargetMatrix(targets, document.cloth()->rest.vertices),
                                vertices, term.value("weight", 1.0));
      const double v = loss.value(trajectory_);
      value_.terms.emplace_back("final", v);
      value_.total += v;
    }
    value_.available = true;
  } catch (const std::exception& e) {
    fileTermsKey_.clear();
    fileTerms_.reset();
    value_ = LossValue();
    value_.note = e.what();
  }
  return value_;
}

}  // namespace weft::editor
