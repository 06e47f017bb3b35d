#include "MeshImport.h"

#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>
#include <weft/mesh/RigidTransform.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace weft::editor {
namespace {

namespace fs = std::filesystem;

// Sizes (largest extent, metres) outside these spans are almost surely not in metres: a
// garment from a glove to a tablecloth, an obstacle from a button to a room.
struct Span {
  double lo, hi;
};
constexpr Span kGarmentSpan{0.05, 5.0}, kObstacleSpan{0.01, 20.0};

std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

nlohmann::json vec(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

// True when some vertex belongs to two triangles: a mesh without one is a pile of loose
// triangles, which as cloth falls apart (a file exported with a vertex per triangle corner).
bool trianglesShareVertices(const TriangleMesh& mesh) {
  std::vector<char> used(std::size_t(mesh.vertexCount()), 0);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles(t, k);
      if (v < 0 || v >= mesh.vertexCount()) continue;  // the loader's checks report those
      if (used[std::size_t(v)]) return true;
      used[std::size_t(v)] = 1;
    }
  return false;
}

// Reads the file, fills the counts and boxes and the "mesh" object. Returns false (with
// result.error set) when the file cannot be used at all.
bool readAndPlace(const MeshImportOptions& o, const std::string& documentFile,
                  const std::string& directory, Span plausible, MeshImport& result,
                  nlohmann::json& mesh, TriangleMesh& read) {
  if (o.file.empty()) {
    result.error = "no file given";
    return false;
  }
  std::error_code ec;
  if (!fs::is_regular_file(o.file, ec)) {
    result.error = o.file + ": file not found";
    return false;
  }
  try {
    read = readMesh(o.file);
  } catch (const std::exception& e) {
    const auto* input = dynamic_cast<const InputError*>(&e);
    result.error =
        o.file + ": cannot read the mesh: " + (input ? input->reason() : std::string(e.what()));
    return false;
  }
  result.vertices = read.vertexCount();
  result.triangles = read.triangleCount();
  if (result.vertices == 0 || result.triangles == 0) {
    result.error =
        o.file + ": the file holds no triangles (" + std::to_string(result.vertices) + " vertices)";
    return false;
  }
  if (!read.vertices.allFinite()) {
    result.error = o.file + ": the mesh has non-finite vertex coordinates";
    return false;
  }
  result.fileLower = read.vertices.colwise().minCoeff().transpose();
  result.fileUpper = read.vertices.colwise().maxCoeff().transpose();
  const double extent = (result.fileUpper - result.fileLower).maxCoeff();

  double scale = o.scale;
  RigidTransform transform;
  transform.rotateDeg = o.rotateDeg;
  transform.translate = o.translate;
  if (o.fit) {
    if (!(o.fitSize > 0.0) || !std::isfinite(o.fitSize)) {
      result.error = "the fit size must be a positive length in metres";
      return false;
    }
    if (!(extent > 0.0)) {
      result.error = o.file + ": the mesh has no extent to fit (all vertices coincide)";
      return false;
    }
    scale = o.fitSize / extent;
    const Vec3 centre = 0.5 * (result.fileLower + result.fileUpper);
    transform.translate = o.translate - transform.rotation() * (scale * centre);
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    result.error = "the scale must be a positive number";
    return false;
  }
  NodeMatrix placed = read.vertices * scale;
  transform.applyTo(placed);
  result.lower = placed.colwise().minCoeff().transpose();
  result.upper = placed.colwise().maxCoeff().transpose();
  const double size = (result.upper - result.lower).maxCoeff();
  if (size > plausible.hi)
    result.warnings.push_back(
        "the mesh spans " + metres(size) +
        " m: the file is probably not in metres (pick its unit, set a scale, or fit it to a size)");
  else if (size < plausible.lo)
    result.warnings.push_back(
        "the mesh spans only " + metres(size) +
        " m: the file is probably not in metres (pick its unit, set a scale, or fit it to a size)");
  if (!o.fit && (size > plausible.hi || size < plausible.lo))
    result.units = plausibleUnits(extent, plausible.lo, plausible.hi);

  mesh = {{"file", documentRelativePath(o.file, documentFile, directory)}};
  if (scale != 1.0) mesh["scale"] = scale;
  if (!transform.rotateDeg.isZero() || !transform.translate.isZero())
    mesh["transform"] = {{"rotate_deg", vec(transform.rotateDeg)},
                         {"translate", vec(transform.translate)}};
  return true;
}

// Validates `entry` alone through the loader, in a minimal scene; the loader's message names the
// file and what is wrong, without the minimal scene's JSON path.
void validate(const nlohmann::json& minimal, const std::string& documentFile,
              const std::string& directory, MeshImport& result) {
  try {
    const Scene scene =
        parseScene(minimal, documentFile.empty() ? "untitled" : documentFile, directory);
    for (const std::string& w : scene.warnings) {
      // "<file>: <path>: what" -> "what" (the path is the minimal scene's, not the document's)
      const std::size_t cut = w.find(": ", w.find(": ") + 2);
      result.warnings.push_back(cut == std::string::npos ? w : w.substr(cut + 2));
    }
  } catch (const InputError& e) {
    result.error = e.reason();
  } catch (const std::exception& e) {
    result.error = e.what();
  }
}

}  // namespace

std::string documentRelativePath(const std::string& file, const std::string& documentFile,
                                 const std::string& documentDirectory) {
  std::error_code ec;
  const fs::path absolute = fs::weakly_canonical(fs::absolute(file), ec);
  if (!documentFile.empty()) {
    const fs::path base = fs::weakly_canonical(fs::absolute(documentDirectory), ec);
    const fs::path relative = absolute.lexically_relative(base);
    if (!relative.empty() && *relative.begin() != "..") return relative.generic_string();
  }
  return absolute.generic_string();
}

nlohmann::json defaultGarmentMaterial() {
  return {{"density", 0.2}, {"stretch", 1000.0}, {"bend", 1e-4}};
}

std::vector<LengthUnit> plausibleUnits(double fileExtent, double lo, double hi) {
  static const LengthUnit kUnits[] = {{"metres", 1.0},
                                      {"centimetres", 0.01},
                                      {"millimetres", 0.001},
                                      {"inches", 0.0254},
                                      {"feet", 0.3048}};
  std::vector<LengthUnit> out;
  if (!(fileExtent > 0.0) || !std::isfinite(fileExtent)) return out;
  for (const LengthUnit& u : kUnits) {
    const double size = fileExtent * u.metres;
    if (size >= lo && size <= hi) out.push_back(u);
  }
  const double middle = 0.5 * std::log(lo * hi);
  std::stable_sort(out.begin(), out.end(), [&](const LengthUnit& a, const LengthUnit& b) {
    return std::abs(std::log(fileExtent * a.metres) - middle) <
           std::abs(std::log(fileExtent * b.metres) - middle);
  });
  return out;
}

MeshImport prepareGarment(const MeshImportOptions& o, const std::string& documentFile,
                          const std::string& documentDirectory) {
  MeshImport result;
  nlohmann::json mesh;
  TriangleMesh read;
  if (!readAndPlace(o, documentFile, documentDirectory, kGarmentSpan, result, mesh, read))
    return result;
  if (result.triangles > 1 && !trianglesShareVertices(read))
    result.warnings.push_back("no two triangles share a vertex: as cloth the " +
                              std::to_string(result.triangles) +
                              " triangles fall apart (weld the file's vertices first)");
  if (o.repair) mesh["repair"] = true;
  result.entry = {{"mesh", mesh}, {"material", defaultGarmentMaterial()}};
  const nlohmann::json minimal = {{"time", {{"dt", 0.01}, {"steps", 1}}},
                                  {"cloths", {result.entry}}};
  validate(minimal, documentFile, documentDirectory, result);
  if (!result.ok()) result.error = o.file + ": " + result.error;
  return result;
}

MeshImport prepareMeshObstacle(const MeshImportOptions& o, const std::string& documentFile,
                               const std::string& documentDirectory) {
  MeshImport result;
  nlohmann::json mesh;
  TriangleMesh read;
  if (!readAndPlace(o, documentFile, documentDirectory, kObstacleSpan, result, mesh, read))
    return result;
  if (!o.smoothNormals) mesh["smooth_normals"] = false;
  result.entry = {{"mesh", mesh}, {"friction", 0.3}};
  const nlohmann::json minimal = {
      {"time", {{"dt", 0.01}, {"steps", 1}}},
      {"cloths",
       {{{"mesh", {{"grid", {{"size", {1.0, 1.0}}, {"resolution", {1, 1}}}}}},
         {"material", defaultGarmentMaterial()}}}},
      {"obstacles", {result.entry}}};
  validate(minimal, documentFile, documentDirectory, result);
  if (!result.ok()) result.error = o.file + ": " + result.error;
  return result;
}

}  // namespace weft::editor
