#pragma once
// Dotted JSON paths into a scene document ("cloths.0.material.stretch"), the addressing used by
// `--set`, by task parameters and by error messages.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace weft {

std::vector<std::string> splitJsonPath(const std::string& path);
// The value at `path`, or nullptr if any component does not exist.
const nlohmann::json* findJsonPath(const nlohmann::json& doc, const std::string& path);
nlohmann::json* findJsonPath(nlohmann::json& doc, const std::string& path);

// Whether `text` is valid UTF-8, as a JSON string must be (nlohmann::json refuses to write one
// that is not, so a scene may not hold one).
bool isValidUtf8(const std::string& text);

// Parses an override value from the command line: JSON if it parses ("[0,-9.8,0]", "0.2",
// "true", "\"text\""), a comma list of numbers as an array ("0,-9.8,0"), otherwise a string.
nlohmann::json parseOverrideValue(const std::string& text);

// Sets `path` to `value`. The parent must exist; an existing number may only be replaced by a
// number, an array by an array of the same length. A missing final key is created (the scene
// validator then rejects it if it is not a key of the format). Returns an error text, or ""
// on success.
std::string setJsonPath(nlohmann::json& doc, const std::string& path, const nlohmann::json& value);

// Creates the objects `path` passes through that `doc` lacks, as empty objects, so that a key a
// file leaves at its default can still be set: "solver.backward.tolerance" on a scene without
// "solver". Only object members are created, never array elements (a path with an index below
// the first missing object creates nothing). Whether the created keys are keys of the format is
// for the scene validator to decide (its lists of allowed keys are the one schema). Returns the
// path of the outermost object created, or "" when nothing was created.
std::string createJsonPathObjects(nlohmann::json& doc, const std::string& path);

}  // namespace weft
