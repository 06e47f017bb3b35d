#include "SceneSource.h"

#include <weft/core/Error.h>
#include <weft/scene/SceneLoader.h>

#include <nlohmann/json.hpp>

namespace weft::python {

std::string SceneSource::name() const {
  return file ? *file : "<dict>";
}

Scene SceneSource::load() const {
  std::vector<SceneOverride> parsed;
  for (const std::string& text : overrides) parsed.push_back(parseSceneOverride(text, name()));
  if (file) return loadScene(*file, parsed);
  if (!documentText) throw InputError(name(), "<scene>", "no scene file or document given");
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(*documentText);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name(), "<json>", std::string("invalid JSON: ") + e.what());
  }
  return loadSceneDocument(std::move(document), name(), ".", parsed);
}

}  // namespace weft::python
