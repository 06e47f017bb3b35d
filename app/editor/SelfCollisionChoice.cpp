#include "SelfCollisionChoice.h"

#include "EditorDocument.h"

#include <string>

namespace weft::editor {

namespace {

bool names(const nlohmann::json& model, const char* which) {
  if (model.is_string()) return model.get<std::string>() == which;
  if (model.is_array())
    for (const nlohmann::json& m : model)
      if (m.is_string() && m.get<std::string>() == which) return true;
  return false;
}

}  // namespace

SelfCollisionChoice selfCollisionChoice(const nlohmann::json* selfCollision) {
  if (!selfCollision || selfCollision->is_null()) return SelfCollisionChoice::None;
  if (!selfCollision->is_object() || !selfCollision->contains("model"))
    return SelfCollisionChoice::Node;  // the default model
  const nlohmann::json& model = (*selfCollision)["model"];
  const bool node = names(model, "node"), zones = names(model, "impact_zones");
  if (node && zones) return SelfCollisionChoice::Both;
  return zones ? SelfCollisionChoice::ImpactZones : SelfCollisionChoice::Node;
}

nlohmann::json selfCollisionFor(SelfCollisionChoice choice, const nlohmann::json* current) {
  if (choice == SelfCollisionChoice::None) return nullptr;
  auto kept = [&](const char* key, double fallback) {
    if (current && current->is_object() && current->contains(key) && (*current)[key].is_number())
      return (*current)[key].get<double>();
    return fallback;
  };
  nlohmann::json out = nlohmann::json::object();
  const bool node = choice != SelfCollisionChoice::ImpactZones;
  const bool zones = choice != SelfCollisionChoice::Node;
  if (choice == SelfCollisionChoice::ImpactZones) out["model"] = "impact_zones";
  if (choice == SelfCollisionChoice::Both) out["model"] = {"node", "impact_zones"};
  if (node) {
    out["radius"] = kept("radius", 0.004);
    out["friction"] = kept("friction", 0.3);
  }
  if (zones) out["thickness"] = kept("thickness", 0.001);
  return out;
}

std::string chooseSelfCollision(EditorDocument& document, int cloth, SelfCollisionChoice choice) {
  const std::string path = "cloths." + std::to_string(cloth) + ".self_collision";
  const nlohmann::json value = selfCollisionFor(choice, document.find(path));
  const int index = static_cast<int>(choice);
  return document.edit(std::string("Self-collision: ") + kSelfCollisionChoiceLabels[index],
                       [&](nlohmann::json& doc) {
                         nlohmann::json& target = doc.at("cloths").at(cloth);
                         if (choice == SelfCollisionChoice::None)
                           target.erase("self_collision");
                         else
                           target["self_collision"] = value;
                       });
}

}  // namespace weft::editor
