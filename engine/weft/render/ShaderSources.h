#pragma once
// The GLSL files of shaders/, embedded into the binary at build time (cmake/EmbedShaders.cmake)
// so rendering never looks for files at run time.

#include <string>

namespace weft::render {

// The source of an embedded shader by its file name ("surface.vert"); throws GlError if absent.
const char* shaderSource(const std::string& fileName);

}  // namespace weft::render
