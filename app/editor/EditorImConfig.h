#pragma once
// Dear ImGui's compile-time configuration for the editor (IMGUI_USER_CONFIG, included by
// imgui.h before anything else): IM_ASSERT checks in every build type and throws instead of
// aborting (ImGuiAssert.h says why). Nothing here changes a type's layout, so code built
// against the plain imconfig.h (Debian's libimgui.a) links with it.

namespace weft::editor {
[[noreturn]] void imguiAssertFailed(const char* expression, const char* file, unsigned line);
}

#define IM_ASSERT(_EXPR) \
  ((_EXPR) ? (void)0 : ::weft::editor::imguiAssertFailed(#_EXPR, __FILE__, __LINE__))
