#include "Placement.h"

#include "Gizmo.h"

#include <weft/mesh/RigidTransform.h>
#include <weft/scene/JsonPath.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace weft::editor {
namespace {

Vec3 vec3At(const nlohmann::json& entry, const char* key, const Vec3& fallback) {
  if (!entry.contains(key)) return fallback;
  const nlohmann::json& v = entry.at(key);
  if (!v.is_array() || v.size() != 3)
    throw std::invalid_argument(std::string(key) + " must be [x, y, z]");
  return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

nlohmann::json array3(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

// Adds `delta` to component `axis` of the [x, y, z] at `key` ([0, 0, 0] when absent), leaving
// the other two components exactly as they were.
void shiftComponent(nlohmann::json& entry, const char* key, int axis, double delta) {
  if (!entry.contains(key)) entry[key] = nlohmann::json::array({0.0, 0.0, 0.0});
  nlohmann::json& v = entry[key];
  if (!v.is_array() || v.size() != 3 || !v[std::size_t(axis)].is_number())
    throw std::invalid_argument(std::string(key) + " must be [x, y, z]");
  v[std::size_t(axis)] = v[std::size_t(axis)].get<double>() + delta;
}

// The transform of a mesh (a cloth's mesh, or a mesh obstacle) turned by `q` about `centre`:
// Q (R x + t - c) + c = (Q R) x + Q (t - c) + c, with the scale inside R x unchanged.
void rotateTransform(nlohmann::json& mesh, const Mat3& q, const Vec3& centre) {
  if (!mesh.contains("transform")) mesh["transform"] = nlohmann::json::object();
  nlohmann::json& transform = mesh["transform"];
  RigidTransform t;
  t.rotateDeg = vec3At(transform, "rotate_deg", Vec3::Zero());
  t.translate = vec3At(transform, "translate", Vec3::Zero());
  transform["rotate_deg"] = array3(eulerXyzDegrees(q * t.rotation(), t.rotateDeg));
  transform["translate"] = array3(q * (t.translate - centre) + centre);
}

nlohmann::json& keyframeList(nlohmann::json& attachment) {
  nlohmann::json& trajectory = attachment["trajectory"];
  if (!trajectory.is_object()) trajectory = nlohmann::json::object();
  if (trajectory.contains("hermite"))
    throw std::invalid_argument(
        "this handle follows a Hermite spline: edit its knots and tangents in the scene file");
  if (!trajectory.contains("keyframes") || !trajectory["keyframes"].is_array())
    trajectory["keyframes"] = nlohmann::json::array();
  return trajectory["keyframes"];
}

}  // namespace

std::string EditorObject::path() const {
  switch (kind) {
    case Kind::None:
      return "";
    case Kind::Obstacle:
      return "obstacles." + std::to_string(index);
    case Kind::Cloth:
      return "cloths." + std::to_string(index);
    case Kind::Handle:
      return "cloths." + std::to_string(index) + ".attachments." + std::to_string(attachment);
  }
  return "";
}

std::string findEditorObject(const nlohmann::json& document, const std::string& path,
                             EditorObject& object) {
  if (path.empty()) {
    object = EditorObject();
    return "";
  }
  const std::vector<std::string> parts = splitJsonPath(path);
  auto index = [](const std::string& text) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoi(text);
  };
  EditorObject found;
  if (parts.size() == 2 && parts[0] == "obstacles")
    found = {EditorObject::Kind::Obstacle, index(parts[1]), -1};
  else if (parts.size() == 2 && parts[0] == "cloths")
    found = {EditorObject::Kind::Cloth, index(parts[1]), -1};
  else if (parts.size() == 4 && parts[0] == "cloths" && parts[2] == "attachments")
    found = {EditorObject::Kind::Handle, index(parts[1]), index(parts[3])};
  else
    return path + ": the gizmo places obstacles.N, cloths.N and cloths.N.attachments.M (a handle)";
  const nlohmann::json* entry = findJsonPath(document, path);
  if (found.index < 0 || (found.kind == EditorObject::Kind::Handle && found.attachment < 0) ||
      !entry || !entry->is_object())
    return path + ": there is no such entry in the scene";
  if (found.kind == EditorObject::Kind::Handle &&
      entry->value("kind", std::string("fixed")) != "handle")
    return path + ": a fixed attachment does not move (only a handle, kind \"handle\", has keys)";
  object = found;
  return "";
}

std::string obstacleShape(const nlohmann::json& obstacle) {
  for (const char* s : {"plane", "sphere", "capsule", "box", "cylinder", "mesh"})
    if (obstacle.is_object() && obstacle.contains(s)) return s;
  return "";
}

bool objectRotates(const nlohmann::json& document, const EditorObject& object) {
  if (object.kind == EditorObject::Kind::Cloth) return true;
  if (object.kind != EditorObject::Kind::Obstacle) return false;
  const nlohmann::json* entry = findJsonPath(document, object.path());
  const std::string shape = entry ? obstacleShape(*entry) : "";
  return !shape.empty() && shape != "sphere";
}

void translateObject(nlohmann::json& entry, EditorObject::Kind kind, int axis, double delta) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("axis must be 0, 1 or 2");
  if (kind == EditorObject::Kind::Cloth) {
    nlohmann::json& mesh = entry.at("mesh");
    if (!mesh.contains("transform")) mesh["transform"] = nlohmann::json::object();
    shiftComponent(mesh["transform"], "translate", axis, delta);
    return;
  }
  if (kind != EditorObject::Kind::Obstacle)
    throw std::invalid_argument("only obstacles and cloths move as a whole");
  const std::string shape = obstacleShape(entry);
  nlohmann::json& s = entry.at(shape);
  if (shape == "plane")
    shiftComponent(s, "point", axis, delta);
  else if (shape == "sphere" || shape == "box")
    shiftComponent(s, "center", axis, delta);
  else if (shape == "capsule" || shape == "cylinder")
    shiftComponent(s, "a", axis, delta), shiftComponent(s, "b", axis, delta);
  else if (shape == "mesh") {
    if (!s.contains("transform")) s["transform"] = nlohmann::json::object();
    shiftComponent(s["transform"], "translate", axis, delta);
  } else {
    throw std::invalid_argument("the obstacle has no shape");
  }
}

void rotateObject(nlohmann::json& entry, EditorObject::Kind kind, int axis, double radians,
                  const Vec3& centre) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("axis must be 0, 1 or 2");
  const Mat3 q = Eigen::AngleAxisd(radians, Vec3::Unit(axis)).toRotationMatrix();
  if (kind == EditorObject::Kind::Cloth) return rotateTransform(entry.at("mesh"), q, centre);
  if (kind != EditorObject::Kind::Obstacle)
    throw std::invalid_argument("only obstacles and cloths turn");
  const std::string shape = obstacleShape(entry);
  nlohmann::json& s = entry.at(shape);
  if (shape == "plane") {
    s["normal"] = array3(q * vec3At(s, "normal", Vec3::UnitY()));
    s["point"] = array3(q * (vec3At(s, "point", Vec3::Zero()) - centre) + centre);
  } else if (shape == "capsule" || shape == "cylinder") {
    s["a"] = array3(q * (vec3At(s, "a", Vec3::Zero()) - centre) + centre);
    s["b"] = array3(q * (vec3At(s, "b", Vec3::Zero()) - centre) + centre);
  } else if (shape == "box") {
    RigidTransform t;
    t.rotateDeg = vec3At(s, "rotate_deg", Vec3::Zero());
    s["rotate_deg"] = array3(eulerXyzDegrees(q * t.rotation(), t.rotateDeg));
    s["center"] = array3(q * (vec3At(s, "center", Vec3::Zero()) - centre) + centre);
  } else if (shape == "mesh") {
    rotateTransform(s, q, centre);
  } else if (shape != "sphere") {
    throw std::invalid_argument("the obstacle has no shape");
  }
}

std::vector<HandleKey> handleKeys(const nlohmann::json& attachment) {
  std::vector<HandleKey> keys;
  if (!attachment.is_object() || !attachment.contains("trajectory")) return keys;
  const nlohmann::json& trajectory = attachment["trajectory"];
  auto vec = [](const nlohmann::json& v) {
    return v.is_array() && v.size() == 3 && v[0].is_number() && v[1].is_number() && v[2].is_number()
               ? Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>())
               : Vec3(Vec3::Zero());
  };
  if (trajectory.contains("keyframes") && trajectory["keyframes"].is_array()) {
    for (const nlohmann::json& k : trajectory["keyframes"])
      if (k.is_object() && k.contains("time") && k["time"].is_number())
        keys.push_back({k["time"].get<double>(),
                        k.contains("offset") ? vec(k["offset"]) : Vec3(Vec3::Zero())});
  } else if (trajectory.contains("hermite") && trajectory["hermite"].is_object()) {
    const nlohmann::json& h = trajectory["hermite"];
    const nlohmann::json times = h.value("times", nlohmann::json::array());
    const nlohmann::json points = h.value("points", nlohmann::json::array());
    for (std::size_t i = 0; i < times.size(); ++i)
      if (times[i].is_number())
        keys.push_back(
            {times[i].get<double>(), i < points.size() ? vec(points[i]) : Vec3(Vec3::Zero())});
  }
  return keys;
}

bool hasKeyframes(const nlohmann::json& attachment) {
  return attachment.is_object() && attachment.contains("trajectory") &&
         attachment["trajectory"].is_object() && !attachment["trajectory"].contains("hermite");
}

void setHandleKey(nlohmann::json& attachment, double time, const Vec3& offset, double tolerance) {
  nlohmann::json& keys = keyframeList(attachment);
  const nlohmann::json key = {{"time", time}, {"offset", array3(offset)}};
  std::size_t nearest = keys.size(), insertAt = keys.size();
  double best = tolerance;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const double t = keys[i].value("time", 0.0);
    if (std::abs(t - time) < best) best = std::abs(t - time), nearest = i;
    if (insertAt == keys.size() && t > time) insertAt = i;
  }
  if (nearest < keys.size()) {
    // The key keeps its own time (a file's key between two frames stays where it was).
    keys[nearest]["offset"] = array3(offset);
    return;
  }
  keys.insert(keys.begin() + std::ptrdiff_t(insertAt), key);
}

bool deleteHandleKey(nlohmann::json& attachment, double time, double tolerance) {
  nlohmann::json& keys = keyframeList(attachment);
  std::size_t nearest = keys.size();
  double best = tolerance;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const double d = std::abs(keys[i].value("time", 0.0) - time);
    if (d < best) best = d, nearest = i;
  }
  if (nearest == keys.size()) return false;
  keys.erase(keys.begin() + std::ptrdiff_t(nearest));
  return true;
}

nlohmann::json newHandleAttachment(const std::vector<int>& vertices) {
  return {{"vertices", vertices},
          {"kind", "handle"},
          {"trajectory",
           {{"keyframes", nlohmann::json::array({{{"time", 0.0}, {"offset", {0.0, 0.0, 0.0}}}})}}}};
}

}  // namespace weft::editor
