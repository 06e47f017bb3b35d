#include "SimulationCache.h"

#include "WorkerThreads.h"

#include <weft/core/Error.h>
#include <weft/io/StagedDirectory.h>
#include <weft/output/RunWriter.h>
#include <weft/physics/Model.h>
#include <weft/physics/Simulator.h>
#include <weft/record/StepContacts.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace weft::editor {

SimulationCache::~SimulationCache() {
  cancel_ = true;
  join();
}

void SimulationCache::join() {
  if (worker_.joinable()) worker_.join();
}

void SimulationCache::start(std::shared_ptr<const Scene> scene, int steps) {
  cancel_ = true;
  join();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    frames_.clear();
    frames_.reserve(static_cast<std::size_t>(std::max(steps, 0)) + 1);
    scene_ = scene;
    model_.reset();
    moduleNames_.clear();
    seconds_ = 0.0;
    restoredFrom_.clear();
    convergence_ = ConvergenceReport();
    error_.clear();
  }
  requested_ = std::max(steps, 0) + 1;
  ++runId_;
  cancel_ = false;
  status_ = Status::Running;
  worker_ = std::thread([this, scene, steps] { run(scene, steps); });
}

void SimulationCache::run(std::shared_ptr<const Scene> scene, int steps) {
  useWorkerThreads();
  try {
    Simulator simulator(*scene);
    const int nodes = simulator.cloth().nodeCount();
    auto first = std::make_shared<CachedFrame>();
    first->positions = simulator.positions();
    first->velocities = simulator.velocities();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      model_ = simulator.sharedModel();
      moduleNames_ = simulator.moduleNames();
      frames_.push_back(std::move(first));
    }
    const auto begin = std::chrono::steady_clock::now();
    for (int s = 1; s <= steps; ++s) {
      if (cancel_) {
        status_ = Status::Cancelled;
        return;
      }
      auto frame = std::make_shared<CachedFrame>();
      frame->stats = simulator.step();
      frame->substeps = simulator.lastSubsteps();
      frame->state = s;
      frame->positions = simulator.positions();
      frame->velocities = simulator.velocities();
      if (simulator.contact()) {
        frame->branches = nodeBranches(simulator.lastContacts(), nodes);
        frame->contacts = simulator.lastContacts();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      convergence_.add(frame->stats);
      frames_.push_back(std::move(frame));
      seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    }
    status_ = Status::Done;
  } catch (const std::exception& e) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
    }
    status_ = Status::Failed;
  }
}

void SimulationCache::cancel() {
  cancel_ = true;
  join();
}

void SimulationCache::wait() {
  join();
}

void SimulationCache::clear() {
  cancel();
  std::lock_guard<std::mutex> lock(mutex_);
  frames_.clear();
  scene_.reset();
  model_.reset();
  restoredFrom_.clear();
  error_.clear();
  requested_ = 0;
  ++runId_;
  status_ = Status::Empty;
}

int SimulationCache::frameCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(frames_.size());
}

double SimulationCache::progress() const {
  const int requested = requested_.load();
  return requested > 0 ? std::min(1.0, double(frameCount()) / requested) : 0.0;
}

std::string SimulationCache::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

std::shared_ptr<const CachedFrame> SimulationCache::frame(int k) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (k < 0 || k >= static_cast<int>(frames_.size())) return nullptr;
  return frames_[static_cast<std::size_t>(k)];
}

Trajectory SimulationCache::trajectory() const {
  Trajectory t;
  bool touched = false;
  for (int k = 0, frames = frameCount(); k < frames; ++k) {
    const std::shared_ptr<const CachedFrame> f = frame(k);
    t.positions.push_back(f->positions);
    t.velocities.push_back(f->velocities);
    if (k == 0) continue;
    t.steps.push_back(f->stats);
    t.contacts.push_back(f->contacts);
    t.substeps.push_back(f->substeps);
    touched = touched || !f->contacts.points.empty();
  }
  if (!touched) t.contacts.clear();  // as a run without contact records it
  std::lock_guard<std::mutex> lock(mutex_);
  t.model = model_;
  return t;
}

ConvergenceReport SimulationCache::convergence() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return convergence_;
}

std::shared_ptr<const Scene> SimulationCache::scene() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return scene_;
}

void SimulationCache::relabel(std::shared_ptr<const Scene> scene) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (scene_ && scene) scene_ = std::move(scene);
}

bool SimulationCache::staleFor(const nlohmann::json& document) const {
  std::shared_ptr<const Scene> scene;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (frames_.empty() || !scene_) return false;
    scene = scene_;
  }
  return simulatedPart(scene->document) != simulatedPart(document);
}

nlohmann::json simulatedPart(const nlohmann::json& document) {
  nlohmann::json part = document;
  if (part.is_object())
    for (const char* key : {"task", "name", "description"}) part.erase(key);
  return part;
}

void SimulationCache::save(const std::string& folder) const {
  if (status() != Status::Done) throw InputError(folder, "run", "no finished run to save");
  std::lock_guard<std::mutex> lock(mutex_);
  if (!restoredFrom_.empty()) {
    // The format cannot be rebuilt from restored frames (their contact forces are gone): the
    // files they came from are copied as they are.
    namespace fs = std::filesystem;
    std::error_code same;
    if (fs::equivalent(restoredFrom_, folder, same)) return;  // already there
    StagedDirectory out(folder);
    for (const auto& e : fs::directory_iterator(restoredFrom_))
      if (e.is_regular_file()) fs::copy_file(e.path(), fs::path(out.path()) / e.path().filename());
    out.commit();
    return;
  }
  StagedDirectory out(folder);
  const int steps = static_cast<int>(frames_.size()) - 1;
  RunWriter writer(out.path(), *scene_, model_->cloth(), steps, model_->hasContact() && steps > 0);
  const std::size_t nodes = static_cast<std::size_t>(model_->nodeCount());
  NpyWriter velocities(out.file("velocities.npy"), {frames_.size(), nodes, 3});
  std::vector<double> row(nodes * 3);
  for (const auto& f : frames_) {
    if (f->state == 0)
      writer.addInitialState(f->positions);
    else
      writer.addStep(f->positions, f->stats, &f->contacts);
    for (std::size_t i = 0; i < nodes; ++i)
      for (int c = 0; c < 3; ++c) row[i * 3 + std::size_t(c)] = f->velocities(Eigen::Index(i), c);
    velocities.append(row.data(), row.size());
  }
  velocities.close();
  RunSummary summary;
  summary.seconds = seconds_;
  summary.moduleNames = moduleNames_;
  summary.moduleSeconds.assign(moduleNames_.size(), 0.0);
  for (const auto& f : frames_)
    for (std::size_t m = 0; m < f->stats.moduleSeconds.size() && m < moduleNames_.size(); ++m)
      summary.moduleSeconds[m] += f->stats.moduleSeconds[m];
  writer.finish(summary);
  out.commit();
}

void SimulationCache::restore(const RunFolder& run) {
  cancel();
  const double dt = run.scene.time.dt;
  std::vector<std::shared_ptr<const CachedFrame>> frames;
  ConvergenceReport convergence;
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    auto f = std::make_shared<CachedFrame>();
    f->state = static_cast<int>(k);
    f->positions = run.states[k];
    if (!run.velocities.empty())
      f->velocities = run.velocities[k];
    else if (k == 0)  // the scene's initial velocity, which the positions cannot tell
      f->velocities = Model::compile(run.scene)->initialVelocities();
    else
      f->velocities = (run.states[k] - run.states[k - 1]) / dt;
    if (k > 0 && k <= run.steps.size()) {
      f->stats = run.steps[k - 1];
      convergence.add(f->stats);
    }
    if (k > 0 && k < run.contacts.branches.size()) f->branches = run.contacts.branches[k];
    frames.push_back(std::move(f));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  frames_ = std::move(frames);
  scene_ = std::make_shared<const Scene>(run.scene);
  model_.reset();
  moduleNames_.clear();
  seconds_ = 0.0;
  restoredFrom_ = run.path;
  convergence_ = convergence;
  error_.clear();
  requested_ = static_cast<int>(frames_.size());
  ++runId_;
  status_ = Status::Done;
}

const char* SimulationCache::statusName(Status status) {
  switch (status) {
    case Status::Empty:
      return "empty";
    case Status::Running:
      return "running";
    case Status::Done:
      return "done";
    case Status::Cancelled:
      return "cancelled";
    case Status::Failed:
      return "failed";
  }
  return "?";
}

std::vector<std::uint8_t> nodeBranches(const StepContacts& contacts, int nodes) {
  std::vector<std::uint8_t> branches(static_cast<std::size_t>(nodes), 0);
  std::vector<double> strength(static_cast<std::size_t>(nodes), -1.0);
  for (const ContactPoint& p : contacts.points) {
    for (int end = 0; end < (p.partner >= 0 ? 2 : 1); ++end) {
      const int node = end == 0 ? p.node : p.partner;
      if (node < 0 || node >= nodes) continue;
      const double rank = p.impulse.norm() + (p.obstacle >= 0 ? 1e9 : 0.0);
      if (rank > strength[static_cast<std::size_t>(node)]) {
        strength[static_cast<std::size_t>(node)] = rank;
        branches[static_cast<std::size_t>(node)] = static_cast<std::uint8_t>(p.branch);
      }
    }
  }
  return branches;
}

void Playback::scrub(int k, int available) {
  frame_ = available > 0 ? std::clamp(k, 0, available - 1) : 0;
  accumulated_ = 0.0;
}

void Playback::step(int delta, int available) {
  playing_ = false;
  scrub(frame_ + delta, available);
}

void Playback::advance(double seconds, double dt, int available, bool growing) {
  if (!playing_ || available <= 0 || dt <= 0) return;
  accumulated_ += seconds * speed_;
  const int frames = static_cast<int>(accumulated_ / dt);
  accumulated_ -= frames * dt;
  const int last = available - 1;
  if (loop_ && !growing && frame_ + frames > last) {
    frame_ = (frame_ + frames) % available;
    return;
  }
  if (frame_ + frames >= last) {
    frame_ = last;
    accumulated_ = 0.0;
    if (!growing) playing_ = false;
  } else {
    frame_ += frames;
  }
}

}  // namespace weft::editor
