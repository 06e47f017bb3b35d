#pragma once
#include <functional>
#include <string>

namespace weft {

// How a call run in a child process ended.
struct ChildOutcome {
  enum class Kind {
    Returned,  // `bytes` is what the call returned
    Threw,     // `bytes` is the what() of the exception it threw
    Died,      // it crashed or exited without a result; `bytes` says how (signal or status)
    TimedOut,  // it did not finish in time and was killed
  };
  Kind kind = Kind::Died;
  std::string bytes;
};

// Runs `call` in a child process made with fork() and hands back what it returned, so that a
// crash, a hang or a runaway allocation inside third-party code (assimp's readers,
// docs/hardening.md) ends that child, not the caller. The child's address space is limited to
// `memoryLimitBytes` (not under the sanitizers, whose shadow memory needs more) and it is killed
// after `timeoutSeconds`; its standard error is discarded, and a fault (SIGSEGV, SIGBUS, SIGILL,
// SIGFPE) kills it at once, whatever handlers the caller installed. Only the calling thread exists
// in the child, so `call` must not wait on another thread of the caller's or on a lock one may hold
// (glibc's allocator is safe after fork).
ChildOutcome runInChildProcess(const std::function<std::string()>& call, double timeoutSeconds,
                               long long memoryLimitBytes);

// "killed by signal 11 (Segmentation fault)", "exited with status 1", for messages.
std::string describeChildExit(int waitStatus);

}  // namespace weft
