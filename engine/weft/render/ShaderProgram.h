#pragma once
// A linked GLSL program built from embedded shader files, with uniform setters.

#include <weft/render/GlFunctions.h>

#include <Eigen/Core>

#include <string>
#include <unordered_map>
#include <vector>

namespace weft::render {

class ShaderProgram {
 public:
  // `files` are embedded shader names; the stage follows the extension (.vert, .geom, .frag).
  // Throws GlError with the compiler's or linker's log.
  ShaderProgram(const GlFunctions& gl, const std::vector<std::string>& files);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const;
  // Uniforms the compiler removed as unused are silently skipped (location -1), as GL does.
  void set(const char* name, int value);
  void set(const char* name, bool value) { set(name, value ? 1 : 0); }
  void set(const char* name, float value);
  void set(const char* name, float x, float y);
  void set(const char* name, const Eigen::Vector3f& value);
  void set(const char* name, const Eigen::Matrix4f& value);

 private:
  GLint location(const char* name);
  const GlFunctions& gl_;
  GLuint program_ = 0;
  std::string name_;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace weft::render
