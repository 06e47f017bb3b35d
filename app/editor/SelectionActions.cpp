#include "SelectionActions.h"

#include "ClothNodes.h"
#include "ObjectPicking.h"

#include <weft/mesh/BoundaryLoops.h>

#include <algorithm>

namespace weft::editor {

SelectionActions::SelectionActions(EditorDocument& document, Selection& selection,
                                   ViewportFrame& viewport, const render::Camera& camera,
                                   ObjectPlacement& placement)
    : document_(document),
      selection_(selection),
      viewport_(viewport),
      camera_(camera),
      placement_(placement) {}

std::string SelectionActions::selectNodes(const std::vector<int>& nodes, bool add) {
  const Scene* scene = viewport_.lastValidScene().get();
  const int count = scene ? scene->vertexCount() : 0;
  for (int n : nodes)
    if (n < 0 || n >= count)
      return "vertex " + std::to_string(n) + " is not a cloth vertex (the scene has " +
             std::to_string(count) + ")";
  if (add)
    selection_.add(nodes);
  else
    selection_.set(nodes);
  return "";
}

std::optional<int> SelectionActions::clickSelect(float x, float y, int width, int height,
                                                 bool add) {
  const render::RenderScene* scene = viewport_.scene();
  if (!scene) return std::nullopt;
  const auto vertex = pickVertex(scene->cloth, pixelRay(camera_, x, y, width, height));
  if (!add) selection_.clear();
  if (vertex) {
    if (add)
      selection_.toggle(*vertex);
    else
      selection_.set({*vertex});
  }
  return vertex;
}

void SelectionActions::boxSelectPixels(float x0, float y0, float x1, float y1, int width,
                                       int height, bool add) {
  const render::RenderScene* scene = viewport_.scene();
  if (!scene) return;
  const auto inside = boxSelect(scene->cloth, camera_, {x0, y0}, {x1, y1}, width, height);
  if (add)
    selection_.add(inside);
  else
    selection_.set(inside);
}

std::string SelectionActions::selectBoundaryLoop(bool add) {
  const int node = selection_.focus();
  if (node < 0) return "click a vertex on the border first (its loop is selected)";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel& model = *document_.cloth();
  const int cloth = clothOfNode(model.vertexOffset, node);
  if (cloth < 0) return "vertex " + std::to_string(node) + " is not a cloth vertex";
  const int offset = model.vertexOffset[std::size_t(cloth)];
  for (const std::vector<int>& loop : boundaryLoops(scene->cloths[std::size_t(cloth)].mesh)) {
    if (std::find(loop.begin(), loop.end(), node - offset) == loop.end()) continue;
    std::vector<int> nodes;
    for (int v : loop) nodes.push_back(v + offset);
    if (add)
      selection_.add(nodes);
    else
      selection_.set(nodes);
    return "";
  }
  return "vertex " + std::to_string(node) + " is not on a border of its cloth";
}

std::string SelectionActions::selectBand(int axis, double low, double high, bool add) {
  if (axis < 0 || axis > 2) return "the axis is x, y or z";
  if (!(low <= high)) return "the band's low end is above its high end";
  const render::RenderScene* shown = viewport_.scene();
  if (!shown) return "the scene does not validate: " + document_.validationError();
  std::vector<int> nodes;
  const auto& positions = shown->cloth.positions;
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    if (positions(v, axis) >= low && positions(v, axis) <= high) nodes.push_back(int(v));
  if (add)
    selection_.add(nodes);
  else
    selection_.set(nodes);
  return "";
}

std::string SelectionActions::pinSelection() {
  if (selection_.empty()) return "nothing is selected";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel& model = *document_.cloth();
  const std::vector<int> nodes = selection_.nodes();
  return document_.edit(
      "Pin " + std::to_string(nodes.size()) + " vertices",
      [&](nlohmann::json& doc) { addFixedAttachments(doc, nodes, model.vertexOffset); });
}

std::string SelectionActions::makeHandle() {
  if (selection_.empty()) return "select the vertices the handle holds first";
  const Scene* scene = document_.scene();
  if (!scene) return "the scene does not validate: " + document_.validationError();
  const ClothModel& model = *document_.cloth();
  const std::vector<int> nodes = selection_.nodes();
  const int cloth = clothOfNode(model.vertexOffset, nodes.front());
  if (cloth < 0 || clothOfNode(model.vertexOffset, nodes.back()) < 0)
    return "the selection is not cloth vertices";
  if (clothOfNode(model.vertexOffset, nodes.back()) != cloth)
    return "a handle holds vertices of one cloth: select vertices of one cloth only";
  std::vector<int> local;
  for (int n : nodes) local.push_back(n - model.vertexOffset[std::size_t(cloth)]);
  const std::string base = "cloths." + std::to_string(cloth);
  const nlohmann::json* attachments = document_.find(base + ".attachments");
  const int index = attachments && attachments->is_array() ? int(attachments->size()) : 0;
  const std::string error = document_.edit(
      "Make a handle of " + std::to_string(nodes.size()) + " vertices", [&](nlohmann::json& doc) {
        nlohmann::json& c = doc.at("cloths").at(std::size_t(cloth));
        if (!c.contains("attachments")) c["attachments"] = nlohmann::json::array();
        c["attachments"].push_back(newHandleAttachment(local));
      });
  if (!error.empty()) return error;
  return placement_.setActiveObject(base + ".attachments." + std::to_string(index));
}

}  // namespace weft::editor
