#pragma once
// The timeline under the viewport: Simulate and Cancel with the cache's progress, the run's
// solver verdict (a red banner when steps stopped at the iteration limit), play/pause and
// stepping, the frame slider (with a red tick per unconverged step and the active handle's keys
// as ticks), the state's time and solver statistics, and the active handle's offset and key
// buttons.

#include <string>

namespace weft::editor {

class EditorApp;
class EditorSession;

class TimelinePanel {
 public:
  TimelinePanel(EditorSession& session, EditorApp& app);
  // Drawn as a fixed window at (left, top), width x height window pixels.
  void draw(float left, float top, float width, float height);

  // What the last frame drew of the solver's state: the banner's text ("" for none) and the
  // number of unconverged-step ticks on the slider.
  const std::string& banner() const { return banner_; }
  int unconvergedTicks() const { return unconvergedTicks_; }

 private:
  void drawUnconvergedTicks(int frames);
  void drawKeyTicks(int frames);
  void keyControls();

  EditorSession& session_;
  EditorApp& app_;
  std::string banner_;
  int unconvergedTicks_ = 0;
  std::string runMessage_;  // "simulating N steps" while the run it announced lasts
};

}  // namespace weft::editor
