// Fuzz target: the run store reader of `weft bench applications --resume` (readRunFile), as a
// stored run of the napkin_4x4 task by L-BFGS-B, seed 0, followed by what a resumed comparison
// asks of it first (bestEvaluation). A bad store must end in InputError; anything else that
// escapes is a finding.

#include "FuzzInput.h"

#include <weft/bench/ApplicationTasks.h>
#include <weft/bench/StoredRun.h>
#include <weft/core/Error.h>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = weft::fuzz::writeInput("napkin_4x4_lbfgsb_0.csv", data, size);
  const weft::bench::ApplicationTask* task = nullptr;
  for (const auto& t : weft::bench::kApplicationTasks)
    if (std::string(t.name) == "napkin_4x4") task = &t;
  if (!task) return 0;
  try {
    const weft::bench::ApplicationRun run = weft::bench::readRunFile(path, *task, 0, 0);
    if (!run.rows.empty()) weft::bench::bestEvaluation(run);
  } catch (const weft::InputError&) {
  }
  return 0;
}
