#pragma once
// Where the scene of a Python call comes from: a scene file, or a scene document (a Python dict,
// handed over as its JSON text), with the call's `set` overrides as "PATH=VALUE" texts, the
// arguments of the CLI's --set.

#include <weft/scene/Scene.h>

#include <optional>
#include <string>
#include <vector>

namespace weft::python {

struct SceneSource {
  std::optional<std::string> file;          // a scene file, as `weft simulate FILE` takes it
  std::optional<std::string> documentText;  // or a document's JSON text
  std::vector<std::string> overrides;       // "PATH=VALUE", as --set takes them

  // The name errors are reported against: the file, or "<dict>" for a document.
  std::string name() const;
  // Loads, overrides and validates the scene as `weft simulate` does (loadScene), a document
  // with its relative paths resolved against the working directory. Throws InputError.
  Scene load() const;
};

}  // namespace weft::python
