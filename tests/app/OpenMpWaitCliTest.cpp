// Weft's executables wait for OpenMP work passively unless the user set OMP_WAIT_POLICY
// (app/process/PassiveOpenMpWait.h: libgomp's spinning default made two-thread runs 16-60x
// slower on a machine whose cores were busy, docs/cli.md, "Threads"). libgomp prints what it read
// at start-up when OMP_DISPLAY_ENV is VERBOSE, which shows what the runtime actually uses. Its
// OMP_WAIT_POLICY line says PASSIVE for an unset policy too; the spin count tells them apart (0
// passive, 300000 unset, 30000000000 active).

#include "CliSupport.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace weft::test {
namespace {

// Runs `binary --help` with OMP_WAIT_POLICY removed from (or set in) the environment the tests
// run with (ctest sets PASSIVE for every test) and returns libgomp's spin-count line.
std::string waitPolicyReport(const std::string& binary, const std::string& policy) {
  std::vector<std::string> argv{"/usr/bin/env", "-u", "OMP_WAIT_POLICY", "OMP_DISPLAY_ENV=VERBOSE"};
  if (!policy.empty()) argv.push_back("OMP_WAIT_POLICY=" + policy);
  argv.push_back(binary);
  argv.push_back("--help");
  const ProcessResult r = runProcess(argv);
  EXPECT_EQ(r.exitCode, 0) << describe(r);
  // The last report is the running process's (a re-executed one printed one before it).
  const std::size_t at = r.err.rfind("GOMP_SPINCOUNT = ");
  if (at == std::string::npos) return "(no report)\n" + r.err;
  return r.err.substr(at, r.err.find('\n', at) - at);
}

TEST(OpenMpWait, WeftWaitsPassivelyByDefault) {
  EXPECT_EQ(waitPolicyReport(WEFT_BINARY, ""), "GOMP_SPINCOUNT = '0'");
}

TEST(OpenMpWait, WeftKeepsThePolicyTheUserSet) {
  EXPECT_EQ(waitPolicyReport(WEFT_BINARY, "ACTIVE"), "GOMP_SPINCOUNT = '30000000000'");
}

TEST(OpenMpWait, EditorWaitsPassivelyByDefault) {
  EXPECT_EQ(waitPolicyReport(WEFT_EDITOR_BINARY, ""), "GOMP_SPINCOUNT = '0'");
}

}  // namespace
}  // namespace weft::test
