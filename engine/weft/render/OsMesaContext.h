#pragma once
// Off-screen rendering through Mesa's OSMesa into a client-memory buffer: no display, no GPU.
// The context is created directly with OSMesaCreateContextAttribs asking for a 3.3 core
// profile, and GL entry points come from OSMesaGetProcAddress. Destroy it before the process
// exits: Mesa tears its state down in exit handlers, and a context released after that (e.g.
// by a static object's destructor) crashes.

#include <weft/render/RenderContext.h>

#include <memory>

namespace weft::render {

class OsMesaContext final : public RenderContext {
 public:
  // Throws ContextError when libOSMesa is missing or refuses a 3.3 core context.
  OsMesaContext(int width, int height);
  ~OsMesaContext() override;

  void* getProcAddress(const char* name) override;
  unsigned framebuffer() const override { return 0; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void resize(int width, int height) override;
  std::string backendName() const override { return "osmesa"; }

 protected:
  void bind() override;
  void release() override;

 private:
  struct Library;
  std::unique_ptr<Library> lib_;
  void* context_ = nullptr;
  std::unique_ptr<unsigned char[]> buffer_;
  int width_ = 0, height_ = 0;
};

}  // namespace weft::render
