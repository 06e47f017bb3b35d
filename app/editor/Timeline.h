#pragma once
// The timeline: simulating the document into the cache, and playback (SimulationCache.h) over
// the states it spans.
// It spans the scene's time.steps + 1 states, or more when the cache holds more: a state not
// simulated yet can be shown (the viewport keeps the last cached state) so that keys can be set
// anywhere on the timeline before simulating.

#include "EditorDocument.h"
#include "SimulationCache.h"
#include "ViewportFrame.h"

#include <string>

namespace weft::editor {

class Timeline {
 public:
  Timeline(const EditorDocument& document, SimulationCache& cache, Playback& playback,
           const ViewportFrame& viewport);

  Playback& playback() { return playback_; }
  const Playback& playback() const { return playback_; }

  // Starts simulating the current document (`steps`, or the scene's time.steps when < 0),
  // staying at the playback frame (clamped to the new run's last state). Returns an error text when
  // the document does not validate.
  std::string simulate(int steps = -1);
  bool cacheStale() const { return cache_.staleFor(document_.document()); }
  int availableFrames() const { return cache_.frameCount(); }  // frames the cache holds
  int frames() const;                                          // states the timeline spans
  // The time of the playback frame: frame * dt of the scene being edited, in seconds.
  double time() const;
  // The scene whose time steps the timeline counts: the document's, or the last valid one.
  const Scene* scene() const;
  // |< and Home: the first state. >| and End: the last simulated state, or the timeline's last
  // when nothing is cached. Playing or paused as before.
  void goToStart();
  void goToEnd();
  // Play or pause (the Play button, Space). Play at the last state starts again from the first.
  void togglePlayback();
  // Playback advance over `seconds`, clamping the frame to the timeline.
  void advance(double seconds);
  // A new document: back to the first frame, paused.
  void reset() { playback_ = Playback(); }

 private:
  const EditorDocument& document_;
  SimulationCache& cache_;
  Playback& playback_;
  const ViewportFrame& viewport_;
};

}  // namespace weft::editor
