// Script commands that add to the scene: a garment or an obstacle from a mesh file, an analytic
// obstacle.
#include "EditorSession.h"
#include "ScriptCommands.h"

namespace weft::editor {
namespace {

// The import options an action names (every key but the file is optional).
MeshImportOptions importOptions(const nlohmann::json& a, const std::string& kind) {
  MeshImportOptions o;
  o.file = a.at(kind).get<std::string>();
  o.scale = a.value("scale", 1.0);
  if (a.contains("fit")) {
    o.fit = true;
    o.fitSize = a["fit"].get<double>();
  }
  if (a.contains("rotate_deg")) o.rotateDeg = vec3Of(a["rotate_deg"], "rotate_deg");
  if (a.contains("translate")) o.translate = vec3Of(a["translate"], "translate");
  o.repair = a.value("repair", false);
  o.smoothNormals = a.value("smooth_normals", true);
  return o;
}

bool importGarment(ScriptCall& call) {
  const std::string error =
      call.session.additions().importGarment(importOptions(call.action, call.kind));
  return call.reportOutcome(error, "imported " + call.action[call.kind].get<std::string>());
}

bool addMeshObstacle(ScriptCall& call) {
  const std::string error =
      call.session.additions().importMeshObstacle(importOptions(call.action, call.kind));
  return call.reportOutcome(error,
                            "added mesh obstacle " + call.action[call.kind].get<std::string>());
}

bool addObstacle(ScriptCall& call) {
  const std::string error = call.session.additions().addObstacle(
      call.action.at(call.kind).get<std::string>(), call.session.selection().nodes());
  return call.reportOutcome(error, call.kind + " done");
}

}  // namespace

void addSceneCommands(ScriptCommandTable& table) {
  table["import_garment"] = importGarment;
  table["add_mesh_obstacle"] = addMeshObstacle;
  table["add_obstacle"] = addObstacle;
}

}  // namespace weft::editor
