#include <weft/render/GpuMesh.h>

#include <cstdint>

namespace weft::render {

GpuMesh::GpuMesh(const GlFunctions& gl, std::vector<VertexAttribute> layout) : gl_(gl) {
  gl_.GenVertexArrays(1, &vao_);
  gl_.GenBuffers(1, &vertexBuffer_);
  gl_.GenBuffers(1, &indexBuffer_);
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffer_);
  gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer_);  // recorded in the VAO
  for (const VertexAttribute& a : layout) stride_ += a.components;
  std::uintptr_t offset = 0;
  for (const VertexAttribute& a : layout) {
    gl_.EnableVertexAttribArray(a.location);
    gl_.VertexAttribPointer(a.location, a.components, GL_FLOAT, GL_FALSE,
                            stride_ * GLsizei(sizeof(float)),
                            reinterpret_cast<const void*>(offset));
    offset += a.components * sizeof(float);
  }
  gl_.BindVertexArray(0);
}

GpuMesh::~GpuMesh() {
  gl_.DeleteBuffers(1, &indexBuffer_);
  gl_.DeleteBuffers(1, &vertexBuffer_);
  gl_.DeleteVertexArrays(1, &vao_);
}

void GpuMesh::upload(const std::vector<float>& vertices, const std::vector<unsigned>& indices) {
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffer_);
  gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(float)), vertices.data(),
                 GL_STREAM_DRAW);
  indexed_ = !indices.empty();
  if (indexed_)
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(unsigned)),
                   indices.data(), GL_STREAM_DRAW);
  gl_.BindVertexArray(0);
  count_ = indexed_ ? GLsizei(indices.size()) : GLsizei(vertices.size() / std::size_t(stride_));
}

void GpuMesh::draw(GLenum mode) const {
  if (count_ == 0) return;
  gl_.BindVertexArray(vao_);
  if (indexed_)
    gl_.DrawElements(mode, count_, GL_UNSIGNED_INT, nullptr);
  else
    gl_.DrawArrays(mode, 0, count_);
  gl_.BindVertexArray(0);
}

}  // namespace weft::render
