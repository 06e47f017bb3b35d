#include <weft/render/OsMesaContext.h>

#include <weft/render/RenderError.h>
#include <weft/render/SharedLibrary.h>

#include <GL/osmesa.h>

namespace weft::render {

struct OsMesaContext::Library {
  SharedLibrary so{
      libraryNames("WEFT_OSMESA_LIBRARY", {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"})};
  decltype(&OSMesaCreateContextAttribs) createContextAttribs =
      so.function<decltype(&OSMesaCreateContextAttribs)>("OSMesaCreateContextAttribs");
  decltype(&OSMesaDestroyContext) destroyContext =
      so.function<decltype(&OSMesaDestroyContext)>("OSMesaDestroyContext");
  decltype(&OSMesaMakeCurrent) makeCurrent =
      so.function<decltype(&OSMesaMakeCurrent)>("OSMesaMakeCurrent");
  decltype(&OSMesaGetProcAddress) getProcAddress =
      so.function<decltype(&OSMesaGetProcAddress)>("OSMesaGetProcAddress");
};

OsMesaContext::OsMesaContext(int width, int height) {
  try {
    lib_ = std::make_unique<Library>();
  } catch (const ContextError& e) {
    throw ContextError(std::string("OSMesa is not available: ") + e.what());
  }
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            0,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  context_ = lib_->createContextAttribs(attributes, nullptr);
  if (!context_)
    throw ContextError("OSMesa (" + lib_->so.name() +
                       ") could not create an OpenGL 3.3 core profile context");
  resize(width, height);
  keepLoadedLibrariesForSanitizers();
}

OsMesaContext::~OsMesaContext() {
  releaseIfCurrent();
  if (context_) lib_->destroyContext(static_cast<OSMesaContext>(context_));
}

void OsMesaContext::release() {
  lib_->makeCurrent(nullptr, nullptr, 0, 0, 0);
}

void OsMesaContext::bind() {
  if (!lib_->makeCurrent(static_cast<OSMesaContext>(context_), buffer_.get(), GL_UNSIGNED_BYTE,
                         width_, height_))
    throw ContextError("OSMesaMakeCurrent failed for a " + std::to_string(width_) + "x" +
                       std::to_string(height_) + " buffer");
}

void* OsMesaContext::getProcAddress(const char* name) {
  return reinterpret_cast<void*>(lib_->getProcAddress(name));
}

void OsMesaContext::resize(int width, int height) {
  if (width < 1 || height < 1) throw ContextError("OSMesa: framebuffer size must be positive");
  if (width == width_ && height == height_ && buffer_) return;
  // OSMesa renders into this client buffer; making the context current again attaches it.
  buffer_.reset(new unsigned char[static_cast<std::size_t>(width) * height * 4]);
  width_ = width;
  height_ = height;
  makeCurrent();
}

}  // namespace weft::render
