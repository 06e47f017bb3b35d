// Fuzz target: the scene loader with --set overrides (loadScene). An input is optional override
// lines followed by the scene file's text:
//
//   set obstacles.0.friction=0.2
//   set time.dt=0.005
//   { "cloths": [ ... ], ... }
//
// A bad scene must end in InputError (the CLI's exit 2); anything else that escapes (another
// exception type, a crash, a sanitizer report) is a finding.

#include "FuzzInput.h"

#include <weft/core/Error.h>
#include <weft/scene/SceneLoader.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<weft::SceneOverride> overrides;
  std::size_t start = 0;
  while (text.compare(start, 4, "set ") == 0) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string line = text.substr(start + 4, end - start - 4);
    const std::size_t equals = line.find('=');
    if (equals == std::string::npos) break;
    overrides.push_back({line.substr(0, equals), line.substr(equals + 1)});
    start = std::min(end + 1, text.size());
  }
  const std::string& scene = text.substr(start);
  const std::string path = weft::fuzz::writeInput(
      "scene.json", reinterpret_cast<const std::uint8_t*>(scene.data()), scene.size());
  try {
    weft::loadScene(path, overrides);
  } catch (const weft::InputError&) {
  }
  return 0;
}
