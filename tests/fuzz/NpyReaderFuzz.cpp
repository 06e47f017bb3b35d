// Fuzz target: the NPY reader (readNpy), which reads run folders' positions.npy back (weft
// render RUNDIR, the editor's simulation cache). A bad file must end in InputError; anything else
// that escapes is a finding.

#include "FuzzInput.h"

#include <weft/core/Error.h>
#include <weft/io/Npy.h>

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = weft::fuzz::writeInput("array.npy", data, size);
  try {
    weft::readNpy(path);
  } catch (const weft::InputError&) {
  }
  return 0;
}
