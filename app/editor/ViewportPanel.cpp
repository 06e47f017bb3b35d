#include "ViewportPanel.h"

#include "EditorApp.h"
#include "EditorGl.h"
#include "EditorSession.h"
#include "PanelStyle.h"
#include "ViewportTarget.h"

#include <weft/render/Legend.h>
#include <weft/render/Renderer.h>

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace weft::editor {

ViewportPanel::ViewportPanel(EditorSession& session, EditorApp& app, render::RenderContext& context)
    : session_(session), app_(app), context_(context) {
  target_ = std::make_unique<ViewportTarget>(context_, 640, 480);
  renderer_ = std::make_unique<render::Renderer>(*target_);
  style_.legend = true;
}

ViewportPanel::~ViewportPanel() {
  context_.makeCurrent();
  renderer_.reset();
  target_.reset();
}

void ViewportPanel::draw(float left, float top, float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(left, top));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  // No background: the image covers the whole window, and on a software GL every filled pixel
  // counts.
  ImGui::Begin("Viewport", nullptr,
               kFixedWindow | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoBackground);
  ImGui::PopStyleVar();
  const ImVec2 size = ImGui::GetContentRegionAvail();
  width_ = std::max(1, int(size.x));
  height_ = std::max(1, int(size.y));
  render();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  // The picture is opaque: drawn without blending, which on a software GL saves reading back
  // every pixel under it (Dear ImGui blends everything it draws; the reset callback restores its
  // state for what follows).
  ImDrawList* drawList = ImGui::GetWindowDrawList();
  drawList->AddCallback([](const ImDrawList*, const ImDrawCmd*) { weftEditorGl.Disable(GL_BLEND); },
                        nullptr);
  ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(target_->colorTexture())),
               ImVec2(float(width_), float(height_)), ImVec2(0, 1), ImVec2(1, 0));
  drawList->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  // The contact legend's labels beside the renderer's swatches (the renderer has no text), noted
  // as "legend:take-off", "legend:stick", "legend:slip" for scripts.
  if (style_.legend) {
    const render::RenderScene* shown = session_.viewport().scene();
    if (shown && shown->contacts) {
      const float fontHeight = ImGui::GetFontSize();
      for (const render::LegendSwatch& w : render::contactLegendSwatches(width_, height_)) {
        const char* name = render::branchName(w.branch);
        const ImVec2 text = ImGui::CalcTextSize(name);
        const ImVec2 at(origin.x + w.left - w.border - 6.0f - text.x,
                        origin.y + 0.5f * (w.top + w.bottom) - 0.5f * fontHeight);
        drawList->AddText(at, IM_COL32(40, 40, 46, 255), name);
        app_.noteItem(std::string("legend:") + name, at.x + 0.5f * text.x,
                      at.y + 0.5f * fontHeight);
      }
    }
  }
  ImGui::SetCursorScreenPos(origin);
  ImGui::InvisibleButton("viewport-input", ImVec2(float(width_), float(height_)),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const ImGuiIO& io = ImGui::GetIO();
  const bool hovered = ImGui::IsItemHovered();
  const ImVec2 mouse(io.MousePos.x - origin.x, io.MousePos.y - origin.y);
  x_ = int(origin.x);
  y_ = int(origin.y);
  render::Camera& camera = session_.camera();
  // The gizmo comes first: a press on one of its handles drags it rather than selecting.
  const GizmoHandle hoveredHandle =
      hovered && !draggingGizmo_ ? session_.placement().pickGizmo(mouse.x, mouse.y, width_, height_)
                                 : GizmoHandle::None;
  if (hovered && io.MouseWheel != 0.0f) camera.zoom(std::pow(0.9f, io.MouseWheel));
  // Orbit and pan follow every pixel of the drag: IsMouseDragging would hold them back until
  // ImGui's 6 px drag threshold and drop the motion before it (these buttons have no click to
  // tell apart from a drag). The press frame's delta is the way the mouse came, not the drag.
  const bool dragging = ImGui::IsItemActive() && !ImGui::IsItemActivated();
  if (dragging && ImGui::IsMouseDown(ImGuiMouseButton_Right))
    camera.orbit(-io.MouseDelta.x * 0.4f, io.MouseDelta.y * 0.4f);
  if (dragging && ImGui::IsMouseDown(ImGuiMouseButton_Middle)) {
    const float scale =
        camera.distance * 2.0f * std::tan(camera.fovYDeg * 3.14159265f / 360.0f) / float(height_);
    camera.pan(-io.MouseDelta.x * scale, io.MouseDelta.y * scale);
  }
  if (ImGui::IsItemActivated() && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    if (hoveredHandle != GizmoHandle::None) {
      const std::string error =
          session_.placement().beginGizmoDrag(hoveredHandle, mouse.x, mouse.y, width_, height_);
      if (error.empty())
        draggingGizmo_ = true;
      else
        app_.report(error, true);
    } else if (io.KeyAlt && !session_.targets().all().empty()) {
      // Alt + drag moves the selected vertices' targets in the view plane (one undo step).
      draggingTargets_ = true;
      ++dragCount_;
      targetDragLast_[0] = mouse.x;
      targetDragLast_[1] = mouse.y;
    } else {
      boxStart_[0] = mouse.x;
      boxStart_[1] = mouse.y;
      boxSelecting_ = true;
    }
  }
  if (draggingTargets_) {
    // Measured from where the button went down, not by the frame's mouse delta: the press frame's
    // delta is the way the mouse came, which is no part of the drag.
    const float dx = mouse.x - targetDragLast_[0], dy = mouse.y - targetDragLast_[1];
    if (dx != 0.0f || dy != 0.0f) {
      targetDragLast_[0] = mouse.x;
      targetDragLast_[1] = mouse.y;
      const std::string error =
          session_.targets().dragTargets(session_.selection().nodes(), dx, dy, width_, height_,
                                         "target drag " + std::to_string(dragCount_));
      if (!error.empty()) app_.report(error, true), draggingTargets_ = false;
    }
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) draggingTargets_ = false;
  }
  if (draggingGizmo_) {
    if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f) {
      const std::string error = session_.placement().dragGizmo(mouse.x, mouse.y);
      if (!error.empty()) app_.report(error, true);
    }
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) ||
        session_.placement().draggedHandle() == GizmoHandle::None) {
      session_.placement().endGizmoDrag();
      draggingGizmo_ = false;
    }
  }
  ImDrawList* draw = ImGui::GetWindowDrawList();
  if (boxSelecting_) {
    const bool dragged = ImGui::IsMouseDragging(ImGuiMouseButton_Left);
    if (dragged)
      draw->AddRect(ImVec2(origin.x + boxStart_[0], origin.y + boxStart_[1]), io.MousePos,
                    IM_COL32(255, 210, 60, 255));
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left)) {
      boxSelecting_ = false;
      const ImVec2 drag = ImGui::GetMouseDragDelta(ImGuiMouseButton_Left);
      if (drag.x != 0.0f || drag.y != 0.0f)
        session_.selecting().boxSelectPixels(boxStart_[0], boxStart_[1], mouse.x, mouse.y, width_,
                                             height_, io.KeyShift);
      else if (io.KeyCtrl)
        pickObjectAt(mouse.x, mouse.y);
      else
        session_.selecting().clickSelect(mouse.x, mouse.y, width_, height_, io.KeyShift);
    }
  }
  // Selected vertices and lines to their targets, drawn over the image (not part of viewport
  // screenshots).
  if (const render::RenderScene* scene = session_.viewport().scene()) {
    for (const FinalTarget& t : session_.targets().all()) {
      if (t.node >= scene->cloth.positions.rows()) continue;
      const auto from =
          projectToPixel(camera, scene->cloth.positions.row(t.node).transpose(), width_, height_);
      const auto to = projectToPixel(camera, t.position.cast<float>(), width_, height_);
      if (from && to)
        draw->AddLine(ImVec2(origin.x + from->x(), origin.y + from->y()),
                      ImVec2(origin.x + to->x(), origin.y + to->y()), IM_COL32(160, 80, 200, 220),
                      1.5f);
    }
    for (int node : session_.selection().nodes()) {
      if (node >= scene->cloth.positions.rows()) continue;
      const auto p =
          projectToPixel(camera, scene->cloth.positions.row(node).transpose(), width_, height_);
      if (!p) continue;
      const ImVec2 at(origin.x + p->x(), origin.y + p->y());
      // White with a dark rim: unlike every contact branch's colour (blue take-off, red stick,
      // yellow slip), the cloth's orange and blue, targets' purple and handles' green.
      draw->AddCircleFilled(at, 4.5f, IM_COL32(20, 20, 24, 255));
      draw->AddCircleFilled(at, 3.0f, IM_COL32(255, 255, 255, 255));
      // The inspected vertex gets a ring as well.
      if (node == session_.selection().focus()) {
        draw->AddCircle(at, 9.0f, IM_COL32(20, 20, 24, 255), 0, 4.0f);
        draw->AddCircle(at, 9.0f, IM_COL32(255, 255, 255, 255), 0, 2.0f);
      }
    }
  }
  drawGizmo(draw, origin.x, origin.y, hoveredHandle);
  if (!session_.document().valid())
    draw->AddText(
        ImVec2(origin.x + 10, origin.y + 10), IM_COL32(230, 80, 70, 255),
        "The scene does not validate: showing the last valid state (see the Scene panel).");
  ImGui::End();
}

void ViewportPanel::pickObjectAt(float x, float y) {
  const std::string error = session_.placement().clickObject(x, y, width_, height_);
  const std::string picked = session_.placement().activeObject().path();
  if (!error.empty())
    app_.report(error, true);
  else
    app_.report(picked.empty() ? "nothing there: gizmo off" : "gizmo on " + picked, false);
}

void ViewportPanel::drawGizmo(ImDrawList* draw, float originX, float originY, GizmoHandle hovered) {
  const auto gizmo = session_.placement().gizmo(width_, height_);
  if (!gizmo) return;
  const GizmoHandle active = session_.placement().draggedHandle() != GizmoHandle::None
                                 ? session_.placement().draggedHandle()
                                 : hovered;
  const ImU32 axisColours[3] = {IM_COL32(225, 60, 50, 255), IM_COL32(60, 175, 60, 255),
                                IM_COL32(50, 100, 230, 255)};
  const ImU32 highlight = IM_COL32(255, 200, 40, 255), outline = IM_COL32(20, 20, 24, 200);
  auto at = [&](const Eigen::Vector2f& p) { return ImVec2(originX + p.x(), originY + p.y()); };
  // Rings under the arrows; every handle has a dark outline so it reads on light and dark.
  for (GizmoHandle h :
       {GizmoHandle::RotateX, GizmoHandle::RotateY, GizmoHandle::RotateZ, GizmoHandle::TranslateX,
        GizmoHandle::TranslateY, GizmoHandle::TranslateZ}) {
    if (!gizmo->has(h)) continue;
    const std::vector<Eigen::Vector2f> line = gizmo->screenPolyline(h);
    if (line.size() < 2) continue;
    const ImU32 colour = h == active ? highlight : axisColours[gizmoAxis(h)];
    std::vector<ImVec2> points;
    for (const Eigen::Vector2f& p : line) points.push_back(at(p));
    const bool ring = isRotation(h);
    draw->AddPolyline(points.data(), int(points.size()), outline, 0, ring ? 4.5f : 5.5f);
    draw->AddPolyline(points.data(), int(points.size()), colour, 0, ring ? 2.5f : 3.5f);
    if (!ring) {
      // The arrow head, in screen space along the shaft's image.
      const Eigen::Vector2f tip = line.back(), along = line.back() - line.front();
      if (along.norm() > 1.0f) {
        const Eigen::Vector2f d = along.normalized(), n(-d.y(), d.x());
        const Eigen::Vector2f base = tip - 12.0f * d;
        draw->AddTriangleFilled(at(tip + 3.0f * d), at(base + 6.5f * n), at(base - 6.5f * n),
                                outline);
        draw->AddTriangleFilled(at(tip), at(base + 5.0f * n), at(base - 5.0f * n), colour);
      }
    }
  }
  if (const auto centre = projectToPixel(session_.camera(), gizmo->origin(), width_, height_)) {
    draw->AddCircleFilled(at(*centre), 4.5f, outline);
    draw->AddCircleFilled(at(*centre), 3.0f, IM_COL32(250, 250, 250, 255));
  }
}

bool ViewportPanel::ViewportState::operator==(const ViewportState& o) const {
  return frameVersion == o.frameVersion && width == o.width && height == o.height &&
         std::equal(camera, camera + 11, o.camera) && wireframe == o.wireframe &&
         legend == o.legend && groundGrid == o.groundGrid;
}

void ViewportPanel::render() {
  target_->resize(width_, height_);
  const render::RenderScene* scene = session_.viewport().scene();
  const render::Camera& c = session_.camera();
  ViewportState now;
  now.frameVersion = session_.viewport().version();
  now.width = width_;
  now.height = height_;
  const float camera[11] = {
      c.target.x(),      c.target.y(), c.target.z(), c.distance,
      c.yawDeg,          c.pitchDeg,   c.fovYDeg,    c.orthographic ? 1.0f : 0.0f,
      c.orthoHalfHeight, c.nearPlane,  c.farPlane};
  std::copy(camera, camera + 11, now.camera);
  now.wireframe = style_.wireframe;
  now.legend = style_.legend;
  now.groundGrid = style_.groundGrid;
  // An unchanged picture is not drawn again (the texture keeps it): on a software GL the
  // viewport is most of a frame's cost.
  if (now == drawn_) return;
  render::RenderScene empty;
  try {
    renderer_->render(scene ? *scene : empty, c, style_);
    drawn_ = now;
  } catch (const std::exception& e) {
    app_.report(std::string("viewport: ") + e.what(), true);
  }
  context_.makeCurrent();
}

render::Image ViewportPanel::image(int width, int height) {
  const int w = width_, h = height_;
  target_->resize(width, height);
  const render::RenderScene* scene = session_.viewport().scene();
  const render::RenderScene empty;
  render::Image image = renderer_->renderImage(scene ? *scene : empty, session_.camera(), style_);
  target_->resize(w, h);
  drawn_ = ViewportState();  // the texture now holds the screenshot's picture
  context_.makeCurrent();
  return image;
}

}  // namespace weft::editor
