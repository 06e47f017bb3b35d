// Script commands of raw input: mouse moves, presses, clicks, drags and scrolls, key presses
// and typed text, fed to ImGui's IO one change per UI frame as a person's input would be.
#include "EditorApp.h"
#include "ScriptCommands.h"

#include <iterator>

namespace weft::editor {
namespace {

// A point of a raw-input action in window pixels (x right, y down from the window's top-left,
// what ImGui's io.MousePos takes): [x, y], or {"viewport": [x, y]} in the viewport pixels of
// click and box_select, placed where the last frame laid the viewport out, or {"item": NAME}:
// where the last frame drew the named item (EditorApp::itemPoint: a document field by its path,
// "tab:scene", "timeline:simulate"...), or {"item_index": k}: the k-th of those items by name.
Eigen::Vector2f pointOf(const nlohmann::json& j, const char* what, const EditorApp& app) {
  if (j.is_object() && j.contains("item_index")) {
    // The k-th named item (by name, modulo their number) of the last frame: lets a generated
    // script (the monkey test) aim at whatever widgets are on screen.
    const auto& items = app.itemPoints();
    if (items.empty())
      throw std::invalid_argument(std::string(what) +
                                  ": no named item was drawn in the last frame");
    const long n = long(items.size());
    auto it = items.begin();
    std::advance(it, ((long(intOf(j["item_index"])) % n) + n) % n);
    return Eigen::Vector2f(it->second[0], it->second[1]);
  }
  if (j.is_object() && j.contains("item")) {
    const std::string name = j["item"].get<std::string>();
    const std::array<float, 2>* point = app.itemPoint(name);
    if (!point)
      throw std::invalid_argument(std::string(what) + ": the item " + name +
                                  " was not drawn in the last frame");
    return Eigen::Vector2f((*point)[0], (*point)[1]);
  }
  const bool inViewport = j.is_object() && j.contains("viewport");
  const nlohmann::json& p = inViewport ? j["viewport"] : j;
  if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
    throw std::invalid_argument(std::string(what) +
                                " takes [x, y] in window pixels, {\"viewport\": [x, y]} or "
                                "{\"item\": NAME}");
  Eigen::Vector2f at(p[0].get<float>(), p[1].get<float>());
  if (inViewport) at += Eigen::Vector2f(float(app.viewportX()), float(app.viewportY()));
  return at;
}

int buttonOf(const nlohmann::json& j) {
  int button = 0;
  if (!j.is_string() || !parseMouseButton(j.get<std::string>(), button))
    throw std::invalid_argument("a mouse button is \"left\", \"right\" or \"middle\"");
  return button;
}

KeyChord chordOf(const nlohmann::json& j, bool modifiersOnly) {
  KeyChord chord;
  if (!j.is_string() || !parseKeyChord(j.get<std::string>(), chord))
    throw std::invalid_argument("unknown key " + j.dump() +
                                " (keys are named like \"ctrl+shift+z\", \"space\", \"f\")");
  if (modifiersOnly && chord.key >= 0)
    throw std::invalid_argument("modifiers are ctrl, shift, alt, super joined by +, got " +
                                j.dump());
  return chord;
}

// A raw-input action as one change of the input per frame.
void queueInput(const nlohmann::json& a, const std::string& kind, const EditorApp& app,
                std::deque<std::function<void(ScriptedInput&)>>& steps) {
  using Step = std::function<void(ScriptedInput&)>;
  const KeyChord held = a.contains("modifiers") ? chordOf(a["modifiers"], true) : KeyChord();
  auto move = [](Eigen::Vector2f p) { return [p](ScriptedInput& in) { in.moveTo(p.x(), p.y()); }; };
  if (kind == "mouse_move") {
    steps.push_back(move(pointOf(a.at(kind), "mouse_move", app)));
  } else if (kind == "mouse_press" || kind == "mouse_release") {
    // With "at", the move and the button change fall in one frame (a quick move and click).
    const int button = buttonOf(a.at(kind));
    const bool down = kind == "mouse_press";
    const std::optional<Eigen::Vector2f> at =
        a.contains("at") ? std::optional(pointOf(a["at"], "at", app)) : std::nullopt;
    steps.push_back([=](ScriptedInput& in) {
      if (at) in.moveTo(at->x(), at->y());
      in.setButton(button, down);
    });
  } else if (kind == "mouse_click" || kind == "mouse_drag") {
    // Modifiers go down with the move to the start and up a frame after the release, since the
    // editor reads them on the release frame (Shift adds to a box, Ctrl picks an object).
    const int button =
        buttonOf(kind == "mouse_click" ? a.value("button", nlohmann::json("left")) : a.at(kind));
    const Eigen::Vector2f from =
        pointOf(kind == "mouse_click" ? a.at(kind) : a.at("from"), "from", app);
    steps.push_back([=](ScriptedInput& in) {
      in.setModifiers(held, true);
      in.moveTo(from.x(), from.y());
    });
    steps.push_back([=](ScriptedInput& in) { in.setButton(button, true); });
    if (kind == "mouse_drag") {
      const Eigen::Vector2f to = pointOf(a.at("to"), "to", app);
      const int n = a.value("steps", 8);
      if (n < 1) throw std::invalid_argument("steps must be at least 1");
      for (int i = 1; i <= n; ++i)
        steps.push_back(move(from + (to - from) * (float(i) / float(n))));
    }
    steps.push_back([=](ScriptedInput& in) { in.setButton(button, false); });
    steps.push_back([=](ScriptedInput& in) { in.setModifiers(held, false); });
  } else if (kind == "scroll") {
    const float notches = a.at(kind).get<float>();
    const std::optional<Eigen::Vector2f> at =
        a.contains("at") ? std::optional(pointOf(a["at"], "at", app)) : std::nullopt;
    steps.push_back([=](ScriptedInput& in) {
      if (at) in.moveTo(at->x(), at->y());
      in.scroll(notches);
    });
  } else if (kind == "key" || kind == "key_down" || kind == "key_up") {
    // A key press is down for one frame and up the next (ImGui sees a press on the first frame
    // a key is down); key_down and key_up hold and let go across actions.
    const KeyChord chord = chordOf(a.at(kind), false);
    const Step down = [=](ScriptedInput& in) {
      in.setModifiers(chord, true);
      in.setKey(chord.key, true);
    };
    const Step up = [=](ScriptedInput& in) {
      in.setKey(chord.key, false);
      in.setModifiers(chord, false);
    };
    if (kind != "key_up") steps.push_back(down);
    if (kind != "key_down") steps.push_back(up);
  } else if (kind == "type") {
    const std::string text = a.at(kind).get<std::string>();
    steps.push_back([=](ScriptedInput& in) { in.type(text); });
  }
}

// Queued on the first call, then played a step per call (each step read by the following frame).
// True when all steps have been read.
bool playInput(ScriptCall& call) {
  ScriptProgress& progress = call.progress;
  if (!progress.inputQueued) {
    progress.inputSteps.clear();
    queueInput(call.action, call.kind, call.app, progress.inputSteps);
    progress.inputQueued = true;
  }
  if (!progress.inputSteps.empty()) {
    progress.inputSteps.front()(call.input);
    progress.inputSteps.pop_front();
    return false;  // the next frame reads it
  }
  progress.inputQueued = false;
  return true;
}

}  // namespace

void addInputCommands(ScriptCommandTable& table) {
  for (const char* k : {"mouse_move", "mouse_press", "mouse_release", "mouse_click", "mouse_drag",
                        "scroll", "key", "key_down", "key_up", "type"})
    table[k] = playInput;
}

}  // namespace weft::editor
