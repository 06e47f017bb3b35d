#pragma once
// The Scene panel's self-collision choice for one cloth: none, DiffCloth's node model, Liang et
// al.'s impact zones, or both (docs/scene-format.md, cloths.K.self_collision). Switching keeps
// the values the new choice shares with the old one and drops the ones it does not accept
// (radius and friction belong to the node model, thickness to impact zones), so that every
// switch leaves a scene that validates.

#include <nlohmann/json.hpp>

#include <string>

namespace weft::editor {

enum class SelfCollisionChoice : int { None = 0, Node = 1, ImpactZones = 2, Both = 3 };

inline constexpr const char* kSelfCollisionChoiceLabels[] = {
    "none", "node (DiffCloth)", "impact zones (Liang)", "node + impact zones"};

// The choice a cloth's self_collision value (null when absent) makes.
SelfCollisionChoice selfCollisionChoice(const nlohmann::json* selfCollision);

// The self_collision value for `choice`, keeping `current`'s shared values (null for None).
nlohmann::json selfCollisionFor(SelfCollisionChoice choice, const nlohmann::json* current);

class EditorDocument;

// Switches cloth `cloth`'s self-collision to `choice` in one undo step; returns an error text
// ("" on success; the document is then unchanged).
std::string chooseSelfCollision(EditorDocument& document, int cloth, SelfCollisionChoice choice);

}  // namespace weft::editor
