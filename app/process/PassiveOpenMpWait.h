#pragma once
// Weft's executables wait for OpenMP work passively unless the user chose otherwise.
//
// Why: libgomp's default lets idle worker threads spin (GOMP_SPINCOUNT 300,000 rounds) at every
// barrier before they sleep. On a machine whose cores are busy with other work (a CI runner, a
// build, a second simulation), the spinning worker takes the core the thread with the actual
// work needs, and every one of a step's many short parallel regions (local step, contact nodes)
// waits for a scheduler slice. docs/cli.md, "Threads", has the measurements.
//
// libgomp reads OMP_WAIT_POLICY once, in its constructor, before main() runs; and glibc sets
// the environment up after an executable's .preinit_array functions, so a setenv there is lost.
// So when OMP_WAIT_POLICY is unset, the process sets it to PASSIVE and executes itself again
// (/proc/self/exe, same arguments) before doing anything else. An explicit OMP_WAIT_POLICY
// (ACTIVE, to benchmark on an idle machine) is kept and costs nothing; if the re-execution is
// impossible the process goes on with libgomp's default.

namespace weft::process {

// Call first thing in main(). Returns only if no re-execution happened.
void preferPassiveOpenMpWait(char** argv);

}  // namespace weft::process
