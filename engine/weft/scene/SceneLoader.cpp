#include <weft/scene/SceneLoader.h>

#include <weft/io/MeshReader.h>
#include <weft/mesh/GridMesh.h>
#include <weft/mesh/MeshCheck.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/JsonReader.h>
#include <weft/scene/ValueChecks.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;

namespace weft {
namespace {

RigidTransform readTransform(const JsonReader& r) {
  r.allowOnly({"translate", "rotate_deg"});
  RigidTransform t;
  if (auto v = r.optional("translate")) t.translate = v->vec3();
  if (auto v = r.optional("rotate_deg")) t.rotateDeg = v->vec3();
  return t;
}

// A mesh file with optional "scale" (applied first) and "transform".
TriangleMesh readMeshFile(const JsonReader& r, const std::string& directory, const char* fileKey) {
  const JsonReader fileNode = r.at(fileKey);
  const std::string path = resolveScenePath(directory, fileNode.string());
  TriangleMesh mesh;
  try {
    mesh = readMesh(path);
  } catch (const InputError& e) {
    fileNode.fail(e.reason() + " (" + path + ")");
  }
  if (auto s = r.optional("scale")) mesh.vertices *= s->positive();
  if (auto t = r.optional("transform")) readTransform(*t).applyTo(mesh.vertices);
  return mesh;
}

// Mesh checks: errors stop the load unless "repair" is set, in which case degenerate
// triangles are dropped with a warning. Non-manifold edges and thin triangles only warn.
void checkClothMesh(TriangleMesh& mesh, const JsonReader& meshNode, bool repair,
                    std::vector<std::string>& warnings) {
  MeshReport report = checkMesh(mesh);
  const std::string where = meshNode.file() + ": " + meshNode.path() + ": ";
  if (!report.nonFiniteVertices.empty())
    meshNode.fail("non-finite vertex coordinates at vertices " +
                  formatIndexList(report.nonFiniteVertices));
  if (!report.badIndexTriangles.empty())
    meshNode.fail("triangles with out-of-range or repeated vertex indices: " +
                  formatIndexList(report.badIndexTriangles));
  if (!report.degenerateTriangles.empty()) {
    if (!repair)
      meshNode.fail("degenerate (zero-area) triangles " +
                    formatIndexList(report.degenerateTriangles) +
                    "; fix the mesh or set \"repair\": true to drop them");
    warnings.push_back(where + "dropped degenerate triangles " +
                       formatIndexList(report.degenerateTriangles));
    removeTriangles(mesh, report.degenerateTriangles);
    report = checkMesh(mesh);
  }
  if (!report.unreferencedVertices.empty()) {
    // A vertex in no triangle has no mass: it cannot be simulated as cloth.
    meshNode.fail("vertices in no triangle " + formatIndexList(report.unreferencedVertices) +
                  (repair ? " (left after dropping degenerate triangles)" : "") +
                  "; remove them from the mesh");
  }
  if (!report.nonManifoldEdges.empty()) {
    std::vector<int> flat;
    for (auto [a, b] : report.nonManifoldEdges) flat.push_back(a), flat.push_back(b);
    warnings.push_back(where + std::to_string(report.nonManifoldEdges.size()) +
                       " non-manifold edges (vertex pairs " + formatIndexList(flat) +
                       "); no bending is applied across them");
  }
  if (!report.thinTriangles.empty())
    warnings.push_back(where + "triangles with an angle under 5 degrees " +
                       formatIndexList(report.thinTriangles) + " may converge slowly");
}

TriangleMesh readClothMesh(const JsonReader& r, const std::string& directory,
                           std::vector<std::string>& warnings) {
  r.allowOnly({"grid", "file", "scale", "transform", "repair"});
  const std::string kind = r.oneOf({"grid", "file"});
  TriangleMesh mesh;
  if (kind == "grid") {
    const JsonReader g = r.at("grid");
    g.allowOnly({"size", "resolution"});
    const JsonReader size = g.at("size");
    if (size.size() != 2) size.fail("must be [extent X, extent Z]");
    const double sx = size[0].positive(), sz = size[1].positive();
    const JsonReader res = g.at("resolution");
    if (res.size() != 2) res.fail("must be [quads X, quads Z]");
    const int qx = res[0].integer(1, 4096), qz = res[1].integer(1, 4096);
    mesh = makeGrid(sx, sz, qx, qz);
    if (r.has("scale")) r.at("scale").fail("applies to mesh files only; set the grid size instead");
    if (auto t = r.optional("transform")) readTransform(*t).applyTo(mesh.vertices);
  } else {
    mesh = readMeshFile(r, directory, "file");
  }
  const bool repair = r.optional("repair") ? r.at("repair").boolean() : false;
  checkClothMesh(mesh, r, repair, warnings);
  return mesh;
}

HandleTrajectory readTrajectory(const JsonReader& r) {
  r.allowOnly({"keyframes", "hermite", "rotate"});
  HandleTrajectory traj;
  if (r.has("keyframes") && r.has("hermite")) r.fail("give 'keyframes' or 'hermite', not both");
  auto checkTimes = [](const JsonReader& node, const std::vector<double>& times) {
    for (std::size_t i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1])) node.fail("times must be strictly increasing");
  };
  if (auto k = r.optional("keyframes")) {
    traj.kind = HandleTrajectory::Kind::Keyframes;
    if (k->size() == 0) k->fail("needs at least one keyframe");
    for (std::size_t i = 0; i < k->size(); ++i) {
      const JsonReader key = (*k)[i];
      key.allowOnly({"time", "offset"});
      traj.times.push_back(key.at("time").number(0.0));
      traj.offsets.push_back(key.at("offset").vec3());
    }
    checkTimes(*k, traj.times);
  } else if (auto h = r.optional("hermite")) {
    traj.kind = HandleTrajectory::Kind::Hermite;
    h->allowOnly({"times", "points", "tangents"});
    const JsonReader times = h->at("times"), points = h->at("points"), tangents = h->at("tangents");
    const std::size_t n = times.size();
    if (n < 2) times.fail("needs at least two knots");
    if (points.size() != n) points.fail("needs one point per time (" + std::to_string(n) + ")");
    if (tangents.size() != n)
      tangents.fail("needs one tangent per time (" + std::to_string(n) + ")");
    for (std::size_t i = 0; i < n; ++i) {
      traj.times.push_back(times[i].number(0.0));
      traj.offsets.push_back(points[i].vec3());
      traj.tangents.push_back(tangents[i].vec3());
    }
    checkTimes(times, traj.times);
  }
  if (auto rot = r.optional("rotate")) {
    rot->allowOnly({"center", "axis", "degrees_per_second"});
    traj.rotates = true;
    traj.rotationCenter = rot->at("center").vec3();
    traj.rotationAxis = rot->at("axis").unitVec3();
    traj.rotationRateDeg = rot->at("degrees_per_second").number();
  }
  if (traj.times.empty() && !traj.rotates) r.fail("needs 'keyframes', 'hermite' or 'rotate'");
  return traj;
}

Cloth readCloth(const JsonReader& r, const std::string& directory,
                std::vector<std::string>& warnings) {
  r.allowOnly(
      {"name", "mesh", "material", "attachments", "forces", "initial_velocity", "self_collision"});
  if (auto n = r.optional("name")) n->string();
  Cloth cloth;
  cloth.mesh = readClothMesh(r.at("mesh").object(), directory, warnings);
  const int m = cloth.mesh.vertexCount();

  const JsonReader mat = r.at("material");
  mat.allowOnly({"density", "stretch", "bend", "bend_model"});
  cloth.material.density = readDensity(mat.at("density"));
  cloth.material.stretch = readStiffness(mat.at("stretch"));
  if (auto b = mat.optional("bend")) cloth.material.bend = readStiffness(*b);
  if (auto v = mat.optional("bend_model"))
    cloth.material.bendModel = v->choice({"magnitude", "oriented"}) == "oriented"
                                   ? Material::BendModel::Oriented
                                   : Material::BendModel::Magnitude;

  if (auto list = r.optional("attachments")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const JsonReader a = (*list)[i];
      a.allowOnly({"vertices", "kind", "stiffness", "trajectory", "name"});
      // A name for people (the editor's pin groups); the simulation does not read it.
      if (auto n = a.optional("name")) n->string();
      Attachment att;
      att.vertices = a.at("vertices").indices(m);
      if (att.vertices.empty()) a.at("vertices").fail("must list at least one vertex");
      const std::string kind =
          a.optional("kind") ? a.at("kind").choice({"fixed", "handle"}) : "fixed";
      att.kind = kind == "fixed" ? Attachment::Kind::Fixed : Attachment::Kind::Handle;
      if (auto s = a.optional("stiffness")) att.stiffness = readAttachmentStiffness(*s);
      if (att.kind == Attachment::Kind::Handle) {
        att.trajectory = readTrajectory(a.at("trajectory").object());
      } else if (a.has("trajectory")) {
        a.at("trajectory").fail("only a 'handle' attachment moves; set \"kind\": \"handle\"");
      }
      cloth.attachments.push_back(std::move(att));
    }
  }
  if (auto list = r.optional("forces")) {
    for (std::size_t i = 0; i < list->size(); ++i) {
      const JsonReader f = (*list)[i];
      f.allowOnly({"vertices", "force"});
      PointForce pf;
      pf.vertices = f.at("vertices").indices(m);
      pf.force = f.at("force").vec3();
      cloth.forces.push_back(std::move(pf));
    }
  }
  if (auto v = r.optional("initial_velocity")) cloth.initialVelocity = v->vec3();
  if (auto sc = r.optional("self_collision")) {
    sc->allowOnly({"model", "radius", "friction", "thickness"});
    SelfCollision s;
    if (auto model = sc->optional("model")) {
      // One model's name, or an array of both.
      std::vector<std::string> names;
      if (model->value().is_array()) {
        if (model->size() == 0) model->fail("an empty list of models");
        for (std::size_t k = 0; k < model->size(); ++k)
          names.push_back((*model)[k].choice({"node", "impact_zones"}));
      } else {
        names.push_back(model->choice({"node", "impact_zones"}));
      }
      s.nodeModel = std::count(names.begin(), names.end(), "node") > 0;
      s.impactZones = std::count(names.begin(), names.end(), "impact_zones") > 0;
      if (names.size() != static_cast<std::size_t>(s.nodeModel) + s.impactZones)
        model->fail("a model is named twice");
    }
    if (s.nodeModel) {
      s.radius = sc->at("radius").positive();
      if (auto f = sc->optional("friction")) s.friction = readFriction(*f);
    } else {
      for (const char* key : {"radius", "friction"})
        if (auto k = sc->optional(key)) k->fail("used only by the \"node\" model");
    }
    if (s.impactZones) {
      if (auto t = sc->optional("thickness")) s.thickness = t->positive();
    } else if (auto t = sc->optional("thickness")) {
      t->fail("used only by the \"impact_zones\" model");
    }
    cloth.selfCollision = s;
  }
  return cloth;
}

Obstacle readObstacle(const JsonReader& r, const std::string& directory) {
  r.allowOnly(
      {"plane", "sphere", "capsule", "box", "cylinder", "mesh", "friction", "thickness", "motion"});
  Obstacle o;
  if (auto f = r.optional("friction")) o.friction = readFriction(*f);
  o.thickness = r.number("thickness", o.thickness, 0.0, 1.0);
  // Kinematic motion: the same keyframes / Hermite spline / rotation as a handle trajectory.
  if (auto m = r.optional("motion")) o.motion = readTrajectory(m->object());
  const std::string kind = r.oneOf({"plane", "sphere", "capsule", "box", "cylinder", "mesh"});
  const JsonReader s = r.at(kind).object();
  if (kind == "plane") {
    s.allowOnly({"point", "normal"});
    o.shape = Obstacle::Shape::Plane;
    o.point = s.at("point").vec3();
    o.normal = s.at("normal").unitVec3();
  } else if (kind == "sphere") {
    s.allowOnly({"center", "radius"});
    o.shape = Obstacle::Shape::Sphere;
    o.center = s.at("center").vec3();
    o.radius = s.at("radius").positive();
  } else if (kind == "capsule" || kind == "cylinder") {
    s.allowOnly({"a", "b", "radius"});
    o.shape = kind == "capsule" ? Obstacle::Shape::Capsule : Obstacle::Shape::Cylinder;
    o.a = s.at("a").vec3();
    o.b = s.at("b").vec3();
    o.radius = s.at("radius").positive();
    if ((o.b - o.a).norm() < 1e-12) s.at("b").fail("must differ from 'a'");
  } else if (kind == "box") {
    s.allowOnly({"center", "size", "rotate_deg"});
    o.shape = Obstacle::Shape::Box;
    o.center = s.at("center").vec3();
    const JsonReader size = s.at("size");
    if (size.size() != 3) size.fail("must be [x, y, z]");
    o.halfExtents = Vec3(size[0].positive(), size[1].positive(), size[2].positive()) * 0.5;
    if (auto rd = s.optional("rotate_deg")) {
      RigidTransform t;
      t.rotateDeg = rd->vec3();
      o.rotation = t.rotation();
    }
  } else {
    s.allowOnly({"file", "scale", "transform", "smooth_normals"});
    o.shape = Obstacle::Shape::Mesh;
    o.mesh = readMeshFile(s, directory, "file");
    if (auto sn = s.optional("smooth_normals")) o.smoothNormals = sn->boolean();
    const MeshReport report = checkMesh(o.mesh);
    if (!report.nonFiniteVertices.empty() || !report.badIndexTriangles.empty())
      s.fail("mesh has non-finite vertices or bad triangle indices");
  }
  return o;
}

Wind readWind(const JsonReader& r, const std::vector<Cloth>& cloths) {
  r.allowOnly({"direction", "strength", "frequency", "phase", "model", "falloff"});
  Wind w;
  w.direction = readWindDirection(r.at("direction"));
  w.strength = readWindStrength(r.at("strength"));
  if (auto f = r.optional("frequency")) w.frequency = readWindFrequency(*f);
  if (auto p = r.optional("phase")) w.phase = readWindPhase(*p);
  if (auto m = r.optional("model")) w.constant = m->choice({"sinusoid", "constant"}) == "constant";
  if (auto f = r.optional("falloff")) {
    // Eq. 35's k: each node's inverse distance to the centre at the initial state (the rest mesh).
    f->object().allowOnly({"center"});
    w.falloffCenter = f->at("center").vec3();
    int count = 0;
    for (const Cloth& c : cloths) count += c.mesh.vertexCount();
    w.coefficients.resize(count);
    int node = 0;
    for (const Cloth& c : cloths)
      for (int i = 0; i < c.mesh.vertexCount(); ++i, ++node) {
        const double d = (c.mesh.vertices.row(i).transpose() - *w.falloffCenter).norm();
        // A node at the centre would receive an unbounded force.
        if (!(d >= 1e-6))
          f->at("center").fail(
              "vertex " + std::to_string(node) +
              " lies at the centre (closer than 1e-6 m): its inverse distance is unbounded");
        w.coefficients[node] = 1.0 / d;
      }
  }
  return w;
}

void readSolver(const JsonReader& r, SolverSettings& s) {
  r.allowOnly({"method", "contact", "pd_iterations", "pd_tolerance", "acceleration",
               "anderson_window", "max_halvings", "remember_halvings", "backward"});
  if (auto v = r.optional("method"))
    s.method = v->choice({"newton", "pd"}) == "pd" ? SolverMethod::ProjectiveDynamics
                                                   : SolverMethod::Newton;
  if (auto v = r.optional("contact")) {
    const std::string c = v->choice({"pd", "active_set", "newton"});
    s.contact = c == "active_set" ? ContactMethod::ActiveSet
                : c == "newton"   ? ContactMethod::Newton
                                  : ContactMethod::ProjectiveDynamics;
  }
  if (auto v = r.optional("pd_iterations")) s.pdIterations = v->integer(1, 1000000);
  if (auto v = r.optional("pd_tolerance")) s.pdTolerance = v->positive();
  if (auto v = r.optional("acceleration"))
    s.acceleration =
        v->choice({"anderson", "none"}) == "none" ? Acceleration::None : Acceleration::Anderson;
  if (auto v = r.optional("anderson_window")) s.andersonWindow = v->integer(1, 50);
  if (auto v = r.optional("max_halvings")) s.maxHalvings = v->integer(0, 10);
  if (auto v = r.optional("remember_halvings")) s.rememberHalvings = v->boolean();
  if (auto b = r.optional("backward")) {
    b->allowOnly({"method", "tolerance", "max_iterations", "fallback", "preconditioner", "history",
                  "accuracy"});
    if (auto v = b->optional("method"))
      s.backward.method = v->choice({"gmres", "fixed_point", "direct"});
    if (auto v = b->optional("tolerance")) s.backward.tolerance = v->positive();
    if (auto v = b->optional("max_iterations")) s.backward.maxIterations = v->integer(1, 1000000);
    if (auto v = b->optional("fallback")) s.backward.fallback = v->choice({"direct", "none"});
    if (auto v = b->optional("preconditioner"))
      s.backward.preconditioner = v->choice({"auto", "p", "hessian"});
    if (auto v = b->optional("history")) s.backward.history = v->integer(0, 64);
    if (auto v = b->optional("accuracy")) s.backward.accuracy = v->number(0.0, 1.0);
  }
}

// Global vertex indices (scene order, as in positions.npy), as the task losses use them.
std::vector<int> readGlobalVertices(const JsonReader& list, int vertices) {
  if (list.size() == 0) list.fail("must list at least one vertex");
  std::vector<int> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader item = list[i];
    if (!item.value().is_number_integer())
      item.fail("must be a vertex index in [0, " + std::to_string(vertices) +
                ") (global, scene order)");
    const long long v = item.value().get<long long>();
    if (v < 0 || v >= vertices)
      item.fail("vertex index " + std::to_string(v) + " out of range: the scene has " +
                std::to_string(vertices) + " vertices (global, scene order)");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

// task.loss.keypoints {points: [{step, vertices, positions | target, weight}], weight}
// (engine/weft/diff/KeypointLoss.h). Target files are checked when the loss is built.
void checkKeypointsTerm(const JsonReader& term, int steps, int vertices) {
  term.allowOnly({"points", "weight"});
  if (term.has("weight")) term.at("weight").positive();
  const JsonReader points = term.at("points");
  if (points.size() == 0)
    points.fail("needs at least one keypoint entry {step, vertices, positions or target}");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const JsonReader entry = points[i].object();
    entry.allowOnly({"step", "vertices", "positions", "target", "weight"});
    entry.at("step").integer(0, steps);
    const std::size_t count = readGlobalVertices(entry.at("vertices"), vertices).size();
    if (entry.oneOf({"positions", "target"}) == "positions") {
      const JsonReader positions = entry.at("positions");
      if (positions.size() != count)
        positions.fail("needs one [x, y, z] per listed vertex (" + std::to_string(count) +
                       "), got " + std::to_string(positions.size()));
      for (std::size_t k = 0; k < count; ++k) positions[k].vec3();
    } else {
      entry.at("target").string();
    }
    if (entry.has("weight")) entry.at("weight").positive();
  }
}

// task.loss.hemline {vertices, height | (apex_angle_deg, apex_height, slant_length), steps, up,
// weight} (engine/weft/diff/HemlineLoss.h).
void checkHemlineTerm(const JsonReader& term, int steps, int vertices) {
  term.allowOnly({"vertices", "height", "apex_angle_deg", "apex_height", "slant_length", "steps",
                  "up", "weight"});
  readGlobalVertices(term.at("vertices"), vertices);
  if (term.has("height")) {
    for (const char* k : {"apex_angle_deg", "apex_height", "slant_length"})
      if (term.has(k)) term.at(k).fail("give 'height' or the apex angle form, not both");
    term.at("height").number();
  } else if (term.has("apex_angle_deg") || term.has("apex_height") || term.has("slant_length")) {
    const double angle = term.at("apex_angle_deg").number(0.0, 180.0);
    if (!(angle > 0.0 && angle < 180.0))
      term.at("apex_angle_deg").fail("must lie strictly between 0 and 180");
    term.at("apex_height").number();
    term.at("slant_length").positive();
  } else {
    term.fail("needs a target: 'height' (m) or 'apex_angle_deg', 'apex_height' and 'slant_length'");
  }
  if (auto list = term.optional("steps")) {
    if (list->size() == 0)
      list->fail("must list at least one step (or leave it out for the last state)");
    for (std::size_t i = 0; i < list->size(); ++i) (*list)[i].integer(0, steps);
  }
  if (auto up = term.optional("up")) up->unitVec3();
  if (term.has("weight")) term.at("weight").positive();
}

Task readTask(const JsonReader& r, const nlohmann::json& doc, const std::string& directory,
              int steps, int vertices) {
  r.allowOnly({"loss", "parameters", "bounds"});
  Task task;
  const JsonReader loss = r.at("loss").object();
  if (loss.value().empty()) loss.fail("needs at least one loss term");
  loss.allowOnly({"trajectory", "final", "keypoints", "hemline", "handle_clearance"});
  for (auto it = loss.value().begin(); it != loss.value().end(); ++it) {
    const JsonReader term = loss.at(it.key()).object();
    if (it.key() == "trajectory" || it.key() == "final") {
      term.allowOnly({"target", "vertices", "weight"});
      const JsonReader target = term.at("target");
      target.string();
      if (term.has("weight")) term.at("weight").positive();
      if (term.has("vertices")) term.at("vertices").size();
      (void)directory;  // targets may be produced later (e.g. by a run); checked when the loss is
                        // built
    } else if (it.key() == "keypoints") {
      checkKeypointsTerm(term, steps, vertices);
    } else if (it.key() == "handle_clearance") {
      term.allowOnly({"weight", "margin"});
      if (term.has("weight")) term.at("weight").positive();
      if (term.has("margin")) term.at("margin").number(0.0);
    } else {
      checkHemlineTerm(term, steps, vertices);
    }
  }
  task.loss = loss.value();
  if (auto params = r.optional("parameters")) {
    for (std::size_t i = 0; i < params->size(); ++i) {
      const JsonReader p = (*params)[i];
      const std::string path = p.string();
      const nlohmann::json* v = findJsonPath(doc, path);
      if (!v)
        p.fail("parameter '" + path +
               "' names no value in the scene (write the value in the scene file)");
      if (!v->is_number()) p.fail("parameter '" + path + "' is not a number in the scene");
      task.parameters.push_back(path);
    }
  }
  if (auto bounds = r.optional("bounds")) {
    bounds->object();
    for (auto it = bounds->value().begin(); it != bounds->value().end(); ++it) {
      const JsonReader b = bounds->at(it.key());
      if (std::find(task.parameters.begin(), task.parameters.end(), it.key()) ==
          task.parameters.end())
        b.fail("bounds are given for '" + it.key() + "', which is not one of task.parameters");
      if (b.size() != 2) b.fail("must be [lower, upper] (null for an unbounded side)");
      const double inf = std::numeric_limits<double>::infinity();
      const double lower = b[0].value().is_null() ? -inf : b[0].number();
      const double upper = b[1].value().is_null() ? inf : b[1].number();
      if (!(lower < upper)) b.fail("lower bound must be below the upper bound");
      task.bounds.push_back({it.key(), lower, upper});
    }
  }
  return task;
}

std::string locate(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n')
      ++line, col = 1;
    else
      ++col;
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

}  // namespace

std::string resolveScenePath(const std::string& directory, const std::string& path) {
  const fs::path p(path);
  if (p.is_absolute()) return path;
  const fs::path local = fs::path(directory) / p;
  if (fs::exists(local) || !fs::exists(p)) return local.lexically_normal().string();
  return p.string();
}

Scene parseScene(const nlohmann::json& document, const std::string& file,
                 const std::string& directory) {
  const JsonReader root(document, file, "");
  root.object();
  root.allowOnly(
      {"name", "description", "time", "gravity", "solver", "cloths", "obstacles", "wind", "task"});
  Scene scene;
  scene.file = file;
  scene.directory = directory;
  scene.document = document;
  scene.name = root.optional("name") ? root.at("name").string() : fs::path(file).stem().string();
  if (auto d = root.optional("description")) d->string();

  const JsonReader time = root.at("time");
  time.allowOnly({"dt", "steps"});
  scene.time.dt = time.at("dt").positive();
  if (scene.time.dt > 1.0) time.at("dt").fail("must be at most 1 s");
  scene.time.steps = time.at("steps").integer(0, 10000000);

  if (auto g = root.optional("gravity")) scene.gravity = g->vec3();
  if (auto s = root.optional("solver")) readSolver(*s, scene.solver);

  const JsonReader cloths = root.at("cloths");
  if (cloths.size() == 0) cloths.fail("needs at least one cloth");
  for (std::size_t i = 0; i < cloths.size(); ++i)
    scene.cloths.push_back(readCloth(cloths[i].object(), directory, scene.warnings));

  if (auto obs = root.optional("obstacles"))
    for (std::size_t i = 0; i < obs->size(); ++i)
      scene.obstacles.push_back(readObstacle((*obs)[i].object(), directory));
  if (auto w = root.optional("wind")) scene.wind = readWind(w->object(), scene.cloths);
  if (auto t = root.optional("task"))
    scene.task = readTask(t->object(), document, directory, scene.time.steps, scene.vertexCount());
  return scene;
}

SceneOverride parseSceneOverride(const std::string& text, const std::string& file) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(file, "--set", "expects PATH=VALUE, got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

Scene loadScene(const std::string& file, const std::vector<SceneOverride>& overrides) {
  std::ifstream in(file);
  if (!fs::is_regular_file(file) || !in) throw InputError(file, "<file>", "cannot open scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    throw InputError(file, "<json>",
                     "invalid JSON at " + locate(text, e.byte > 0 ? e.byte - 1 : 0) +
                         (pos != std::string::npos ? ": " + what.substr(pos) : ""));
  } catch (const nlohmann::json::exception& e) {
    // E.g. out_of_range 406, "number overflow parsing '1e999'": no byte offset is given, so the
    // quoted token is looked up in the text to say where it is.
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const auto detail = what.find("] ");
    std::string where;
    if (open != std::string::npos && close > open) {
      const auto at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) where = " at " + locate(text, at);
    }
    const std::string reason = detail != std::string::npos ? what.substr(detail + 2) : what;
    throw InputError(file, "<json>", "invalid JSON" + where + ": " + reason);
  }
  const std::string directory = fs::path(file).parent_path().string();
  return loadSceneDocument(std::move(doc), file, directory.empty() ? "." : directory, overrides);
}

Scene loadSceneDocument(nlohmann::json doc, const std::string& file, const std::string& directory,
                        const std::vector<SceneOverride>& overrides) {
  // Per override that introduced keys: the outermost key it created (the path itself, or the
  // first of the objects it had to create), the override's path, and whether it created objects.
  struct Created {
    std::string key, option;
    bool objects;
  };
  std::vector<Created> created;
  for (const SceneOverride& o : overrides) {
    // A scene's keys and strings are UTF-8 (its file is parsed as JSON); so must an override be.
    if (!isValidUtf8(o.path) || !isValidUtf8(o.value))
      throw InputError(file, "--set " + o.path, "not valid UTF-8");
    const bool existed = findJsonPath(doc, o.path) != nullptr;
    // Keys the format defines are settable when the file leaves them (and their objects) at
    // their defaults; the validator below rejects the keys it does not define.
    const std::string createdObject = existed ? "" : createJsonPathObjects(doc, o.path);
    const std::string err = setJsonPath(doc, o.path, parseOverrideValue(o.value));
    if (!err.empty()) throw InputError(file, "--set " + o.path, err);
    if (!existed)
      created.push_back(
          {createdObject.empty() ? o.path : createdObject, o.path, !createdObject.empty()});
  }
  try {
    return parseScene(doc, file, directory);
  } catch (const InputError& e) {
    // A key that only an override introduced is reported against the option that wrote it; an
    // object it created that the format does not define makes the path an unknown one.
    for (const Created& c : created)
      if (e.path() == c.key || e.path().rfind(c.key + ".", 0) == 0) {
        const std::string reason = e.reason() == "" ? "invalid" : e.reason();
        throw InputError(file, "--set " + c.option,
                         c.objects && reason.rfind("unknown key", 0) == 0
                             ? "unknown path: " + e.path() + ": " + reason
                             : reason);
      }
    throw;
  }
}

}  // namespace weft
