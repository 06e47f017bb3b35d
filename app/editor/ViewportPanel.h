#pragma once
// The viewport: the Renderer drawing the session's picture (ViewportFrame) into an off-screen
// target shown as an image, redrawn only when the picture, size, camera or style changes; and
// the input over it: orbit (right drag), pan (middle drag), zoom (wheel), click and box
// selection (Shift adds), Ctrl+click picking the object the gizmo places, gizmo drags, and
// Alt+drag moving the selected vertices' targets. Drawn over the image (not part of viewport
// screenshots): the selection, lines to the targets, and the gizmo.

#include "Gizmo.h"

#include <weft/render/Image.h>
#include <weft/render/RenderContext.h>
#include <weft/render/RenderStyle.h>

#include <memory>

struct ImDrawList;

namespace weft::render {
class Renderer;
}

namespace weft::editor {

class EditorApp;
class EditorSession;
class ViewportTarget;

class ViewportPanel {
 public:
  // `context` is current; the viewport's target and renderer draw through it.
  ViewportPanel(EditorSession& session, EditorApp& app, render::RenderContext& context);
  ~ViewportPanel();
  ViewportPanel(const ViewportPanel&) = delete;
  ViewportPanel& operator=(const ViewportPanel&) = delete;

  // Drawn as a fixed window at (left, top), width x height window pixels.
  void draw(float left, float top, float width, float height);
  // The viewport alone, drawn at width x height with the current camera and style.
  render::Image image(int width, int height);

  // Size in pixels and top-left pixel in the window, as laid out by the last frame.
  int width() const { return width_; }
  int height() const { return height_; }
  int x() const { return x_; }
  int y() const { return y_; }
  float aspect() const { return float(width_) / float(height_ > 1 ? height_ : 1); }
  // A gizmo drag is under way (Esc does not take the gizmo off then).
  bool draggingGizmo() const { return draggingGizmo_; }
  render::RenderStyle& style() { return style_; }
  const render::RenderStyle& style() const { return style_; }

 private:
  void render();
  void drawGizmo(ImDrawList* draw, float originX, float originY, GizmoHandle hovered);
  void pickObjectAt(float x, float y);  // Ctrl+click in the viewport (viewport pixels)

  EditorSession& session_;
  EditorApp& app_;
  render::RenderContext& context_;
  std::unique_ptr<ViewportTarget> target_;
  std::unique_ptr<render::Renderer> renderer_;
  render::RenderStyle style_;
  int width_ = 1, height_ = 1, x_ = 0, y_ = 0;
  bool boxSelecting_ = false;
  bool draggingTargets_ = false;
  bool draggingGizmo_ = false;
  int dragCount_ = 0;  // numbers target drags, so each drag is one undo step
  float boxStart_[2] = {0, 0};
  float targetDragLast_[2] = {0, 0};  // the mouse when a target drag last moved the targets
  // What the target shows now; it is drawn again only when this changes.
  struct ViewportState {
    long frameVersion = -1;
    int width = 0, height = 0;
    float camera[11] = {};
    bool wireframe = false, legend = false, groundGrid = false;
    bool operator==(const ViewportState& o) const;
  } drawn_;
};

}  // namespace weft::editor
