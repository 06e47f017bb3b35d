#pragma once
// The timeline under the viewport: Simulate and Cancel with the cache's progress, play/pause
// and stepping, the frame slider (with the active handle's keys as ticks), the state's time and
// solver statistics, and the active handle's offset and key buttons.

namespace weft::editor {

class EditorApp;
class EditorSession;

class TimelinePanel {
 public:
  TimelinePanel(EditorSession& session, EditorApp& app);
  // Drawn as a fixed window at (left, top), width x height window pixels.
  void draw(float left, float top, float width, float height);

 private:
  void drawKeyTicks(int frames);
  void keyControls();

  EditorSession& session_;
  EditorApp& app_;
};

}  // namespace weft::editor
