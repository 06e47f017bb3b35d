#pragma once
// Failures of the renderer. They are not input errors of a scene: a missing OpenGL
// implementation or a GL error is an environment or programming problem, reported as such.

#include <stdexcept>
#include <string>

namespace weft::render {

// No usable OpenGL: a backend library is missing, or a context could not be created.
class ContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A GL call failed (glGetError, shader compilation, incomplete framebuffer).
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An image file that cannot be written or read.
class ImageFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace weft::render
