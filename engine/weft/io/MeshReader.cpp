#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE  // the double-precision build of Debian's tinyobjloader
#endif
#include <weft/io/MeshReader.h>

#include <weft/core/Error.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vector>

namespace weft {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

TriangleMesh readObj(const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // we fan-triangulate ourselves so the vertex set is untouched
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    std::string msg = reader.Error();
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
    throw InputError(path, "mesh", "cannot read OBJ: " + (msg.empty() ? "unknown error" : msg));
  }
  const auto& attrib = reader.GetAttrib();
  TriangleMesh mesh;
  const int m = static_cast<int>(attrib.vertices.size() / 3);
  mesh.vertices.resize(m, 3);
  for (int i = 0; i < m; ++i)
    mesh.vertices.row(i) << attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
        attrib.vertices[3 * i + 2];
  std::vector<int> tri;
  for (const auto& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (unsigned char arity : shape.mesh.num_face_vertices) {
      for (int k = 1; k + 1 < arity; ++k) {
        tri.push_back(shape.mesh.indices[offset].vertex_index);
        tri.push_back(shape.mesh.indices[offset + k].vertex_index);
        tri.push_back(shape.mesh.indices[offset + k + 1].vertex_index);
      }
      offset += arity;
    }
  }
  mesh.triangles = Eigen::Map<TriangleIndices>(tri.data(), static_cast<int>(tri.size() / 3), 3);
  return mesh;
}

TriangleMesh readWithAssimp(const std::string& path) {
  Assimp::Importer importer;
  // No post-processing that welds, splits or reorders vertices.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (!scene || !scene->mRootNode)
    throw InputError(path, "mesh", std::string("cannot read mesh: ") + importer.GetErrorString());
  TriangleMesh mesh;
  mesh.vertices.resize(0, 3);
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const aiMesh* in = scene->mMeshes[k];
    TriangleMesh part;
    part.vertices.resize(in->mNumVertices, 3);
    for (unsigned i = 0; i < in->mNumVertices; ++i)
      part.vertices.row(i) << in->mVertices[i].x, in->mVertices[i].y, in->mVertices[i].z;
    std::vector<int> tri;
    for (unsigned f = 0; f < in->mNumFaces; ++f) {
      const aiFace& face = in->mFaces[f];
      for (unsigned j = 1; j + 1 < face.mNumIndices; ++j) {
        tri.push_back(static_cast<int>(face.mIndices[0]));
        tri.push_back(static_cast<int>(face.mIndices[j]));
        tri.push_back(static_cast<int>(face.mIndices[j + 1]));
      }
    }
    part.triangles = Eigen::Map<TriangleIndices>(tri.data(), static_cast<int>(tri.size() / 3), 3);
    mesh.append(part);
  }
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no mesh");
  return mesh;
}

}  // namespace

TriangleMesh readMesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path, "mesh", "no such file");
  TriangleMesh mesh = lowerExtension(path) == ".obj" ? readObj(path) : readWithAssimp(path);
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no vertices");
  if (mesh.triangleCount() == 0) throw InputError(path, "mesh", "the file holds no faces");
  return mesh;
}

}  // namespace weft
