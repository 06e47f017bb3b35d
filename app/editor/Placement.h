#pragma once
// What placing things writes into the scene document: moving or turning an obstacle or a cloth
// (a gizmo drag), and a handle attachment's keyframes (set, delete). Plain JSON edits on the
// document's own numbers, so a drag along X changes only X components and everything else keeps
// its digits. No GL, no window: unit tested.

#include <weft/core/Types.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft::editor {

// What the gizmo places: an obstacle, a cloth (its mesh.transform), or a handle attachment (the
// offset keyed on the timeline).
struct EditorObject {
  enum class Kind { None, Obstacle, Cloth, Handle };
  Kind kind = Kind::None;
  int index = -1;       // obstacle or cloth
  int attachment = -1;  // handle: its index in cloth `index`'s attachments
  // "obstacles.N", "cloths.N", "cloths.N.attachments.M", or "" for none: the document path.
  std::string path() const;
  bool operator==(const EditorObject& o) const {
    return kind == o.kind && index == o.index && attachment == o.attachment;
  }
  bool operator!=(const EditorObject& o) const { return !(*this == o); }
};

// The object at `path` of `document` ("" is none). Returns an error text when the path names
// nothing the gizmo places (no such entry, or an attachment that is not a handle).
std::string findEditorObject(const nlohmann::json& document, const std::string& path,
                             EditorObject& object);

// The shape key of an obstacle entry ("plane", "sphere", ..., "mesh"), "" when it has none.
std::string obstacleShape(const nlohmann::json& obstacle);
// Whether the gizmo turns it: every obstacle but a sphere, and cloths. Handles only translate
// (the trajectory's offset is a translation).
bool objectRotates(const nlohmann::json& document, const EditorObject& object);

// Moves an obstacle entry or a cloth entry by `delta` metres along world axis `axis` (0, 1, 2):
// a plane's point, a sphere's or box's center, both ends of a capsule or cylinder, a mesh's or
// cloth's mesh.transform.translate (created when absent). Only that component changes.
void translateObject(nlohmann::json& entry, EditorObject::Kind kind, int axis, double delta);
// Turns it by `radians` about world axis `axis` through `centre`: a plane's normal, a capsule's or
// cylinder's ends, a box's rotate_deg, a mesh's or cloth's mesh.transform (rotate_deg, and
// translate so that `centre` stays put). A sphere does not turn.
void rotateObject(nlohmann::json& entry, EditorObject::Kind kind, int axis, double radians,
                  const Vec3& centre);

// A handle's keys: keyframes {time, offset}, or a Hermite spline's knots (time, point).
struct HandleKey {
  double time = 0.0;
  Vec3 offset = Vec3::Zero();
};
std::vector<HandleKey> handleKeys(const nlohmann::json& attachment);
// True when the handle's path is keyframes (the editor edits those; a Hermite spline is edited
// in the file, where its tangents are).
bool hasKeyframes(const nlohmann::json& attachment);
// Sets the key at `time`: replaces a key less than `tolerance` from it (the nearest), or inserts
// one in time order. Creates trajectory.keyframes when the trajectory has none (and no spline).
void setHandleKey(nlohmann::json& attachment, double time, const Vec3& offset, double tolerance);
// Removes the key nearest `time` within `tolerance`; false when there is none there.
bool deleteHandleKey(nlohmann::json& attachment, double time, double tolerance);

// A handle attachment of cloth-local `vertices` that holds still until keyed: one key at t = 0
// with zero offset (the loader needs one, and a first key later would make it jump at t = 0).
nlohmann::json newHandleAttachment(const std::vector<int>& vertices);

}  // namespace weft::editor
