#pragma once
// Chooses the off-screen backend: OSMesa when it is installed, else EGL surfaceless. Every
// headless context logs GL_VERSION and GL_RENDERER, so a run's output says what drew it.

#include <weft/render/RenderContext.h>

#include <iosfwd>
#include <memory>
#include <string>

namespace weft::render {

enum class HeadlessBackend { Auto, OsMesa, Egl };

// "auto", "osmesa" or "egl"; returns false for anything else.
bool parseHeadlessBackend(const std::string& text, HeadlessBackend& backend);

// Creates a current context with a width x height framebuffer. `log` (may be null) receives
// one line naming the backend, GL_VERSION and GL_RENDERER. Throws ContextError naming why
// each backend tried was unusable.
std::unique_ptr<RenderContext> createHeadlessContext(
    int width, int height, HeadlessBackend backend = HeadlessBackend::Auto,
    std::ostream* log = nullptr);

}  // namespace weft::render
