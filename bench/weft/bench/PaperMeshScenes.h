#pragma once
// The garment tasks on the DiffCloth release's own garment meshes (`weft bench applications
// --paper-meshes`; ../shared/meshes/README.md): the task scene with its cloth's mesh replaced by
// the paper's, placed by a fixed rotation (the paper's frame differs from the task's for the Sock
// and the Flag), a uniform scale mapping the largest bounding-box extent onto the task garment's
// largest extent, and a translation putting the two bounding-box centres together. Every vertex
// index list of the scene (every "vertices" key: attachments, forces, loss vertices, keypoints,
// hemline) is remapped to the nearest vertices of the new mesh, and a handle's path after its
// first knot moves with its vertices (shiftHandlePaths); recorded-motion targets
// (trajectory loss) are re-recorded in-process from the hidden values the scene's description
// names (`weft simulate ... --set P=V ...`, what weft_task_targets runs at build time), and a
// final-pose target that is the rest shape translated (the Hat) is rebuilt as the new rest shape
// translated so that its bounding box's top centre lands where the task's own target puts its
// garment's. The meshes are read where they lie, never copied.
//
// Header-only: used by ApplicationsBench.cpp and by the tests.

#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>
#include <weft/io/Npy.h>
#include <weft/mesh/RigidTransform.h>
#include <weft/physics/Simulator.h>
#include <weft/record/Trajectory.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace weft::bench::paper {

struct PaperMesh {
  const char* task;     // the applications task it replaces the garment of
  const char* file;     // below the paper-mesh folder
  double rotateDeg[3];  // applied before the fit (scene transform convention: X, then Y, then Z)
  const char* why;
};

// The Dress task is a skirt whose waist ring turns and whose hem is measured: skirt1252.obj (a
// skirt with a waist and a hem loop) fits it; dress-handsup-drape.obj is a whole dress with a
// bodice. The Sock's cuff faces +Y in the paper's frame: -90 deg about X turns it to face -Z, the
// foot it is pulled onto, as the task's own tube does. The Flag's capture frame is tilted: the
// rotation puts its straighter short side (the pole) along +Y and its long sides along +X.
inline const std::vector<PaperMesh>& paperMeshes() {
  static const std::vector<PaperMesh> table = {
      {"tshirt", "tshirt1000-tri.obj", {0, 0, 0}, "upright as given"},
      {"hat", "agenthat2-579.obj", {0, 0, 0}, "upright as given"},
      {"sock", "sock1055-2081.obj", {-90, 0, 0}, "cuff turned from +Y to face -Z (the foot)"},
      {"dress", "skirt1252.obj", {0, 0, 0}, "upright as given; a skirt, as the task's"},
      {"flag",
       "flag001.obj",
       {23.983, -34.507, 59.247},
       "pole (straighter short side) along +Y, fly along +X"},
  };
  return table;
}

inline const PaperMesh* paperMeshFor(const std::string& task) {
  for (const PaperMesh& m : paperMeshes())
    if (task == m.task) return &m;
  return nullptr;
}

// The default folder: ../shared/meshes/diffcloth relative to the repository (source tree).
inline std::string defaultPaperMeshDirectory(const std::string& repository) {
  return (std::filesystem::path(repository) / ".." / "shared" / "meshes" / "diffcloth")
      .lexically_normal()
      .string();
}

// Empty when every mesh of the table is readable in `dir`, else what is missing.
inline std::string missingPaperMeshes(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    return "no such folder (the DiffCloth garment meshes, see ../shared/meshes/README.md)";
  std::string missing;
  for (const PaperMesh& m : paperMeshes())
    if (!fs::is_regular_file(fs::path(dir) / m.file, ec))
      missing += (missing.empty() ? "" : ", ") + std::string(m.file);
  return missing.empty() ? "" : "missing " + missing;
}

struct IndexRemap {
  std::string path;          // JSON path of the list
  int count = 0;             // entries after remapping
  int original = 0;          // entries before
  double maxDistance = 0.0;  // m, from an original vertex's rest position to its new vertex
};

// A handle whose path was moved with its vertices (shiftHandlePaths).
struct HandleShift {
  std::string path;       // JSON path of the attachment
  double distance = 0.0;  // m, how far its knots after the first moved
};

struct PaperScene {
  nlohmann::json document;  // the scene, ready for parseScene
  std::string meshFile;     // absolute
  double scale = 1.0;
  Vec3 rotateDeg = Vec3::Zero(), translate = Vec3::Zero();
  int vertices = 0, originalVertices = 0;
  std::vector<IndexRemap> remaps;
  std::vector<HandleShift> handleShifts;
  std::string target;  // the target file written, or "" when the task needs none
};

namespace detail {

inline void bounds(const NodeMatrix& x, Vec3& lo, Vec3& hi) {
  lo = x.colwise().minCoeff().transpose();
  hi = x.colwise().maxCoeff().transpose();
}

inline int nearest(const NodeMatrix& x, const Vec3& p) {
  int best = 0;
  double bestD = std::numeric_limits<double>::infinity();
  for (int i = 0; i < x.rows(); ++i) {
    const double d = (x.row(i).transpose() - p).squaredNorm();
    if (d < bestD) bestD = d, best = i;
  }
  return best;
}

// Remaps every array of integers under a key "vertices" (the scene format's only index lists).
// Lists paired with "positions" (keypoints) keep their length; the others drop repeats.
inline void remapIndexLists(nlohmann::json& node, const std::string& path, const NodeMatrix& from,
                            const NodeMatrix& to, std::vector<IndexRemap>& out) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it) {
      const std::string child = path.empty() ? it.key() : path + "." + it.key();
      if (it.key() == "vertices" && it.value().is_array() && !it.value().empty() &&
          std::all_of(it.value().begin(), it.value().end(),
                      [](const nlohmann::json& v) { return v.is_number_integer(); })) {
        const bool paired = node.contains("positions");
        IndexRemap r;
        r.path = child;
        r.original = static_cast<int>(it.value().size());
        std::vector<int> mapped;
        for (const nlohmann::json& v : it.value()) {
          const int i = v.get<int>();
          if (i < 0 || i >= from.rows())
            throw InputError(path, child, "vertex index " + std::to_string(i) + " out of range");
          const Vec3 p = from.row(i).transpose();
          const int j = nearest(to, p);
          r.maxDistance = std::max(r.maxDistance, (to.row(j).transpose() - p).norm());
          if (paired || std::find(mapped.begin(), mapped.end(), j) == mapped.end())
            mapped.push_back(j);
        }
        r.count = static_cast<int>(mapped.size());
        it.value() = mapped;
        out.push_back(r);
      } else {
        remapIndexLists(it.value(), child, from, to, out);
      }
    }
  } else if (node.is_array()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      remapIndexLists(node[i], path + "." + std::to_string(i), from, to, out);
  }
}

// A handle's targets are its vertices' rest positions plus the trajectory's offsets. The remap
// moves those rest positions, by up to 9 cm on the Sock, whose cuff the uniform fit does not put
// where the task's cuff is, and the whole path moves with them: into the foot and the leg. So
// every knot after the first (a Hermite point or a keyframe offset) is moved back by the mean
// displacement of the attachment's vertices. The path still starts at the new vertices, but it
// ends where the task's handle ended. `original` is the scene before the remap.
inline void shiftHandlePaths(nlohmann::json& doc, const nlohmann::json& original,
                             const NodeMatrix& from, const NodeMatrix& to,
                             std::vector<HandleShift>& out) {
  const nlohmann::json& before = original["cloths"][0].value("attachments", nlohmann::json());
  nlohmann::json& attachments = doc["cloths"][0]["attachments"];
  if (!attachments.is_array()) return;
  const auto mean = [](const nlohmann::json& vertices, const NodeMatrix& x) {
    Vec3 sum = Vec3::Zero();
    for (const nlohmann::json& v : vertices) sum += x.row(v.get<int>()).transpose();
    return Vec3(sum / static_cast<double>(vertices.size()));
  };
  for (std::size_t a = 0; a < attachments.size(); ++a) {
    nlohmann::json& attachment = attachments[a];
    if (attachment.value("kind", "") != "handle" || !attachment.contains("trajectory")) continue;
    const Vec3 d = mean(before[a]["vertices"], from) - mean(attachment["vertices"], to);
    nlohmann::json& trajectory = attachment["trajectory"];
    const auto move = [&](nlohmann::json& offset) {
      for (int i = 0; i < 3; ++i) offset[i] = offset[i].get<double>() + d[i];
    };
    if (trajectory.contains("hermite")) {
      nlohmann::json& points = trajectory["hermite"]["points"];
      for (std::size_t k = 1; k < points.size(); ++k) move(points[k]);
    } else if (trajectory.contains("keyframes")) {
      nlohmann::json& keys = trajectory["keyframes"];
      for (std::size_t k = 1; k < keys.size(); ++k) move(keys[k]["offset"]);
    } else {
      continue;
    }
    out.push_back({"cloths.0.attachments." + std::to_string(a), d.norm()});
  }
}

// The `--set P=V` pairs of the `weft simulate` command a scene's description gives for its
// recorded target.
inline std::vector<SceneOverride> hiddenValues(const std::string& description,
                                               const std::string& file) {
  const auto at = description.find("weft simulate ");
  if (at == std::string::npos)
    throw InputError(file, "description",
                     "names no 'weft simulate ... --set P=V' command recording the target");
  std::stringstream words(description.substr(at));
  std::vector<SceneOverride> out;
  std::string word;
  while (words >> word && word != "then" && word != "then,") {
    if (word != "--set" || !(words >> word)) continue;
    while (!word.empty() && (word.back() == ',' || word.back() == ';')) word.pop_back();
    const auto eq = word.find('=');
    if (eq == std::string::npos) throw InputError(file, "description", "malformed --set " + word);
    out.push_back({word.substr(0, eq), word.substr(eq + 1)});
  }
  if (out.empty()) throw InputError(file, "description", "the target command sets no values");
  return out;
}

}  // namespace detail

// Builds the paper-mesh variant of `sceneFile` (a task scene with one cloth). Targets it has to
// record or rebuild are written to `targetDir` as <name>_target.npy; with `reuseTarget`, a
// recorded motion already there is kept (a resumed comparison's). Throws InputError.
inline PaperScene makePaperScene(const std::string& sceneFile, const PaperMesh& mesh,
                                 const std::string& meshDir, const std::string& targetDir,
                                 bool reuseTarget = false) {
  namespace fs = std::filesystem;
  const Scene original = loadScene(sceneFile);
  if (original.cloths.size() != 1)
    throw InputError(sceneFile, "cloths",
                     "paper meshes replace the garment of one-cloth scenes only");
  const NodeMatrix& from = original.cloths[0].mesh.vertices;

  PaperScene out;
  out.meshFile = fs::absolute(fs::path(meshDir) / mesh.file).lexically_normal().string();
  TriangleMesh paperMesh = readMesh(out.meshFile);
  RigidTransform rotate;
  rotate.rotateDeg = Vec3(mesh.rotateDeg[0], mesh.rotateDeg[1], mesh.rotateDeg[2]);
  rotate.applyTo(paperMesh.vertices);
  Vec3 loT, hiT, loP, hiP;
  detail::bounds(from, loT, hiT);
  detail::bounds(paperMesh.vertices, loP, hiP);
  out.scale = (hiT - loT).maxCoeff() / (hiP - loP).maxCoeff();
  out.rotateDeg = rotate.rotateDeg;
  out.translate = 0.5 * (loT + hiT) - out.scale * 0.5 * (loP + hiP);
  NodeMatrix to = paperMesh.vertices * out.scale;
  to.rowwise() += out.translate.transpose();
  out.vertices = static_cast<int>(to.rows());
  out.originalVertices = static_cast<int>(from.rows());

  nlohmann::json doc = original.document;
  doc["cloths"][0]["mesh"] = {
      {"file", out.meshFile},
      {"scale", out.scale},
      {"transform",
       {{"rotate_deg", {out.rotateDeg.x(), out.rotateDeg.y(), out.rotateDeg.z()}},
        {"translate", {out.translate.x(), out.translate.y(), out.translate.z()}}}}};
  const std::string name = doc.value("name", fs::path(sceneFile).stem().string());
  doc["name"] = name + "_paper";
  detail::remapIndexLists(doc, "", from, to, out.remaps);
  detail::shiftHandlePaths(doc, original.document, from, to, out.handleShifts);

  nlohmann::json& loss = doc["task"]["loss"];
  fs::create_directories(targetDir);
  const std::string targetFile =
      fs::absolute(fs::path(targetDir) / (name + "_target.npy")).lexically_normal().string();
  if (loss.contains("trajectory") && reuseTarget && fs::is_regular_file(targetFile)) {
    loss["trajectory"]["target"] = targetFile;
    out.target = targetFile;
  } else if (loss.contains("trajectory")) {
    // The recorded motion: the hidden values on the new garment, simulated here.
    nlohmann::json hidden = doc;
    for (const SceneOverride& o :
         detail::hiddenValues(original.document.value("description", ""), sceneFile)) {
      const std::string err = setJsonPath(hidden, o.path, parseOverrideValue(o.value));
      if (!err.empty()) throw InputError(sceneFile, "description: --set " + o.path, err);
    }
    hidden.erase("task");
    const Scene scene = parseScene(hidden, sceneFile, original.directory);
    Simulator sim(scene);
    Trajectory trajectory;
    sim.run(scene.time.steps, trajectory);
    const std::vector<double> flat = trajectory.flattenedPositions();
    const std::string tmp = targetFile + ".tmp";
    writeNpy(tmp,
             {trajectory.positions.size(), static_cast<std::size_t>(trajectory.nodeCount()), 3},
             flat.data());
    fs::rename(tmp, targetFile);  // whole or absent, for a resumed comparison
    loss["trajectory"]["target"] = targetFile;
    out.target = targetFile;
  }
  if (loss.contains("final")) {
    // The task's target must be its rest shape translated; the new one is translated so that
    // the top centre of its bounding box goes where the old target's goes.
    const std::string oldFile =
        resolveScenePath(original.directory, loss["final"]["target"].get<std::string>());
    const NpyArray old = readNpy(oldFile);
    const std::size_t n = static_cast<std::size_t>(from.rows());
    if (old.data.size() < 3 * n)
      throw InputError(oldFile, "<npy>", "fewer values than the task garment's vertices");
    const std::size_t base = old.data.size() - 3 * n;  // the last state of a trajectory
    Vec3 shift = Vec3::Zero();
    for (std::size_t i = 0; i < n; ++i)
      shift +=
          Vec3(old.data[base + 3 * i], old.data[base + 3 * i + 1], old.data[base + 3 * i + 2]) -
          from.row(static_cast<Eigen::Index>(i)).transpose();
    shift /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 d =
          Vec3(old.data[base + 3 * i], old.data[base + 3 * i + 1], old.data[base + 3 * i + 2]) -
          from.row(static_cast<Eigen::Index>(i)).transpose();
      if ((d - shift).norm() > 1e-5)
        throw InputError(oldFile, "<npy>",
                         "the final target is not the rest shape translated; cannot rebuild it "
                         "for another mesh");
    }
    Vec3 loN, hiN;
    detail::bounds(to, loN, hiN);
    const Vec3 topOld(0.5 * (loT.x() + hiT.x()), hiT.y(), 0.5 * (loT.z() + hiT.z()));
    const Vec3 topNew(0.5 * (loN.x() + hiN.x()), hiN.y(), 0.5 * (loN.z() + hiN.z()));
    const Vec3 newShift = topOld + shift - topNew;
    NodeMatrix target = to;
    target.rowwise() += newShift.transpose();
    std::vector<double> flat(3 * static_cast<std::size_t>(target.rows()));
    for (Eigen::Index i = 0; i < target.rows(); ++i)
      for (int k = 0; k < 3; ++k) flat[3 * static_cast<std::size_t>(i) + k] = target(i, k);
    writeNpy(targetFile, {static_cast<std::size_t>(target.rows()), 3}, flat.data());
    loss["final"]["target"] = targetFile;
    out.target = targetFile;
  }
  out.document = std::move(doc);
  return out;
}

}  // namespace weft::bench::paper
