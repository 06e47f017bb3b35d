#pragma once
// Dear ImGui's assertions, made recoverable. ImGui checks its callers' contract with IM_ASSERT
// (an item edited while another is active, unbalanced Begin/End...). By default that is
// assert(): in a Release build of ours it still aborts, because Debian's libimgui.a is compiled
// with assertions on, and the user's unsaved work is lost. Instead, a failed ImGui assertion
// throws ImGuiAssertion; EditorApp::frame catches it, logs it with its context (file, line,
// expression, what the UI was doing), ends the frame through ImGui's own error recovery and
// carries on.
//
// Two routes lead here:
//   - ImGui code compiled in our targets (the inline functions of imgui.h, the OpenGL3 backend)
//     uses IM_ASSERT as EditorImConfig.h defines it (IMGUI_USER_CONFIG), in Release too;
//   - the prebuilt libimgui.a calls glibc's __assert_fail: the editor's targets link with
//     --wrap=__assert_fail, and __wrap___assert_fail (ImGuiAssert.cpp) turns the failures whose
//     file is one of ImGui's sources into ImGuiAssertion. Any other assertion aborts as before.

#include <stdexcept>
#include <string>

namespace weft::editor {

class ImGuiAssertion : public std::logic_error {
 public:
  ImGuiAssertion(const char* expression, const char* file, unsigned line);
  const std::string& expression() const { return expression_; }
  const std::string& file() const { return file_; }
  unsigned line() const { return line_; }

 private:
  std::string expression_, file_;
  unsigned line_;
};

// Throws ImGuiAssertion (never returns). Called by IM_ASSERT and by the __assert_fail wrapper.
[[noreturn]] void imguiAssertFailed(const char* expression, const char* file, unsigned line);

// True when `file` (as __FILE__ spells it) is one of Dear ImGui's sources or headers: its base
// name starts with "imgui".
bool isImGuiSource(const char* file);

}  // namespace weft::editor
