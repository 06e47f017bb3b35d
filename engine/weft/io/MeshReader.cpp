#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE  // the double-precision build of Debian's tinyobjloader
#endif
#include <weft/io/MeshReader.h>

#include "AssimpReader.h"
#include "GltfReader.h"
#include "PlyReader.h"

#include <weft/core/Error.h>

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace weft {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// tinyobjloader reads an unparsable or missing coordinate ("abc", "nan", "v 1 2") as 0, which
// would silently move a vertex; every `v` line is checked here first.
void checkObjVertexLines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    const auto comment = line.find('#');
    if (comment != std::string::npos) line.erase(comment);
    std::istringstream fields(line);
    std::string tag, token;
    if (!(fields >> tag) || tag != "v") continue;
    int count = 0;
    while (fields >> token) {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(value))
        throw InputError(path, "mesh",
                         "line " + std::to_string(lineNumber) + ": vertex coordinate '" + token +
                             "' is not a finite number");
      ++count;
    }
    if (count < 3)
      throw InputError(path, "mesh",
                       "line " + std::to_string(lineNumber) +
                           ": a vertex needs 3 coordinates, got " + std::to_string(count));
  }
}

TriangleMesh readObj(const std::string& path) {
  checkObjVertexLines(path);
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

}  // namespace

TriangleMesh readMesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "mesh", "no such file");
  const std::string ext = lowerExtension(path);
  TriangleMesh mesh = ext == ".obj"                     ? readObj(path)
                      : ext == ".ply"                   ? readPly(path)
                      : ext == ".gltf" || ext == ".glb" ? readGltf(path)
                                                        : readWithAssimp(path, ext == ".fbx");
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no vertices");
  if (mesh.triangleCount() == 0) throw InputError(path, "mesh", "the file holds no faces");
  return mesh;
}

}  // namespace weft
