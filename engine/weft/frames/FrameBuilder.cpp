#include <weft/frames/FrameBuilder.h>

#include <weft/core/Error.h>
#include <weft/io/Npy.h>
#include <weft/scene/SceneLoader.h>

#include <algorithm>
#include <set>

namespace weft {
namespace {

render::Vec3f f(const Vec3& v) {
  return v.cast<float>();
}

// A target array as states of `nodes` x 3: [states, nodes, 3] or [nodes, 3].
std::vector<NodeMatrix> readStates(const std::string& path, Eigen::Index nodes) {
  const NpyArray a = readNpy(path);
  std::size_t states = 0, rows = 0;
  if (a.shape.size() == 3 && a.shape[2] == 3)
    states = a.shape[0], rows = a.shape[1];
  else if (a.shape.size() == 2 && a.shape[1] == 3)
    states = 1, rows = a.shape[0];
  else
    throw InputError(path, "shape", "expected [states, vertices, 3] or [vertices, 3]");
  if (nodes >= 0 && rows != static_cast<std::size_t>(nodes))
    throw InputError(
        path, "shape",
        "has " + std::to_string(rows) + " vertices, the scene " + std::to_string(nodes));
  std::vector<NodeMatrix> out(states, NodeMatrix(Eigen::Index(rows), 3));
  for (std::size_t s = 0; s < states; ++s)
    for (std::size_t i = 0; i < rows; ++i)
      for (int c = 0; c < 3; ++c)
        out[s](Eigen::Index(i), c) = a.data[(s * rows + i) * 3 + std::size_t(c)];
  return out;
}

}  // namespace

render::ObstacleShape toRenderShape(const Obstacle& o) {
  render::ObstacleShape s;
  using K = render::ObstacleShape::Kind;
  switch (o.shape) {
    case Obstacle::Shape::Plane:
      s.kind = K::Plane;
      break;
    case Obstacle::Shape::Sphere:
      s.kind = K::Sphere;
      break;
    case Obstacle::Shape::Capsule:
      s.kind = K::Capsule;
      break;
    case Obstacle::Shape::Box:
      s.kind = K::Box;
      break;
    case Obstacle::Shape::Cylinder:
      s.kind = K::Cylinder;
      break;
    case Obstacle::Shape::Mesh:
      s.kind = K::Mesh;
      break;
  }
  s.point = f(o.point);
  s.normal = f(o.normal);
  s.center = f(o.center);
  s.radius = static_cast<float>(o.radius);
  s.a = f(o.a);
  s.b = f(o.b);
  s.halfExtents = f(o.halfExtents);
  s.rotation = o.rotation.cast<float>();
  s.mesh.positions = toRenderPoints(o.mesh.vertices);
  s.mesh.triangles = o.mesh.triangles;
  s.smoothNormals = o.smoothNormals;
  return s;
}

render::PointMatrix toRenderPoints(const NodeMatrix& positions) {
  return positions.cast<float>();
}

render::ObstacleShape movedShape(const render::ObstacleShape& shape, const HandleTrajectory& motion,
                                 double t) {
  auto move = [&](const render::Vec3f& p) { return f(motion.target(p.cast<double>(), t)); };
  // The rotation part, read off the motion itself: where it takes the ends of unit axes.
  const Vec3 origin = motion.target(Vec3::Zero(), t);
  Mat3 rotation;
  for (int k = 0; k < 3; ++k) rotation.col(k) = motion.target(Vec3::Unit(k), t) - origin;
  const Eigen::Matrix3f r = rotation.cast<float>();
  render::ObstacleShape moved = shape;
  moved.point = move(shape.point);
  moved.normal = r * shape.normal;
  moved.center = move(shape.center);
  moved.a = move(shape.a);
  moved.b = move(shape.b);
  moved.rotation = r * shape.rotation;
  for (Eigen::Index i = 0; i < moved.mesh.positions.rows(); ++i)
    moved.mesh.positions.row(i) = move(shape.mesh.positions.row(i).transpose()).transpose();
  return moved;
}

FrameBuilder::FrameBuilder(const Scene& scene, const ClothModel& model,
                           std::vector<std::string>* warnings)
    : dt_(scene.time.dt), triangles_(model.rest.triangles) {
  for (const Obstacle& o : scene.obstacles) {
    static_.obstacles.push_back(toRenderShape(o));
    motions_.push_back(o.motion);
  }

  const double duration = scene.time.steps * scene.time.dt;
  int group = 0;
  for (std::size_t c = 0; c < scene.cloths.size(); ++c) {
    const Cloth& cloth = scene.cloths[c];
    for (const Attachment& a : cloth.attachments) {
      for (int v : a.vertices) {
        (a.kind == Attachment::Kind::Fixed ? fixed_ : handles_)
            .push_back(model.vertexOffset[c] + v);
        if (a.kind == Attachment::Kind::Fixed) fixedGroups_.push_back(group);
      }
      if (a.kind == Attachment::Kind::Fixed) ++group;
      if (a.kind != Attachment::Kind::Handle || a.vertices.empty()) continue;
      // The path of the handle's centroid over the whole simulation, through every key time.
      Vec3 centroid = Vec3::Zero();
      for (int v : a.vertices) centroid += cloth.mesh.vertices.row(v).transpose();
      centroid /= double(a.vertices.size());
      std::set<double> times;
      const int samples = 120;
      for (int k = 0; k <= samples; ++k) times.insert(duration * k / samples);
      for (double t : a.trajectory.times)
        if (t >= 0.0 && t <= duration) times.insert(t);
      render::Curve curve;
      for (double t : times) curve.points.push_back(f(a.trajectory.target(centroid, t)));
      static_.curves.push_back(std::move(curve));
    }
  }

  if (!scene.task) return;
  const nlohmann::json& loss = scene.task->loss;
  auto warn = [&](const std::string& what) {
    if (warnings) warnings->push_back(what);
  };
  const Eigen::Index nodes = model.nodeCount();
  if (loss.contains("trajectory")) {
    const std::string path =
        resolveScenePath(scene.directory, loss["trajectory"].value("target", ""));
    try {
      targetStates_ = readStates(path, nodes);
    } catch (const InputError& e) {
      warn(std::string("trajectory target not shown: ") + e.what());
    }
  }
  if (loss.contains("final")) {
    const nlohmann::json& term = loss["final"];
    const std::string path = resolveScenePath(scene.directory, term.value("target", ""));
    try {
      const std::vector<NodeMatrix> states = readStates(path, -1);
      const NodeMatrix& last = states.back();
      if (term.contains("vertices")) {
        finalVertices_ = term["vertices"].get<std::vector<int>>();
        const bool full =
            last.rows() == nodes;  // a full state indexed by vertex, or one row per listed vertex
        if (!full && last.rows() != Eigen::Index(finalVertices_.size()))
          throw InputError(path, "shape",
                           "matches neither the scene's vertices nor the listed ones");
        finalTarget_.resize(Eigen::Index(finalVertices_.size()), 3);
        for (std::size_t k = 0; k < finalVertices_.size(); ++k) {
          const int v = finalVertices_[k];
          if (v < 0 || v >= nodes)
            throw InputError(path, "vertices", "vertex " + std::to_string(v) + " is out of range");
          finalTarget_.row(Eigen::Index(k)) = last.row(full ? v : Eigen::Index(k));
        }
      } else {
        if (last.rows() != nodes)
          throw InputError(path, "shape", "does not match the scene's vertices");
        finalTarget_ = last;
      }
    } catch (const InputError& e) {
      finalVertices_.clear();
      finalTarget_.resize(0, 3);
      warn(std::string("final target not shown: ") + e.what());
    } catch (const nlohmann::json::exception& e) {
      finalVertices_.clear();
      finalTarget_.resize(0, 3);
      warn(std::string("final target not shown: ") + e.what());
    }
  }
}

render::RenderScene FrameBuilder::frame(const NodeMatrix& x, int state) const {
  render::RenderScene frame = static_;
  for (std::size_t k = 0; k < motions_.size(); ++k)
    if (motions_[k])
      frame.obstacles[k] = movedShape(static_.obstacles[k], *motions_[k], state * dt_);
  frame.cloth.positions = toRenderPoints(x);
  frame.cloth.triangles = triangles_;
  for (int v : fixed_) frame.fixedPoints.push_back(f(x.row(v).transpose()));
  // One group draws in the style's colour; several get a colour each (pinGroupColor).
  if (!fixedGroups_.empty() && fixedGroups_.back() > 0) frame.fixedPointGroups = fixedGroups_;
  for (int v : handles_) frame.handlePoints.push_back(f(x.row(v).transpose()));
  if (!targetStates_.empty()) {
    const NodeMatrix& target = targetStates_[std::min<std::size_t>(std::size_t(std::max(state, 0)),
                                                                   targetStates_.size() - 1)];
    frame.ghosts.push_back({{toRenderPoints(target), triangles_}, {0.55f, 0.25f, 0.75f}, 0.35f});
  }
  if (finalTarget_.rows() > 0) {
    if (finalVertices_.empty())
      frame.ghosts.push_back(
          {{toRenderPoints(finalTarget_), triangles_}, {0.55f, 0.25f, 0.75f}, 0.35f});
    else
      for (Eigen::Index k = 0; k < finalTarget_.rows(); ++k)
        frame.targetPoints.push_back(f(finalTarget_.row(k).transpose()));
  }
  return frame;
}

}  // namespace weft
