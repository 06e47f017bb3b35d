#include <weft/render/ShaderProgram.h>

#include <weft/render/RenderError.h>
#include <weft/render/ShaderSources.h>

namespace weft::render {
namespace {

GLenum stageOf(const std::string& file) {
  auto endsWith = [&](const char* ext) {
    const std::string e(ext);
    return file.size() > e.size() && file.compare(file.size() - e.size(), e.size(), e) == 0;
  };
  if (endsWith(".vert")) return GL_VERTEX_SHADER;
  if (endsWith(".geom")) return GL_GEOMETRY_SHADER;
  if (endsWith(".frag")) return GL_FRAGMENT_SHADER;
  throw GlError(file + ": unknown shader stage (expected .vert, .geom or .frag)");
}

}  // namespace

ShaderProgram::ShaderProgram(const GlFunctions& gl, const std::vector<std::string>& files)
    : gl_(gl) {
  for (const std::string& f : files) name_ += (name_.empty() ? "" : "+") + f;
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) gl_.DeleteShader(s);
  };
  program_ = gl_.CreateProgram();
  for (const std::string& file : files) {
    const GLuint shader = gl_.CreateShader(stageOf(file));
    shaders.push_back(shader);
    const char* source = shaderSource(file);
    gl_.ShaderSource(shader, 1, &source, nullptr);
    gl_.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {0};
      gl_.GetShaderInfoLog(shader, sizeof log, nullptr, log);
      cleanup();
      gl_.DeleteProgram(program_);
      throw GlError("shader " + file + " does not compile: " + log);
    }
    gl_.AttachShader(program_, shader);
  }
  gl_.LinkProgram(program_);
  cleanup();  // the program keeps what it needs once linked
  GLint ok = GL_FALSE;
  gl_.GetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {0};
    gl_.GetProgramInfoLog(program_, sizeof log, nullptr, log);
    gl_.DeleteProgram(program_);
    throw GlError("shader program " + name_ + " does not link: " + log);
  }
  gl_.check(("building shader program " + name_).c_str());
}

ShaderProgram::~ShaderProgram() {
  gl_.DeleteProgram(program_);
}

void ShaderProgram::use() const {
  gl_.UseProgram(program_);
}

GLint ShaderProgram::location(const char* name) {
  auto it = locations_.find(name);
  if (it == locations_.end())
    it = locations_.emplace(name, gl_.GetUniformLocation(program_, name)).first;
  return it->second;
}

void ShaderProgram::set(const char* name, int value) {
  gl_.Uniform1i(location(name), value);
}
void ShaderProgram::set(const char* name, float value) {
  gl_.Uniform1f(location(name), value);
}
void ShaderProgram::set(const char* name, float x, float y) {
  gl_.Uniform2f(location(name), x, y);
}
void ShaderProgram::set(const char* name, const Eigen::Vector3f& v) {
  gl_.Uniform3f(location(name), v.x(), v.y(), v.z());
}
void ShaderProgram::set(const char* name, const Eigen::Matrix4f& m) {
  gl_.UniformMatrix4fv(location(name), 1, GL_FALSE, m.data());  // Eigen is column-major, as GL
}

}  // namespace weft::render
