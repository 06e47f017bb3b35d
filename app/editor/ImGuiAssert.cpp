#include "ImGuiAssert.h"

#include <cstring>

namespace weft::editor {

ImGuiAssertion::ImGuiAssertion(const char* expression, const char* file, unsigned line)
    : std::logic_error(std::string(file) + ":" + std::to_string(line) +
                       ": Dear ImGui assertion failed: " + expression),
      expression_(expression),
      file_(file),
      line_(line) {}

void imguiAssertFailed(const char* expression, const char* file, unsigned line) {
  throw ImGuiAssertion(expression, file, line);
}

bool isImGuiSource(const char* file) {
  if (!file) return false;
  const char* slash = std::strrchr(file, '/');
  const char* base = slash ? slash + 1 : file;
  return std::strncmp(base, "imgui", 5) == 0;
}

}  // namespace weft::editor

// The prebuilt libimgui.a's assert() calls, redirected here by the linker (--wrap=__assert_fail,
// set on weft_editor_ui for whatever links it). glibc declares __assert_fail noreturn: both
// branches keep that promise, one by throwing, the other by calling glibc's own.
extern "C" {
[[noreturn]] void __real___assert_fail(const char* assertion, const char* file, unsigned line,
                                       const char* function);

[[noreturn]] void __wrap___assert_fail(const char* assertion, const char* file, unsigned line,
                                       const char* function) {
  if (weft::editor::isImGuiSource(file)) weft::editor::imguiAssertFailed(assertion, file, line);
  __real___assert_fail(assertion, file, line, function);
}
}
