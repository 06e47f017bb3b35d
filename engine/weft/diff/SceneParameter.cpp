#include <weft/diff/SceneParameter.h>

#include <weft/core/Error.h>
#include <weft/scene/JsonPath.h>
#include <weft/scene/JsonReader.h>
#include <weft/scene/ValueChecks.h>

#include <cstdlib>

namespace weft {
namespace {

bool parseIndex(const std::string& s, int& out) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos)
    return false;
  out = std::atoi(s.c_str());
  return true;
}

const char* kSupported =
    "differentiable parameters are cloths.K.material.{stretch,bend,density}, "
    "cloths.K.initial_velocity.i, cloths.K.forces.J.force.i, cloths.K.attachments.J.stiffness, "
    "cloths.K.attachments.J.trajectory.keyframes.P.offset.i, "
    "cloths.K.attachments.J.trajectory.hermite.{points,tangents}.P.i, "
    "wind.{strength,frequency,phase}, wind.direction.i, gravity.i, obstacles.J.friction, "
    "cloths.K.self_collision.friction";

}  // namespace

SceneParameter resolveSceneParameter(const Scene& scene, const std::string& path,
                                     const std::string& where) {
  auto fail = [&](const std::string& what) { throw InputError(scene.file, where, what); };
  const nlohmann::json* value = findJsonPath(scene.document, path);
  if (!value)
    fail("parameter '" + path +
         "' names no value in the scene (write the value in the scene file)");
  if (!value->is_number()) fail("parameter '" + path + "' is not a number in the scene");

  SceneParameter p;
  p.path = path;
  const std::vector<std::string> parts = splitJsonPath(path);
  const std::size_t n = parts.size();
  auto component = [&](const std::string& s) {
    int c = -1;
    if (!parseIndex(s, c) || c > 2) fail("parameter '" + path + "': component must be 0, 1 or 2");
    return c;
  };
  if (n >= 3 && parts[0] == "cloths") {
    if (!parseIndex(parts[1], p.cloth) || p.cloth >= static_cast<int>(scene.cloths.size()))
      fail("parameter '" + path + "': no such cloth");
    if (n == 4 && parts[2] == "material") {
      if (parts[3] == "stretch")
        p.kind = SceneParameter::Kind::Stretch;
      else if (parts[3] == "bend")
        p.kind = SceneParameter::Kind::Bend;
      else if (parts[3] == "density")
        p.kind = SceneParameter::Kind::Density;
      else
        fail("parameter '" + path + "' is not differentiable; " + kSupported);
      return p;
    }
    if (n == 4 && parts[2] == "self_collision" && parts[3] == "friction") {
      if (!scene.cloths[p.cloth].selfCollision || !scene.cloths[p.cloth].selfCollision->nodeModel)
        fail("parameter '" + path + "': the cloth has no node-model self-collision");
      p.kind = SceneParameter::Kind::SelfCollisionFriction;
      return p;
    }
    if (n == 4 && parts[2] == "initial_velocity") {
      p.kind = SceneParameter::Kind::InitialVelocity;
      p.component = component(parts[3]);
      return p;
    }
    if (n == 6 && parts[2] == "forces" && parts[4] == "force") {
      p.kind = SceneParameter::Kind::NodalForce;
      if (!parseIndex(parts[3], p.index)) fail("parameter '" + path + "': no such force");
      p.component = component(parts[5]);
      return p;
    }
    if (n >= 5 && parts[2] == "attachments") {
      const std::vector<Attachment>& attachments = scene.cloths[p.cloth].attachments;
      if (!parseIndex(parts[3], p.index) || p.index >= static_cast<int>(attachments.size()))
        fail("parameter '" + path + "': no such attachment");
      if (n == 5 && parts[4] == "stiffness") {
        p.kind = SceneParameter::Kind::AttachmentStiffness;
        return p;
      }
      // The knot values of a handle's trajectory: the loader's keys (SceneLoader readTrajectory).
      const HandleTrajectory& trajectory = attachments[p.index].trajectory;
      const bool keyframe = n == 9 && parts[5] == "keyframes" && parts[7] == "offset";
      const bool hermite =
          n == 9 && parts[5] == "hermite" && (parts[6] == "points" || parts[6] == "tangents");
      if (parts[4] == "trajectory" && (keyframe || hermite)) {
        p.kind = keyframe || parts[6] == "points" ? SceneParameter::Kind::HandleOffset
                                                  : SceneParameter::Kind::HandleTangent;
        if (!parseIndex(parts[keyframe ? 6 : 7], p.knot) ||
            p.knot >= static_cast<int>(trajectory.times.size()))
          fail("parameter '" + path + "': no such knot");
        p.component = component(parts[n - 1]);
        return p;
      }
    }
  } else if (n >= 2 && parts[0] == "wind" && scene.wind) {
    if (n == 2 && parts[1] == "strength")
      p.kind = SceneParameter::Kind::WindStrength;
    else if (n == 2 && parts[1] == "frequency")
      p.kind = SceneParameter::Kind::WindFrequency;
    else if (n == 2 && parts[1] == "phase")
      p.kind = SceneParameter::Kind::WindPhase;
    else if (n == 3 && parts[1] == "direction") {
      p.kind = SceneParameter::Kind::WindDirection;
      p.component = component(parts[2]);
    } else {
      fail("parameter '" + path + "' is not differentiable; " + kSupported);
    }
    if (scene.wind->constant && (p.kind == SceneParameter::Kind::WindFrequency ||
                                 p.kind == SceneParameter::Kind::WindPhase))
      fail("parameter '" + path + "' has no effect: the wind model is \"constant\"");
    return p;
  } else if (n == 3 && parts[0] == "obstacles" && parts[2] == "friction") {
    // Contact friction: differentiated through the slip branch (ContactAdjoint).
    if (!parseIndex(parts[1], p.index) || p.index >= static_cast<int>(scene.obstacles.size()))
      fail("parameter '" + path + "': no such obstacle");
    p.kind = SceneParameter::Kind::ObstacleFriction;
    return p;
  } else if (n == 2 && parts[0] == "gravity" && scene.gravity) {
    p.kind = SceneParameter::Kind::Gravity;
    p.component = component(parts[1]);
    return p;
  }
  fail("parameter '" + path + "' is not differentiable; " + kSupported);
  return p;  // not reached
}

namespace {

// The typed scene's vector that holds a vector parameter's component (null for scalars); Scene or
// const Scene.
template <class SceneT>
auto vectorOf(SceneT& scene, const SceneParameter& p)
    -> decltype(&scene.cloths[0].initialVelocity) {
  using Kind = SceneParameter::Kind;
  switch (p.kind) {
    case Kind::InitialVelocity:
      return &scene.cloths[p.cloth].initialVelocity;
    case Kind::NodalForce:
      return &scene.cloths[p.cloth].forces[p.index].force;
    case Kind::WindDirection:
      return &scene.wind->direction;
    case Kind::Gravity:
      return &*scene.gravity;
    case Kind::HandleOffset:
      return &scene.cloths[p.cloth].attachments[p.index].trajectory.offsets[p.knot];
    case Kind::HandleTangent:
      return &scene.cloths[p.cloth].attachments[p.index].trajectory.tangents[p.knot];
    default:
      return nullptr;
  }
}

// The typed scene's number that holds the parameter; Scene or const Scene.
template <class SceneT>
auto scalarOf(SceneT& scene, const SceneParameter& p) -> decltype((scene.time.dt)) {
  using Kind = SceneParameter::Kind;
  switch (p.kind) {
    case Kind::Stretch:
      return scene.cloths[p.cloth].material.stretch;
    case Kind::Bend:
      return scene.cloths[p.cloth].material.bend;
    case Kind::Density:
      return scene.cloths[p.cloth].material.density;
    case Kind::WindStrength:
      return scene.wind->strength;
    case Kind::WindFrequency:
      return scene.wind->frequency;
    case Kind::WindPhase:
      return scene.wind->phase;
    case Kind::ObstacleFriction:
      return scene.obstacles[p.index].friction;
    case Kind::SelfCollisionFriction:
      return scene.cloths[p.cloth].selfCollision->friction;
    case Kind::AttachmentStiffness:
      return scene.cloths[p.cloth].attachments[p.index].stiffness;
    default:
      return (*vectorOf(scene, p))[p.component];
  }
}

// The JSON path of the vector a component path names ("gravity.1" -> "gravity").
std::string parentPath(const std::string& path) {
  return path.substr(0, path.rfind('.'));
}

}  // namespace

double parameterValue(const Scene& scene, const SceneParameter& parameter) {
  return scalarOf(scene, parameter);
}

void setParameterValue(Scene& scene, const SceneParameter& p, double value) {
  using Kind = SceneParameter::Kind;
  // The value is read back through the loader's own check of the node it would sit in.
  if (Vec3* vector = vectorOf(scene, p)) {
    nlohmann::json node = {(*vector)[0], (*vector)[1], (*vector)[2]};
    node[p.component] = value;
    const JsonReader reader(node, scene.file, parentPath(p.path));
    *vector = p.kind == Kind::WindDirection ? readWindDirection(reader) : reader.vec3();
  } else {
    const nlohmann::json node = value;
    const JsonReader reader(node, scene.file, p.path);
    double& slot = scalarOf(scene, p);
    switch (p.kind) {
      case Kind::Stretch:
      case Kind::Bend:
        slot = readStiffness(reader);
        break;
      case Kind::Density:
        slot = readDensity(reader);
        break;
      case Kind::WindStrength:
        slot = readWindStrength(reader);
        break;
      case Kind::WindFrequency:
        slot = readWindFrequency(reader);
        break;
      case Kind::WindPhase:
        slot = readWindPhase(reader);
        break;
      case Kind::ObstacleFriction:
      case Kind::SelfCollisionFriction:
        slot = readFriction(reader);
        break;
      case Kind::AttachmentStiffness:
        slot = readAttachmentStiffness(reader);
        break;
      default:
        break;
    }
  }
  const std::string err = setJsonPath(scene.document, p.path, value);
  if (!err.empty()) throw InputError(scene.file, p.path, err);
}

namespace {

void collectParameterPaths(const Scene& scene, const nlohmann::json& node, const std::string& path,
                           std::vector<std::string>& out) {
  if (node.is_number()) {
    // Resolving is the one definition of what is differentiable; a refusal just means "not one".
    try {
      resolveSceneParameter(scene, path, "");
      out.push_back(path);
    } catch (const InputError&) {
    }
    return;
  }
  const std::string prefix = path.empty() ? "" : path + ".";
  if (node.is_object()) {
    for (const auto& [key, child] : node.items())
      if (!(path.empty() && key == "task") && key != "mesh")
        collectParameterPaths(scene, child, prefix + key, out);
  } else if (node.is_array() && (node.size() <= 3 || !node[0].is_number())) {
    for (std::size_t i = 0; i < node.size(); ++i)
      collectParameterPaths(scene, node[i], prefix + std::to_string(i), out);
  }
}

}  // namespace

std::vector<std::string> differentiableParameterPaths(const Scene& scene) {
  std::vector<std::string> paths;
  collectParameterPaths(scene, scene.document, "", paths);
  return paths;
}

}  // namespace weft
