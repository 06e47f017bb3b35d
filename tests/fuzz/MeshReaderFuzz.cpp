// Fuzz target: the mesh reader (readMesh) for one file format, chosen at build time by
// WEFT_FUZZ_MESH_EXTENSION ("obj" goes through tinyobjloader, "ply" and "gltf" through Weft's own
// readers, any other extension through assimp). A bad mesh must end in InputError; anything else
// that escapes is a finding.

#include "FuzzInput.h"

#include <weft/core/Error.h>
#include <weft/io/MeshReader.h>

#include <cstddef>
#include <cstdint>

#ifndef WEFT_FUZZ_MESH_EXTENSION
#error "WEFT_FUZZ_MESH_EXTENSION names the format, e.g. \"obj\""
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = weft::fuzz::writeInput("mesh." WEFT_FUZZ_MESH_EXTENSION, data, size);
  try {
    weft::readMesh(path);
  } catch (const weft::InputError&) {
  }
  return 0;
}
