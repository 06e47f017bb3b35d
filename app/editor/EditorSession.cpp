#include "EditorSession.h"

#include "ClothNodes.h"

#include <weft/core/Error.h>

#include <algorithm>
#include <filesystem>

namespace weft::editor {
namespace {

// Two warning texts as one ("" when both are empty).
std::string joined(const std::string& a, const std::string& b) {
  return a.empty() ? b : b.empty() ? a : a + "; " + b;
}

}  // namespace

EditorSession::EditorSession(const std::string& recentStore) : recent_(recentStore) {
  frameCamera(16.0f / 9.0f);
}

void EditorSession::newDocument(nlohmann::json document) {
  cache_.clear();
  savedRunNote_.clear();
  document_ = EditorDocument(std::move(document));
  afterDocumentReplaced();
}

void EditorSession::open(const std::string& file) {
  EditorDocument opened;
  opened.open(file);  // throws, leaving the current document as it was
  cache_.clear();
  document_ = std::move(opened);
  recent_.add(file);
  afterDocumentReplaced();
  restoreRunBeside();
}

void EditorSession::afterDocumentReplaced() {
  // Final targets of an opened scene become editable (their positions come from its .npy).
  if (const Scene* scene = document_.scene()) document_.resetSidecar(readFinalTargets(*scene));
  selection_.clear();
  placement_.reset();
  timeline_.reset();
  viewport_.reset();
  frameCamera(16.0f / 9.0f);
}

std::string EditorSession::save() {
  if (document_.file().empty())
    throw InputError("untitled", "-", "the document has no file yet: use Save As");
  const std::string warning = targets_.writeTargets(document_.file());
  document_.save();
  recent_.add(document_.file());
  return joined(warning, saveRunBeside());
}

std::string EditorSession::saveAs(const std::string& file) {
  if (file.empty()) throw InputError("-", "-", "no file name given");
  const std::string warning = targets_.writeTargets(file);
  const bool current = cache_.scene() && !timeline_.cacheStale();
  document_.saveAs(file);
  // Rebased references name the same files: the cached run is still the document's own.
  if (current && document_.valid()) cache_.relabel(document_.sharedScene());
  recent_.add(file);
  return joined(warning, saveRunBeside());
}

std::string EditorSession::runFolderBeside(const std::string& sceneFile) {
  return std::filesystem::path(sceneFile).replace_extension(".run").string();
}

std::string EditorSession::saveRunBeside() {
  if (cache_.status() != SimulationCache::Status::Done || timeline_.cacheStale() || !cache_.scene())
    return "";
  const std::string folder = runFolderBeside(document_.file());
  try {
    cache_.save(folder);
  } catch (const std::exception& e) {
    return std::string("the simulation was not saved beside the scene: ") + e.what();
  }
  savedRunNote_ = "run saved in " + std::filesystem::path(folder).filename().string();
  return "";
}

void EditorSession::restoreRunBeside() {
  savedRunNote_.clear();
  const std::string folder = runFolderBeside(document_.file());
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return;
  const std::string name = std::filesystem::path(folder).filename().string();
  try {
    const RunFolder run = loadRunFolder(folder);
    if (simulatedPart(run.scene.document) != simulatedPart(document_.document())) {
      savedRunNote_ = name + " is the run of another version of the scene: not loaded";
      return;
    }
    cache_.restore(run);
    savedRunNote_ = "run reopened from " + name;
  } catch (const std::exception& e) {
    savedRunNote_ = name + " cannot be read: " + e.what();
  }
}

void EditorSession::frameCamera(float aspect, render::NamedView view) {
  camera_ = viewport_.framing(aspect, view);
}

std::optional<VertexReport> EditorSession::inspect() const {
  const int node = selection_.focus();
  const int available = cache_.frameCount();
  const std::shared_ptr<const Scene> cached = cache_.scene();
  if (node < 0 || available == 0 || !cached) return std::nullopt;
  const std::shared_ptr<const Scene>& lastValid = viewport_.lastValidScene();
  if (lastValid && lastValid->vertexCount() != cached->vertexCount()) return std::nullopt;
  const auto f = cache_.frame(std::min(playback_.frame(), available - 1));
  if (!f) return std::nullopt;
  return inspectVertex(*f, node, cached->time.dt, clothVertexOffsets(*cached));
}

bool EditorSession::animating() const {
  return playback_.playing() || cache_.running() ||
         optimisation_.optimizer().status() == OptimizerRun::Status::Running ||
         gradients_.computing() || autosave_.pending(document_);
}

std::string EditorSession::restore(const Recovery& recovery) {
  try {
    std::error_code ec;
    if (!recovery.sceneFile.empty() && std::filesystem::is_regular_file(recovery.sceneFile, ec))
      open(recovery.sceneFile);
    else
      newDocument();
  } catch (const std::exception& e) {
    return e.what();
  }
  const std::string error = document_.edit("Recovered unsaved changes",
                                           [&](nlohmann::json& doc) { doc = recovery.document; });
  if (error.empty()) Autosave::remove(recovery);
  return error;
}

void EditorSession::tick(double seconds) {
  autosave_.tick(document_, seconds);
  timeline_.advance(seconds);
  stepSeries_.update(cache_);
  placement_.dropStaleActiveObject();
  gradients_.collect();
}

}  // namespace weft::editor
