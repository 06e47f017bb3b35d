#include "AssimpReader.h"

#include "ChildProcess.h"

#include <weft/core/Error.h>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <vector>

namespace weft {
namespace {

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

TriangleMesh readInThisProcess(const std::string& path, bool joinCorners) {
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
      if (joinCorners) joinCoincidentCorners(part);
      mesh.append(part);
    }
  }
  if (mesh.vertexCount() == 0) throw InputError(path, "mesh", "the file holds no mesh");
  return mesh;
}

// The child's answer: 'M', vertex and triangle counts (two uint64), the coordinates (doubles),
// the corner indices (int32); or 'E' and the reason of the InputError it threw.
std::string encode(const TriangleMesh& mesh) {
  const std::uint64_t counts[2] = {static_cast<std::uint64_t>(mesh.vertexCount()),
                                   static_cast<std::uint64_t>(mesh.triangleCount())};
  std::string bytes = "M";
  bytes.append(reinterpret_cast<const char*>(counts), sizeof counts);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.vertices(v, k);
      bytes.append(reinterpret_cast<const char*>(&x), sizeof x);
    }
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = mesh.triangles(t, k);
      bytes.append(reinterpret_cast<const char*>(&i), sizeof i);
    }
  return bytes;
}

TriangleMesh decode(const std::string& path, const std::string& bytes) {
  const auto broken = [&] {
    return InputError(path, "mesh", "the assimp reader's answer is malformed");
  };
  std::uint64_t counts[2];
  if (bytes.size() < 1 + sizeof counts) throw broken();
  std::memcpy(counts, bytes.data() + 1, sizeof counts);
  const std::uint64_t limit = std::uint64_t{1} << 31;
  if (counts[0] >= limit || counts[1] >= limit ||
      bytes.size() !=
          1 + sizeof counts + counts[0] * 3 * sizeof(double) + counts[1] * 3 * sizeof(std::int32_t))
    throw broken();
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(counts[0]), 3);
  mesh.triangles.resize(static_cast<Eigen::Index>(counts[1]), 3);
  const char* p = bytes.data() + 1 + sizeof counts;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k, p += sizeof(double)) std::memcpy(&mesh.vertices(v, k), p, 8);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k, p += sizeof(std::int32_t)) {
      std::int32_t i;
      std::memcpy(&i, p, sizeof i);
      mesh.triangles(t, k) = i;
    }
  return mesh;
}

}  // namespace

TriangleMesh readWithAssimp(const std::string& path, bool joinCorners) {
  const ChildOutcome outcome = runInChildProcess(
      [&]() -> std::string {
        try {
          return encode(readInThisProcess(path, joinCorners));
        } catch (const InputError& e) {
          return "E" + e.reason();
        }
      },
      kAssimpTimeoutSeconds, kAssimpMemoryLimitBytes);
  switch (outcome.kind) {
    case ChildOutcome::Kind::Returned:
      if (!outcome.bytes.empty() && outcome.bytes[0] == 'E')
        throw InputError(path, "mesh", outcome.bytes.substr(1));
      if (outcome.bytes.empty() || outcome.bytes[0] != 'M')
        throw InputError(path, "mesh", "the assimp reader's answer is malformed");
      return decode(path, outcome.bytes);
    case ChildOutcome::Kind::Threw:
      throw InputError(path, "mesh", "cannot read mesh: " + outcome.bytes);
    case ChildOutcome::Kind::Died:
      throw InputError(path, "mesh",
                       "cannot read mesh: assimp's reader " + outcome.bytes +
                           " on this file (a malformed file, or a fault in assimp)");
    case ChildOutcome::Kind::TimedOut:
      break;
  }
  throw InputError(path, "mesh",
                   "cannot read mesh: assimp's reader did not finish within " +
                       std::to_string(static_cast<int>(kAssimpTimeoutSeconds)) + " s");
}

}  // namespace weft
