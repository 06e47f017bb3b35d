#pragma once
// Small scene documents for tests, built in code so each test states exactly the physics it
// needs. All follow the scene-file contract of the spec (they go through the strict loader).

#include <weft/scene/Scene.h>

#include <nlohmann/json.hpp>

#include <string>

namespace weft::test {

// One square grid cloth of `size` metres with `quads` x `quads` quads, no attachments, in a
// scene with the given time step and step count and no gravity (callers add effects).
nlohmann::json gridScene(double size, int quads, double dt, int steps, double stretch = 1000.0,
                         double bend = 0.0, double density = 0.1);

// A square cloth hanging in the XY plane (grid rotated 90 degrees about X, translated up by
// 1 m), pinned by fixed attachments at its two top corners (vertices 0 and quads), gravity on.
nlohmann::json hangingClothScene(double size, int quads, double dt, int steps, double stretch,
                                 double bend = 0.0, double density = 0.1);

// Validates a document through the real loader; relative paths resolve against tests/data.
Scene parse(const nlohmann::json& document, const std::string& name = "test-scene.json");

// Writes a document as a scene file and returns its path.
std::string writeScene(const std::string& path, const nlohmann::json& document);

}  // namespace weft::test
