#include "Timeline.h"

#include <algorithm>
#include <cmath>

namespace weft::editor {

Timeline::Timeline(const EditorDocument& document, SimulationCache& cache, Playback& playback,
                   const ViewportFrame& viewport)
    : document_(document), cache_(cache), playback_(playback), viewport_(viewport) {}

std::string Timeline::simulate(int steps) {
  auto scene = document_.sharedScene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const int count = steps >= 0 ? steps : scene->time.steps;
  cache_.start(scene, count);
  // The frame being looked at stays (clamped to the new run): the viewport shows the newest
  // state until the run reaches it, then that frame of the new run.
  playback_.scrub(playback_.frame(), count + 1);
  return "";
}

const Scene* Timeline::scene() const {
  return document_.valid() ? document_.scene() : viewport_.lastValidScene().get();
}

int Timeline::frames() const {
  const Scene* scene = this->scene();
  return std::max(cache_.frameCount(), scene ? scene->time.steps + 1 : 1);
}

double Timeline::time() const {
  const Scene* scene = this->scene();
  // Rounded to 1e-12 s so that a key written at frame 3 of dt = 0.0111 reads 0.0333 in the file
  // rather than 0.033299999999999996; far below any time step the simulator compares against.
  return scene ? std::round(playback_.frame() * scene->time.dt * 1e12) / 1e12 : 0.0;
}

void Timeline::goToStart() {
  playback_.scrub(0, frames());
}

void Timeline::goToEnd() {
  const int available = cache_.frameCount();
  playback_.scrub(available > 0 ? available - 1 : frames() - 1, frames());
}

void Timeline::togglePlayback() {
  // Playing on from the end would stop at once. A growing cache is left alone (its end is not
  // the end).
  const int available = cache_.frameCount();
  if (!playback_.playing() && playback_.frame() >= available - 1 && !cache_.running())
    playback_.scrub(0, available);
  playback_.toggle();
}

void Timeline::advance(double seconds) {
  const int available = cache_.frameCount();
  const Scene* scene = cache_.scene().get();
  playback_.advance(seconds, scene ? scene->time.dt : 0.01, available, cache_.running());
  const int frames = this->frames();
  if (playback_.frame() >= frames) playback_.scrub(playback_.frame(), frames);
}

}  // namespace weft::editor
