#include "ScriptedInput.h"

#include <imgui.h>

// Only the key-code constants: nothing here calls GLFW.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cctype>
#include <cstdlib>
#include <sstream>
#include <utility>

namespace weft::editor {
namespace {

int namedKey(const std::string& name) {
  if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_A + (std::tolower(static_cast<unsigned char>(name[0])) - 'a');
  if (name.size() == 1 && std::isdigit(static_cast<unsigned char>(name[0])))
    return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'f' && std::isdigit(static_cast<unsigned char>(name[1]))) {
    const int n = std::atoi(name.c_str() + 1);
    if (n >= 1 && n <= 12 && name == "f" + std::to_string(n)) return GLFW_KEY_F1 + n - 1;
  }
  static const std::pair<const char*, int> keys[] = {
      {"space", GLFW_KEY_SPACE},   {"enter", GLFW_KEY_ENTER},    {"escape", GLFW_KEY_ESCAPE},
      {"esc", GLFW_KEY_ESCAPE},    {"tab", GLFW_KEY_TAB},        {"backspace", GLFW_KEY_BACKSPACE},
      {"delete", GLFW_KEY_DELETE}, {"insert", GLFW_KEY_INSERT},  {"home", GLFW_KEY_HOME},
      {"end", GLFW_KEY_END},       {"pageup", GLFW_KEY_PAGE_UP}, {"pagedown", GLFW_KEY_PAGE_DOWN},
      {"left", GLFW_KEY_LEFT},     {"right", GLFW_KEY_RIGHT},    {"up", GLFW_KEY_UP},
      {"down", GLFW_KEY_DOWN}};
  for (const auto& [n, code] : keys)
    if (name == n) return code;
  return -1;
}

}  // namespace

bool parseMouseButton(const std::string& text, int& button) {
  if (text == "left")
    button = ImGuiMouseButton_Left;
  else if (text == "right")
    button = ImGuiMouseButton_Right;
  else if (text == "middle")
    button = ImGuiMouseButton_Middle;
  else
    return false;
  return true;
}

bool parseKeyChord(const std::string& text, KeyChord& chord) {
  KeyChord c;
  std::istringstream parts(text);
  std::string part;
  bool any = false;
  while (std::getline(parts, part, '+')) {
    for (char& ch : part) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    any = true;
    if (part == "ctrl" || part == "control")
      c.ctrl = true;
    else if (part == "shift")
      c.shift = true;
    else if (part == "alt")
      c.alt = true;
    else if (part == "super")
      c.super = true;
    else {
      const int key = namedKey(part);
      if (key < 0 || c.key >= 0) return false;  // unknown, or a second key
      c.key = key;
    }
  }
  if (!any || text.empty() || text.back() == '+') return false;
  chord = c;
  return true;
}

void ScriptedInput::installKeyMap(ImGuiIO& io) {
  const std::pair<ImGuiKey, int> map[] = {{ImGuiKey_Tab, GLFW_KEY_TAB},
                                          {ImGuiKey_LeftArrow, GLFW_KEY_LEFT},
                                          {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},
                                          {ImGuiKey_UpArrow, GLFW_KEY_UP},
                                          {ImGuiKey_DownArrow, GLFW_KEY_DOWN},
                                          {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
                                          {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN},
                                          {ImGuiKey_Home, GLFW_KEY_HOME},
                                          {ImGuiKey_End, GLFW_KEY_END},
                                          {ImGuiKey_Insert, GLFW_KEY_INSERT},
                                          {ImGuiKey_Delete, GLFW_KEY_DELETE},
                                          {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
                                          {ImGuiKey_Space, GLFW_KEY_SPACE},
                                          {ImGuiKey_Enter, GLFW_KEY_ENTER},
                                          {ImGuiKey_Escape, GLFW_KEY_ESCAPE},
                                          {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER},
                                          {ImGuiKey_A, GLFW_KEY_A},
                                          {ImGuiKey_C, GLFW_KEY_C},
                                          {ImGuiKey_V, GLFW_KEY_V},
                                          {ImGuiKey_X, GLFW_KEY_X},
                                          {ImGuiKey_Y, GLFW_KEY_Y},
                                          {ImGuiKey_Z, GLFW_KEY_Z}};
  for (const auto& [imguiKey, code] : map) io.KeyMap[imguiKey] = code;
}

void ScriptedInput::moveTo(float x, float y) {
  x_ = x, y_ = y;
  used_ = true;
}

void ScriptedInput::setButton(int button, bool down) {
  if (button < 0 || button >= int(buttons_.size())) return;
  buttons_[std::size_t(button)] = down;
  used_ = true;
}

void ScriptedInput::scroll(float notches) {
  wheel_ += notches;
  used_ = true;
}

void ScriptedInput::setKey(int key, bool down) {
  if (key < 0 || key >= kKeys) return;
  keys_[std::size_t(key)] = down ? 1 : -1;
  used_ = true;
}

void ScriptedInput::setModifiers(const KeyChord& chord, bool down) {
  if (chord.ctrl) setKey(GLFW_KEY_LEFT_CONTROL, down);
  if (chord.shift) setKey(GLFW_KEY_LEFT_SHIFT, down);
  if (chord.alt) setKey(GLFW_KEY_LEFT_ALT, down);
  if (chord.super) setKey(GLFW_KEY_LEFT_SUPER, down);
}

void ScriptedInput::type(const std::string& utf8) {
  text_ += utf8;
  used_ = true;
}

void ScriptedInput::apply(ImGuiIO& io) {
  io.MousePos = ImVec2(x_, y_);
  for (std::size_t b = 0; b < buttons_.size(); ++b) io.MouseDown[b] = buttons_[b];
  io.MouseWheel += wheel_;
  wheel_ = 0.0f;
  // A key the script released is left to the platform again (io keeps it up until a window's
  // key callback says otherwise); one it holds is written every frame.
  for (int k = 0; k < kKeys; ++k) {
    signed char& key = keys_[std::size_t(k)];
    if (key != 0) io.KeysDown[k] = key > 0;
    if (key < 0) key = 0;
  }
  // As ImGui's GLFW backend derives them: from either key of each pair.
  io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
  io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
  io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
  io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
  if (!text_.empty()) io.AddInputCharactersUTF8(text_.c_str());
  text_.clear();
}

}  // namespace weft::editor
