#include "SimulationCache.h"

#include "WorkerThreads.h"

#include <weft/physics/Simulator.h>
#include <weft/record/StepContacts.h>

#include <algorithm>

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
      frames_.push_back(std::move(first));
    }
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
