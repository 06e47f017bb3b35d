#pragma once
// Mouse and keyboard input a script plays into Dear ImGui the way a platform backend does, so
// that scripted sessions run EditorApp's own input handling (orbit, pan, zoom, clicks, drags,
// shortcuts, dialogs) rather than the session methods behind it.
//
// Dear ImGui 1.86 (Debian's) reads input as state set before each NewFrame (io.MousePos,
// io.MouseDown, io.MouseWheel, io.KeysDown, io.KeyCtrl...), not as queued events: this class
// holds that state and writes it into ImGuiIO once per frame. A press and its release must
// therefore fall in different frames, which the script runner arranges.
//
// Keys are GLFW's key codes, the ones ImGui's GLFW backend puts into io.KeysDown in a window
// (EditorApp names letter shortcuts by them), so the same shortcut code runs headless.

#include <array>
#include <cfloat>
#include <string>

struct ImGuiIO;

namespace weft::editor {

// "left", "right", "middle": Dear ImGui's button index (0, 1, 2). False for anything else.
bool parseMouseButton(const std::string& text, int& button);

// A key with the modifiers held with it, e.g. "ctrl+shift+z", "space", "f", "escape", "alt".
// `key` is a GLFW key code; a chord of modifiers only (e.g. "alt") has key -1.
struct KeyChord {
  int key = -1;
  bool ctrl = false, shift = false, alt = false, super = false;
};
// Names: a-z, 0-9, space, enter, escape (esc), tab, backspace, delete, insert, home, end,
// pageup, pagedown, left, right, up, down, f1-f12; modifiers ctrl, shift, alt, super joined by
// "+". False (and `chord` unchanged) for an unknown name or two keys.
bool parseKeyChord(const std::string& text, KeyChord& chord);

class ScriptedInput {
 public:
  // io.KeyMap as ImGui's GLFW backend sets it for a window: ImGui's named keys (arrows, Enter,
  // Escape, Ctrl+A/C/V/X/Y/Z...) at GLFW's codes. The headless platform calls it once.
  static void installKeyMap(ImGuiIO& io);

  void moveTo(float x, float y);  // window pixels, x right, y down (io.MousePos)
  void setButton(int button, bool down);
  void scroll(float notches);  // positive: the wheel turned away from the user
  void setKey(int key, bool down);
  void setModifiers(const KeyChord& chord, bool down);  // the chord's modifier keys (left ones)
  void type(const std::string& utf8);                   // text characters, as typed

  // True once the script has set any input: a window then takes its input from here.
  bool used() const { return used_; }
  float x() const { return x_; }
  float y() const { return y_; }

  // Writes the state into `io` for the next frame: after the platform's own NewFrame in a
  // window, so the script's input wins. The wheel and typed text are consumed (once each).
  void apply(ImGuiIO& io);

 private:
  static constexpr int kKeys = 512;    // io.KeysDown's size in 1.86
  float x_ = -FLT_MAX, y_ = -FLT_MAX;  // "no mouse" until the script moves it
  std::array<bool, 5> buttons_{};
  float wheel_ = 0.0f;
  // Per key: 0 left to the platform, 1 held by the script, -1 released by it (written once).
  std::array<signed char, kKeys> keys_{};
  std::string text_;
  bool used_ = false;
};

}  // namespace weft::editor
