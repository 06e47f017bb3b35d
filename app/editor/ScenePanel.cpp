#include "ScenePanel.h"

#include "EditorApp.h"
#include "EditorSession.h"
#include "ObstacleTemplates.h"
#include "PinGroups.h"
#include "SelfCollisionChoice.h"

#include <weft/render/ColorMap.h>

#include <imgui.h>

#include <algorithm>

namespace weft::editor {

ScenePanel::ScenePanel(EditorSession& session, EditorApp& app)
    : session_(session), app_(app), fields_(session, app) {}

void ScenePanel::draw() {
  if (ImGui::CollapsingHeader("Time step and solver", ImGuiTreeNodeFlags_DefaultOpen)) timePanel();
  if (ImGui::CollapsingHeader("Cloth and material", ImGuiTreeNodeFlags_DefaultOpen)) clothPanel();
  if (ImGui::CollapsingHeader("Gravity and wind")) effectsPanel();
  if (ImGui::CollapsingHeader("Obstacles")) obstaclePanel();
  if (ImGui::CollapsingHeader("Selection", ImGuiTreeNodeFlags_DefaultOpen)) selectionPanel();
}

void ScenePanel::timePanel() {
  fields_.number("dt (s)", "time.dt", 0.01);
  fields_.integer("steps", "time.steps", 100);
  static const char* methods[] = {"newton", "pd"};
  fields_.combo("method", "solver.method", methods, 2, "newton");
  fields_.integer("PD iterations", "solver.pd_iterations", 100);
  fields_.number("PD tolerance (m/s^2)", "solver.pd_tolerance", 1e-4);
  static const char* accelerations[] = {"anderson", "none"};
  fields_.combo("acceleration", "solver.acceleration", accelerations, 2, "anderson");
}

void ScenePanel::clothPanel() {
  // Copies, here and below: a field edit replaces the document, and a pointer into it would
  // dangle for the rows drawn after the edit.
  const nlohmann::json* found = session_.document().find("cloths");
  const nlohmann::json clothList = found ? *found : nlohmann::json();
  const nlohmann::json* cloths = &clothList;
  if (!cloths->is_array()) {
    ImGui::TextDisabled("no cloths");
    return;
  }
  for (std::size_t c = 0; c < cloths->size(); ++c) {
    const std::string base = "cloths." + std::to_string(c);
    ImGui::PushID(int(c));
    const bool open = ImGui::TreeNodeEx("cloth", ImGuiTreeNodeFlags_DefaultOpen, "Cloth %zu", c);
    ImGui::SameLine();
    placeButton(base);
    ImGui::SameLine();
    if (ImGui::SmallButton("remove")) {
      // The cloths after it are numbered down, and `cloths` changes: stop drawing this frame.
      fields_.apply(session_.document().removeValue(base));
      if (open) ImGui::TreePop();
      ImGui::PopID();
      return;
    }
    if (open) {
      static const double zero[3] = {0, 0, 0};
      if (const nlohmann::json* file = session_.document().find(base + ".mesh.file")) {
        ImGui::TextDisabled("mesh: %s", file->is_string() ? file->get<std::string>().c_str() : "?");
        fields_.number("scale", base + ".mesh.scale", 1.0);
      } else if (session_.document().find(base + ".mesh.grid")) {
        const nlohmann::json* size = session_.document().find(base + ".mesh.grid.size");
        const nlohmann::json* res = session_.document().find(base + ".mesh.grid.resolution");
        ImGui::TextDisabled("grid %s m, %s quads", size ? size->dump().c_str() : "?",
                            res ? res->dump().c_str() : "?");
      }
      if (ImGui::TreeNode("placement", "placement (mesh.transform)")) {
        fields_.vector("rotate (deg)", base + ".mesh.transform.rotate_deg", zero);
        fields_.vector("translate (m)", base + ".mesh.transform.translate", zero);
        ImGui::TreePop();
      }
      fields_.number("density (kg/m^2)", base + ".material.density", 0.1);
      fields_.number("stretch (N/m)", base + ".material.stretch", 100.0);
      fields_.number("bend (N m)", base + ".material.bend", 0.0);
      const nlohmann::json* selfCollision = session_.document().find(base + ".self_collision");
      const SelfCollisionChoice choice = selfCollisionChoice(selfCollision);
      int chosen = static_cast<int>(choice);
      if (ImGui::Combo("self-collision", &chosen, kSelfCollisionChoiceLabels,
                       IM_ARRAYSIZE(kSelfCollisionChoiceLabels)) &&
          chosen != static_cast<int>(choice)) {
        fields_.apply(chooseSelfCollision(session_.document(), static_cast<int>(c),
                                          static_cast<SelfCollisionChoice>(chosen)));
      }
      if (choice == SelfCollisionChoice::Node || choice == SelfCollisionChoice::Both) {
        fields_.number("radius (m)", base + ".self_collision.radius", 0.004);
        fields_.number("friction", base + ".self_collision.friction", 0.3);
      }
      if (choice == SelfCollisionChoice::ImpactZones || choice == SelfCollisionChoice::Both)
        fields_.number("thickness (m)##self", base + ".self_collision.thickness", 0.001);
      const nlohmann::json* listed = session_.document().find(base + ".attachments");
      const nlohmann::json attachmentList = listed ? *listed : nlohmann::json();
      const nlohmann::json* attachments = &attachmentList;
      if (attachments->is_array()) {
        // Pin groups: each fixed attachment with its marker colour (as the viewport draws it),
        // a name, its size, and buttons to select or remove it.
        const Scene* scene = session_.document().scene();
        const std::vector<PinGroup> groups = scene ? pinGroups(*scene) : std::vector<PinGroup>();
        for (std::size_t a = 0; a < attachments->size(); ++a) {
          const nlohmann::json& at = (*attachments)[a];
          const std::string path = base + ".attachments." + std::to_string(a);
          const std::size_t n =
              at.contains("vertices") && at["vertices"].is_array() ? at["vertices"].size() : 0;
          const std::string kind = at.value("kind", std::string("fixed"));
          ImGui::PushID(int(a));
          if (kind == "handle") {
            ImGui::Text("handle %zu: %zu vertices", a, n);
            ImGui::SameLine();
            placeButton(path);
          } else {
            const auto group = std::find_if(groups.begin(), groups.end(), [&](const PinGroup& g) {
              return g.cloth == int(c) && g.attachment == int(a);
            });
            const render::Rgb rgb =
                pinGroupColor(group != groups.end() ? group->group : 0, app_.style());
            ImGui::ColorButton("##colour", ImVec4(rgb.x(), rgb.y(), rgb.z(), 1.0f),
                               ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop,
                               ImVec2(14, 14));
            ImGui::SameLine();
            ImGui::SetNextItemWidth(110.0f);
            const std::string hint = "pin group " + std::to_string(a);
            fields_.text("##name", path + ".name", hint.c_str());
            ImGui::SameLine();
            ImGui::Text("%zu vertices", n);
            ImGui::SameLine();
            if (ImGui::SmallButton("select") && group != groups.end())
              session_.selection().set(group->nodes);
            app_.noteLastItem("pins:select:" + path);
          }
          ImGui::SameLine();
          const bool remove = ImGui::SmallButton("remove");
          app_.noteLastItem("pins:remove:" + path);
          ImGui::PopID();
          if (remove) {
            // The attachments after it are numbered down: stop listing them this frame.
            fields_.apply(session_.document().removeValue(path));
            break;
          }
        }
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void ScenePanel::effectsPanel() {
  EditorDocument& doc = session_.document();
  bool gravity = doc.find("gravity") != nullptr;
  if (ImGui::Checkbox("gravity", &gravity)) {
    fields_.apply(gravity ? doc.setValue("gravity", nlohmann::json::array({0.0, -9.8, 0.0}))
                          : doc.removeValue("gravity"));
  }
  if (doc.find("gravity")) {
    static const double g[3] = {0.0, -9.8, 0.0};
    fields_.vector("g (m/s^2)", "gravity", g);
  }
  bool wind = doc.find("wind") != nullptr;
  if (ImGui::Checkbox("wind", &wind)) {
    fields_.apply(wind ? doc.setValue("wind", {{"direction", {1.0, 0.0, 0.0}},
                                               {"strength", 1.0},
                                               {"frequency", 1.0},
                                               {"phase", 0.0}})
                       : doc.removeValue("wind"));
  }
  if (doc.find("wind")) {
    static const double x[3] = {1.0, 0.0, 0.0};
    fields_.vector("direction", "wind.direction", x);
    // With a falloff centre (DiffCloth Eq. 35) the per-vertex factor is an inverse distance (1/m)
    // instead of an area (m^2), so strength is in N m instead of a pressure.
    const bool falloff = doc.find("wind.falloff") != nullptr;
    fields_.number(falloff ? "strength (N m, falloff)" : "strength (N/m^2)", "wind.strength", 0.0);
    if (falloff) {
      static const double origin[3] = {0.0, 0.0, 0.0};
      fields_.vector("falloff centre (m)", "wind.falloff.center", origin);
    }
    fields_.number("frequency (Hz)", "wind.frequency", 0.0);
    fields_.number("phase (rad)", "wind.phase", 0.0);
    static const char* models[] = {"sinusoid", "constant"};
    fields_.combo("model", "wind.model", models, 2, "sinusoid");
  }
  ImGui::TextDisabled("Adding or removing an effect adds or removes its module.");
}

void ScenePanel::obstaclePanel() {
  EditorDocument& doc = session_.document();
  // A copy, as in clothPanel: a field edit replaces the document.
  const nlohmann::json* found = doc.find("obstacles");
  const nlohmann::json obstacleList = found ? *found : nlohmann::json();
  const nlohmann::json* obstacles = &obstacleList;
  const std::size_t count = obstacles && obstacles->is_array() ? obstacles->size() : 0;
  for (std::size_t i = 0; i < count; ++i) {
    const nlohmann::json& o = (*obstacles)[i];
    std::string shape = "?";
    for (const char* s : {"plane", "sphere", "capsule", "box", "cylinder", "mesh"})
      if (o.contains(s)) shape = s;
    const std::string base = "obstacles." + std::to_string(i);
    ImGui::PushID(int(i));
    const bool open =
        ImGui::TreeNodeEx("obstacle", ImGuiTreeNodeFlags_DefaultOpen, "%zu: %s", i, shape.c_str());
    ImGui::SameLine();
    placeButton(base);
    ImGui::SameLine();
    bool removed = false;
    if (ImGui::SmallButton("remove")) {
      fields_.apply(doc.removeValue(base));
      removed = true;
    }
    if (open) {
      if (!removed) {
        static const double zero[3] = {0, 0, 0}, up[3] = {0, 1, 0}, one[3] = {1, 1, 1};
        const std::string s = base + "." + shape;
        if (shape == "plane") {
          fields_.vector("point", s + ".point", zero);
          fields_.vector("normal", s + ".normal", up);
        } else if (shape == "sphere") {
          fields_.vector("center", s + ".center", zero);
          fields_.number("radius", s + ".radius", 0.3);
        } else if (shape == "capsule" || shape == "cylinder") {
          fields_.vector("a", s + ".a", zero);
          fields_.vector("b", s + ".b", up);
          fields_.number("radius", s + ".radius", 0.1);
        } else if (shape == "box") {
          fields_.vector("center", s + ".center", zero);
          fields_.vector("size", s + ".size", one);
          fields_.vector("rotate (deg)", s + ".rotate_deg", zero);
        } else if (shape == "mesh") {
          const nlohmann::json* file = doc.find(s + ".file");
          ImGui::TextDisabled("mesh file: %s",
                              file && file->is_string() ? file->get<std::string>().c_str() : "?");
          fields_.number("scale", s + ".scale", 1.0);
          fields_.vector("rotate (deg)", s + ".transform.rotate_deg", zero);
          fields_.vector("translate (m)", s + ".transform.translate", zero);
        }
        fields_.number("friction", base + ".friction", 0.0);
        fields_.number("thickness (m)", base + ".thickness", 1e-3);
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
    if (removed) break;  // indices shifted; the list is drawn again next frame
  }
  ImGui::TextUnformatted("Add:");
  for (const std::string& shape : analyticObstacleShapes()) {
    ImGui::SameLine();
    if (ImGui::SmallButton(shape.c_str()))
      fields_.apply(session_.additions().addObstacle(shape, session_.selection().nodes()));
  }
  ImGui::SameLine();
  if (ImGui::SmallButton("mesh...")) app_.openImport(MeshImportDialog::Kind::Obstacle);
}

void ScenePanel::placeButton(const std::string& path) {
  // Toggles which object the viewport's gizmo places; the active one's button is orange (one
  // label for both states keeps the attachment rows inside the panel).
  const bool active = session_.placement().activeObject().path() == path;
  ImGui::PushID(("place " + path).c_str());
  if (active) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.85f, 0.60f, 0.10f, 1.0f));
  if (ImGui::SmallButton("gizmo")) {
    const std::string error = session_.placement().setActiveObject(active ? "" : path);
    if (!error.empty()) app_.report(error, true);
  }
  if (active) ImGui::PopStyleColor();
  ImGui::PopID();
}

void ScenePanel::selectionPanel() {
  const auto& nodes = session_.selection().nodes();
  ImGui::Text("%zu vertices selected", nodes.size());
  if (!nodes.empty()) {
    std::string list;
    for (std::size_t i = 0; i < nodes.size() && i < 24; ++i)
      list += (i ? ", " : "") + std::to_string(nodes[i]);
    if (nodes.size() > 24) list += ", ...";
    ImGui::TextWrapped("%s", list.c_str());
  }
  ImGui::BeginDisabled(nodes.empty() || !session_.document().valid());
  if (ImGui::Button("Pin selection")) {
    const std::string error = session_.selecting().pinSelection();
    app_.report(error.empty() ? "pinned " + std::to_string(nodes.size()) + " vertices" : error,
                !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Make handle")) {
    const std::string error = session_.selecting().makeHandle();
    app_.report(error.empty()
                    ? "made a handle of " + std::to_string(nodes.size()) +
                          " vertices: drag it with the gizmo, then Set key on the timeline"
                    : error,
                !error.empty());
  }
  ImGui::SameLine();
  if (ImGui::Button("Clear")) session_.selection().clear();
  ImGui::EndDisabled();
  // By region: the border loop through the inspected vertex, or a band along an axis.
  ImGui::BeginDisabled(session_.selection().focus() < 0);
  if (ImGui::Button("Select its border loop")) {
    const std::string error = session_.selecting().selectBoundaryLoop(ImGui::GetIO().KeyShift);
    app_.report(error.empty()
                    ? "selected the border loop: " + std::to_string(nodes.size()) + " vertices"
                    : error,
                !error.empty());
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("The border (waist, hem, cuff) through the vertex last clicked; Shift adds.");
  static const char* axes[] = {"x", "y", "z"};
  ImGui::SetNextItemWidth(50.0f);
  ImGui::Combo("##band axis", &bandAxis_, axes, 3);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(150.0f);
  ImGui::InputScalarN("##band", ImGuiDataType_Double, band_, 2, nullptr, nullptr, "%.3f");
  ImGui::SameLine();
  ImGui::BeginDisabled(!session_.document().valid());
  if (ImGui::Button("Select band")) {
    const std::string error =
        session_.selecting().selectBand(bandAxis_, band_[0], band_[1], ImGui::GetIO().KeyShift);
    app_.report(error.empty() ? "selected " + std::to_string(nodes.size()) + " vertices in the band"
                              : error,
                !error.empty());
  }
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(
        "The vertices whose coordinate (as shown) lies between the two values, in metres; Shift "
        "adds.");
  ImGui::TextDisabled("Click: pick (and inspect) a vertex; drag: box");
  ImGui::TextDisabled("select; Shift adds. Right drag: orbit; middle:");
  ImGui::TextDisabled("pan; wheel: zoom; F: frame the scene; Alt+drag:");
  ImGui::TextDisabled("move the selected vertices' targets. Ctrl+click");
  ImGui::TextDisabled("an obstacle or cloth (or \"gizmo\" under");
  ImGui::TextDisabled("Obstacles, Cloth) to place it: drag the");
  ImGui::TextDisabled("gizmo's arrows and rings; Esc takes it off.");
}

}  // namespace weft::editor
