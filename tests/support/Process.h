#pragma once
// Runs a child process (the real `weft` binary) and captures its exit code and output.

#include <string>
#include <vector>

namespace weft::test {

struct ProcessResult {
  int exitCode = -1;  // -1 if it did not exit normally (e.g. killed by a signal)
  int signal = 0;     // the signal that ended it, if any
  std::string out, err;
};

// argv[0] is the executable path; no shell is involved, so arguments need no quoting.
ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& workDir = "");

}  // namespace weft::test
