#pragma once
// One vertex array on the GPU: interleaved float attributes, optional triangle or line
// indices, re-uploaded whenever a frame changes it.

#include <weft/render/GlFunctions.h>

#include <vector>

namespace weft::render {

struct VertexAttribute {
  GLuint location;  // the shader's layout(location = ...)
  GLint components;
};

class GpuMesh {
 public:
  GpuMesh(const GlFunctions& gl, std::vector<VertexAttribute> layout);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  // `vertices` interleaves the layout's attributes; without `indices` vertices draw in order.
  void upload(const std::vector<float>& vertices, const std::vector<unsigned>& indices = {});
  void draw(GLenum mode) const;
  bool empty() const { return count_ == 0; }

 private:
  const GlFunctions& gl_;
  GLuint vao_ = 0, vertexBuffer_ = 0, indexBuffer_ = 0;
  GLint stride_ = 0;  // floats per vertex
  GLsizei count_ = 0;
  bool indexed_ = false;
};

}  // namespace weft::render
