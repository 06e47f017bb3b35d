#include <weft/render/Image.h>

#include <weft/render/RenderError.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include <memory>

namespace weft::render {

void writePng(const std::string& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != std::size_t(image.width) * image.height * 3)
    throw ImageFileError(path + ": cannot write an empty or malformed image");
  if (!stbi_write_png(path.c_str(), image.width, image.height, 3, image.pixels.data(),
                      image.width * 3))
    throw ImageFileError(path + ": cannot write PNG");
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &channels, 3),
                                                 stbi_image_free);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw ImageFileError(path + ": cannot read PNG" +
                         (reason ? std::string(" (") + reason + ")" : ""));
  }
  Image image(w, h);
  std::copy(data.get(), data.get() + image.pixels.size(), image.pixels.begin());
  return image;
}

}  // namespace weft::render
