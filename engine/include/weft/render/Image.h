#pragma once
// An 8-bit RGB image, rows from top to bottom, and its PNG files (through stb).

#include <cstdint>
#include <string>
#include <vector>

namespace weft::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, row-major, first row at the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3, 0) {}
  std::uint8_t* at(int x, int y) { return &pixels[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* at(int x, int y) const {
    return &pixels[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

// Throws ImageFileError when the file cannot be written or read.
void writePng(const std::string& path, const Image& image);
Image readPng(const std::string& path);  // any PNG, converted to RGB

}  // namespace weft::render
