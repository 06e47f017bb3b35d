#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE  // the double-precision build of Debian's tinyobjloader
#endif
#include <weft/io/MeshReader.h>

#include "GltfReader.h"
#include "PlyReader.h"

#include <weft/core/Error.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
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

// assimp's FBX reader gives every triangle corner its own vertex (it unrolls the file's
// polygon-vertex list instead of indexing the shared control points), so an FBX cloth would be
// loose triangles. Corners at bit-identical positions are joined again, in order of first
// appearance: the file's own vertex order cannot be recovered through assimp, and two control
// points at exactly one position (a cut left open in the file) become one vertex.
void joinCoincidentCorners(TriangleMesh& part) {
  std::map<std::array<double, 3>, int> index;
  std::vector<int> joined(static_cast<std::size_t>(part.vertexCount()));
  NodeMatrix kept(part.vertexCount(), 3);
  int count = 0;
  for (int v = 0; v < part.vertexCount(); ++v) {
    const std::array<double, 3> key{part.vertices(v, 0), part.vertices(v, 1), part.vertices(v, 2)};
    const auto [it, inserted] = index.emplace(key, count);
    if (inserted) kept.row(count++) = part.vertices.row(v);
    joined[static_cast<std::size_t>(v)] = it->second;
  }
  // assimp numbers the corners triangle by triangle, so this is the order of first use.
  part.vertices = kept.topRows(count);
  for (Eigen::Index t = 0; t < part.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      part.triangles(t, k) = joined[static_cast<std::size_t>(part.triangles(t, k))];
}

// Where each of the file's meshes sits: the global transform (the product of the node
// transforms from the root down) of every node that references it, in depth-first order.
void collectPlacements(const aiNode* node, const aiMatrix4x4& parent,
                       std::vector<std::vector<aiMatrix4x4>>& placements) {
  const aiMatrix4x4 global = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i)
    if (node->mMeshes[i] < placements.size()) placements[node->mMeshes[i]].push_back(global);
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    collectPlacements(node->mChildren[c], global, placements);
}

TriangleMesh readWithAssimp(const std::string& path) {
  const bool fbx = lowerExtension(path) == ".fbx";
  Assimp::Importer importer;
  // No post-processing that welds, splits or reorders vertices.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (!scene || !scene->mRootNode)
    throw InputError(path, "mesh", std::string("cannot read mesh: ") + importer.GetErrorString());
  // The file's node transforms place its meshes (a glTF or FBX exporter puts an object's
  // translation, rotation and scale there, not into the vertices): each mesh is read where its
  // node puts it, once per node that references it, in mesh order (so a file without transforms
  // reads exactly as its vertex lists are stored); a mesh no node references stays where it is.
  std::vector<std::vector<aiMatrix4x4>> placements(scene->mNumMeshes);
  collectPlacements(scene->mRootNode, aiMatrix4x4(), placements);
  TriangleMesh mesh;
  mesh.vertices.resize(0, 3);
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const aiMesh* in = scene->mMeshes[k];
    if (placements[k].empty()) placements[k].push_back(aiMatrix4x4());
    for (const aiMatrix4x4& placement : placements[k]) {
      TriangleMesh part;
      part.vertices.resize(in->mNumVertices, 3);
      for (unsigned i = 0; i < in->mNumVertices; ++i) {
        const aiVector3D p = placement * in->mVertices[i];
        part.vertices.row(i) << p.x, p.y, p.z;
      }
      // A mirroring placement (negative determinant) would turn the surface inside out: the
      // corners are listed the other way round to keep its outward side.
      const bool mirrored = placement.Determinant() < 0.0f;
      std::vector<int> tri;
      for (unsigned f = 0; f < in->mNumFaces; ++f) {
        const aiFace& face = in->mFaces[f];
        for (unsigned j = 1; j + 1 < face.mNumIndices; ++j) {
          tri.push_back(static_cast<int>(face.mIndices[0]));
          tri.push_back(static_cast<int>(face.mIndices[mirrored ? j + 1 : j]));
          tri.push_back(static_cast<int>(face.mIndices[mirrored ? j : j + 1]));
        }
      }
      part.triangles = Eigen::Map<TriangleIndices>(tri.data(), static_cast<int>(tri.size() / 3), 3);
      if (fbx) joinCoincidentCorners(part);
      mesh.append(part);
    }
  }
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no mesh");
  return mesh;
}

}  // namespace

TriangleMesh readMesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "mesh", "no such file");
  const std::string ext = lowerExtension(path);
  TriangleMesh mesh = ext == ".obj"                     ? readObj(path)
                      : ext == ".ply"                   ? readPly(path)
                      : ext == ".gltf" || ext == ".glb" ? readGltf(path)
                                                        : readWithAssimp(path);
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no vertices");
  if (mesh.triangleCount() == 0) throw InputError(path, "mesh", "the file holds no faces");
  return mesh;
}

}  // namespace weft
