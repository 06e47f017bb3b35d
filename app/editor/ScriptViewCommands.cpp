// Script commands on what is shown: the camera, screenshots of the viewport and the window, the
// panel tab, and the contact overlays.
#include "EditorApp.h"
#include "EditorSession.h"
#include "ScriptCommands.h"

#include <weft/render/Image.h>

#include <algorithm>

namespace weft::editor {
namespace {

bool camera(ScriptCall& call) {
  const nlohmann::json& c = call.action.at("camera");
  if (c.is_string()) {
    render::NamedView view;
    if (!render::parseNamedView(c.get<std::string>(), view))
      throw std::invalid_argument("camera must be front, side, top, auto or an object");
    call.session.frameCamera(call.aspect(), view);
  } else {
    render::Camera& cam = call.session.camera();
    cam.yawDeg = c.value("yaw", cam.yawDeg);
    cam.pitchDeg = c.value("pitch", cam.pitchDeg);
    cam.distance = c.value("distance", cam.distance);
    if (c.contains("target")) {
      const auto t = c["target"].get<std::vector<float>>();
      if (t.size() != 3) throw std::invalid_argument("camera target must be [x, y, z]");
      cam.target = render::Vec3f(t[0], t[1], t[2]);
    }
  }
  return true;
}

bool screenshot(ScriptCall& call) {
  const nlohmann::json& a = call.action;
  EditorApp& app = call.app;
  if (a.value("overlays", false)) {
    // The viewport as the window shows it, with what the editor draws over the picture (the
    // gizmo, the selection, target lines): cut from the last drawn window, so at its size.
    if (a.contains("size"))
      throw std::invalid_argument("a screenshot with overlays has the viewport's own size");
    const render::Image window = app.windowImage();
    render::Image image(app.viewportWidth(), app.viewportHeight());
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const int wx = std::min(app.viewportX() + x, window.width - 1),
                  wy = std::min(app.viewportY() + y, window.height - 1);
        std::copy(window.at(wx, wy), window.at(wx, wy) + 3, image.at(x, y));
      }
    render::writePng(outputFile(a.at("screenshot")), image);
    return true;
  }
  int w = app.viewportWidth(), h = app.viewportHeight();
  if (a.contains("size")) {
    const auto s = intsOf(a["size"]);
    if (s.size() != 2 || s[0] <= 0 || s[1] <= 0 || s[0] > 16384 || s[1] > 16384)
      throw std::invalid_argument("size must be [width, height], each 1 to 16384 pixels");
    w = s[0], h = s[1];
  }
  render::writePng(outputFile(a.at("screenshot")), app.viewportImage(w, h));
  return true;
}

bool windowScreenshot(ScriptCall& call) {
  render::writePng(outputFile(call.action.at("window_screenshot")), call.app.windowImage());
  return true;
}

bool panel(ScriptCall& call) {
  PanelTab tab;
  if (!parsePanelTab(call.action.at(call.kind).get<std::string>(), tab))
    throw std::invalid_argument("panel must be scene, inspect, targets or optimise");
  call.app.showTab(tab);
  return true;
}

bool contactColours(ScriptCall& call) {
  call.session.viewport().contactColours = call.action.at(call.kind).get<bool>();
  return true;
}

// {"see_through": true|false}: the View menu's See-through cloth (opacity 0.45 as there).
bool seeThrough(ScriptCall& call) {
  call.app.style().clothOpacity = call.action.at(call.kind).get<bool>() ? 0.45f : 1.0f;
  return true;
}

// {"obstacles_in_front": true|false}: the View menu's Obstacles in front.
bool obstaclesInFront(ScriptCall& call) {
  call.app.style().obstaclesInFront = call.action.at(call.kind).get<bool>();
  return true;
}

bool forceArrows(ScriptCall& call) {
  call.session.viewport().forceArrows = call.action.at(call.kind).get<bool>();
  return true;
}

}  // namespace

void addViewCommands(ScriptCommandTable& table) {
  table["camera"] = camera;
  table["screenshot"] = screenshot;
  table["window_screenshot"] = windowScreenshot;
  table["panel"] = panel;
  table["contact_colours"] = contactColours;
  table["force_arrows"] = forceArrows;
  table["see_through"] = seeThrough;
  table["obstacles_in_front"] = obstaclesInFront;
}

}  // namespace weft::editor
