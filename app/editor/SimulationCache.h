#pragma once
// The editor's timeline data: a worker thread runs the Simulator on a copy of the validated
// scene and appends every state to a frame cache (positions, per-node contact branch, step
// statistics) while the UI keeps drawing. The UI reads frames as they arrive, shows progress,
// can cancel, and knows the cache is stale once the document differs from the one simulated.
// No GL and no window: unit tested on its own.

#include <weft/core/Types.h>
#include <weft/output/RunFolder.h>
#include <weft/record/ConvergenceReport.h>
#include <weft/record/StepContacts.h>
#include <weft/record/StepStats.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/Scene.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace weft::editor {

struct CachedFrame {
  int state = 0;          // 0 = the initial state
  NodeMatrix positions;   // all cloth nodes, scene order
  NodeMatrix velocities;  // m/s, same layout (the vertex inspector shows them)
  // Per node: the Signorini-Coulomb branch of the step that produced this state (0 none,
  // 1 take-off, 2 stick, 3 slip), chosen as `weft simulate` writes contact_branches.npy: an
  // obstacle contact before any self-collision pair, else the strongest. Empty for state 0
  // and for scenes without contact.
  std::vector<std::uint8_t> branches;
  StepStats stats;  // of the step that produced this state (zero for state 0)
  // Every contact of that step as the solver left it (branch, normal, impulse, velocity), for
  // the vertex inspector and the force arrows. Empty for state 0 and scenes without contact.
  StepContacts contacts;
  // The pieces of the step when adaptive time stepping split it (the backward pass runs
  // through them); empty when it was solved whole.
  std::vector<Substep> substeps;
};

class SimulationCache {
 public:
  enum class Status { Empty, Running, Done, Cancelled, Failed };

  SimulationCache() = default;
  ~SimulationCache();  // cancels a running simulation and waits for the worker
  SimulationCache(const SimulationCache&) = delete;
  SimulationCache& operator=(const SimulationCache&) = delete;

  // Drops the cache and simulates `steps` steps of `scene` (which must be valid) off the
  // calling thread: states 0..steps. A running simulation is cancelled first.
  void start(std::shared_ptr<const Scene> scene, int steps);
  // Asks the worker to stop after its current step and waits for it. The frames computed so
  // far stay available (status Cancelled).
  void cancel();
  void wait();   // until the worker has finished (any status)
  void clear();  // cancels and drops every frame (status Empty)

  Status status() const { return status_.load(); }
  bool running() const { return status() == Status::Running; }
  int frameCount() const;                                    // states available so far
  int requestedFrames() const { return requested_.load(); }  // steps + 1 of the last start
  double progress() const;    // frameCount / requestedFrames, in [0, 1]
  std::string error() const;  // the failure message (status Failed)
  // The frame of state k (0 <= k < frameCount()), or null. Safe while the worker appends.
  std::shared_ptr<const CachedFrame> frame(int k) const;
  // The cached states as the recorded run the engine's losses and backward pass read: positions
  // and velocities of every state, step statistics, (when any step touched) contacts and the
  // model the worker simulated (null before its first frame).
  Trajectory trajectory() const;
  // How well the cached steps were solved so far: steps stopped at the iteration limit, the
  // worst residual, the deepest node inside an obstacle (the timeline shows it).
  ConvergenceReport convergence() const;
  // The scene the cache was computed from (null when empty).
  std::shared_ptr<const Scene> scene() const;
  // True when there are frames and they were computed from a document other than `document`:
  // a parameter changed since, and the timeline shows old results. Keys that do not change
  // the motion (task, name, description) are ignored: editing a target keeps the run current.
  bool staleFor(const nlohmann::json& document) const;
  // Describes the cached run by `scene` from now on: for a document that moved without changing
  // what it simulates (Save As naming the same files from another folder), so that the frames
  // stay current for it. The caller vouches that `scene` simulates as the cached one did. Does
  // nothing on an empty cache.
  void relabel(std::shared_ptr<const Scene> scene);
  // Writes the finished run (status Done) as a `weft simulate` run folder (RunWriter.h) at
  // `folder`, with velocities.npy beside positions.npy, replacing what was there only once all
  // of it is written (StagedDirectory). A reopened run (restored()) is copied from where it came
  // from. Throws InputError.
  void save(const std::string& folder) const;
  // Replaces the cache with a saved run (what save() wrote, or a `weft simulate` folder): status
  // Done with its positions, velocities (velocities.npy, else (x_k - x_k-1) / dt, DiffCloth
  // Eq. 4's update), per-node branches and step statistics. The solver's contact records and
  // sub-steps are not in the format: restored() stays true until the next start() or clear(),
  // and the backward pass asks for a new simulation. `run.scene` must be the document's.
  void restore(const RunFolder& run);
  bool restored() const { return !restoredFrom_.empty(); }
  // Changes with every start() and clear(): lets readers keep what they derived from one run.
  long runId() const { return runId_.load(); }

  static const char* statusName(Status status);

 private:
  void run(std::shared_ptr<const Scene> scene, int steps);
  void join();

  mutable std::mutex mutex_;
  std::vector<std::shared_ptr<const CachedFrame>> frames_;
  std::shared_ptr<const Scene> scene_;
  std::shared_ptr<const Model> model_;    // the worker's, once its simulator is built
  std::vector<std::string> moduleNames_;  // the worker's simulator's (the frames' module times)
  double seconds_ = 0.0;                  // wall time of the worker's steps
  std::string restoredFrom_;  // the folder restore() read, when the frames came from disk
  ConvergenceReport convergence_;
  std::string error_;
  std::atomic<Status> status_{Status::Empty};
  std::atomic<int> requested_{0};
  std::atomic<long> runId_{0};
  std::atomic<bool> cancel_{false};
  std::thread worker_;
};

// Per-node branches of one step's contacts (see CachedFrame::branches).
std::vector<std::uint8_t> nodeBranches(const StepContacts& contacts, int nodes);

// The part of a scene document that decides the motion: without task, name and description.
nlohmann::json simulatedPart(const nlohmann::json& document);

// Playback over the cache: the current frame, play/pause at the scene's own rate (one state
// per dt of wall-clock time times `speed`), single steps, scrubbing. Pure arithmetic.
class Playback {
 public:
  int frame() const { return frame_; }
  bool playing() const { return playing_; }
  double speed() const { return speed_; }
  void setSpeed(double speed) { speed_ = speed > 0 ? speed : 1.0; }

  // Moves to frame k, clamped to [0, available - 1] (0 with nothing available).
  void scrub(int k, int available);
  void step(int delta, int available);  // one frame forwards (or back); pauses
  void play() { playing_ = true; }
  void pause() { playing_ = false; }
  void toggle() { playing_ = !playing_; }
  // Looping: playing past the last frame goes on from the first instead of stopping.
  bool loop() const { return loop_; }
  void setLoop(bool loop) { loop_ = loop; }
  // Advances by wall-clock `seconds` while playing; at the last available frame stops, or with
  // loop() wraps to the first, unless more frames are still coming (`growing`: it waits there).
  // `dt` is the scene's time step.
  void advance(double seconds, double dt, int available, bool growing);

 private:
  int frame_ = 0;
  bool playing_ = false, loop_ = false;
  double speed_ = 1.0;
  double accumulated_ = 0.0;  // wall-clock seconds not yet turned into frames
};

}  // namespace weft::editor
