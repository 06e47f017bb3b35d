#pragma once
// Draws a RenderScene with OpenGL 3.3 core into whatever framebuffer its RenderContext
// provides (a window, an OSMesa buffer, an EGL FBO), and reads the result back.

#include <weft/render/Camera.h>
#include <weft/render/Image.h>
#include <weft/render/RenderContext.h>
#include <weft/render/RenderScene.h>
#include <weft/render/RenderStyle.h>

#include <memory>
#include <string>

namespace weft::render {

struct RendererOptions {
  // Check glGetError after every draw path, so a GlError names the path that failed. Off, the
  // check runs once per frame (GL errors are always exceptions). On by default in debug
  // builds and when WEFT_GL_DEBUG=1.
  bool checkEveryDrawPath = defaultCheckEveryDrawPath();
  static bool defaultCheckEveryDrawPath();
};

class Renderer {
 public:
  // Compiles the shaders in `context` (made current). Throws ContextError or GlError.
  explicit Renderer(RenderContext& context, RendererOptions options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Draws one frame at the context's framebuffer size. Throws std::invalid_argument for an
  // inconsistent scene (e.g. a per-vertex array of the wrong length) and GlError on GL errors.
  void render(const RenderScene& scene, const Camera& camera, const RenderStyle& style = {});
  // The framebuffer as an RGB image, top row first.
  Image readPixels() const;
  Image renderImage(const RenderScene& scene, const Camera& camera, const RenderStyle& style = {}) {
    render(scene, camera, style);
    return readPixels();
  }

  RenderContext& context() const { return context_; }
  const std::string& glVersion() const { return version_; }
  const std::string& glRenderer() const { return renderer_; }

 private:
  struct Resources;
  struct Frame;
  void checkpoint(const char* where) const;
  void drawGround(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  // `inFront`: the second, translucent pass over the cloth (RenderStyle::obstaclesInFront).
  void drawObstacles(const RenderScene& scene, const RenderStyle& style, const Frame& f,
                     bool inFront);
  void drawCloth(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawWireframe(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawCurves(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawArrows(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawPoints(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawGhosts(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void drawLegend(const RenderScene& scene, const RenderStyle& style, const Frame& f);
  void useSurfaceProgram(const Frame& f, const Rgb& front, const Rgb& back, float opacity);
  void drawLines(const std::vector<float>& vertices, float widthPixels, const Frame& f);

  RenderContext& context_;
  RendererOptions options_;
  std::unique_ptr<Resources> r_;
  std::string version_, renderer_;
};

}  // namespace weft::render
