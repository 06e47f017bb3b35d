#pragma once
// Independent work items handed out to the processes of one run and their results gathered:
// serially in one process, or over MPI's ranks when Weft is built with MPI and launched by
// mpirun or srun (docs/distributed.md). Every process runs the same command (SPMD); the commands
// that distribute (`weft sweep`, `weft landscape`, `weft optimize --method cmaes|es1p1`, `weft
// bench applications`) call map() at the same points on every rank, with the same items, and
// rank 0 alone writes their output.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace weft {

// What one item gave: its bytes, or its failure with the exit code it would have given the CLI
// (2 bad input, 3 numerical failure, 1 anything else) and the CLI's message.
struct WorkItemResult {
  bool ok = true;
  std::string data;     // what the work function returned, when ok
  int exitCode = 0;     // when !ok
  std::string message;  // when !ok: the error's text (without "error: ")
  int rank = 0;         // the process that ran the item
  // When !ok: the error's kind and fields, for rethrowFailure ("input\0file\0path\0reason",
  // "numerical\0step\0module\0quantity", or empty for other errors).
  std::string detail;
};

// Thrown on a rank other than 0 to leave the command without printing anything: rank 0 reports
// (what failed on rank 0, or a non-MPI build's extra processes). main() returns `code`.
struct QuietExit {
  int code = 0;
};

class WorkDistributor {
 public:
  using Work = std::function<std::string(std::size_t item)>;
  virtual ~WorkDistributor() = default;

  virtual int rank() const = 0;  // 0 .. size() - 1; rank 0 gathers and writes
  virtual int size() const = 0;
  bool isRoot() const { return rank() == 0; }
  // "serial" or "MPI, N ranks".
  virtual std::string description() const = 0;

  // Collective: every rank calls it with the same `count` and the same work. Each item runs once,
  // on some rank (handed out as ranks become free, so long and short items balance); every
  // rank gets every item's result, in item order. An item that throws InputError,
  // NumericalError or another std::exception is a failed result, not an exception here; the
  // other items still run. The results do not depend on which rank ran what, as long as
  // work(i) is deterministic.
  virtual std::vector<WorkItemResult> map(std::size_t count, const Work& work) = 0;

  // Collective: runs `step` on rank 0, then (once it succeeded) on the other ranks, and returns
  // when every rank has run it; for set-up that must not race (creating a run store the others
  // then read). If it throws on rank 0, the exception leaves rank 0 and the others throw
  // QuietExit with its exit code.
  virtual void rootFirst(const std::function<void()>& step) = 0;
};

// The processes this run was launched as: MPI's ranks (mpirun, srun: detected from the
// launcher's environment) in a build with MPI, else this process alone. MPI starts on the first
// call. In a build without MPI launched as several processes, rank 0 runs the whole job alone
// and says so on stderr, and the other processes throw QuietExit{0}.
WorkDistributor& processWorkers();
// Whether this build can use MPI.
bool builtWithMpi();
// Ends MPI if processWorkers() started it; main() calls it on every way out with the exit code.
// A non-zero code (other than a QuietExit's) with several ranks ends the whole job through
// MPI_Abort, so that no rank is left waiting for one that failed.
void endProcessWorkers(int exitCode = 0, bool quiet = false);
// This process's rank as the launcher gave it (0 without one), known before MPI starts: the
// CLI prints errors on rank 0 only.
int launchRank();
// How many processes the launcher started (1 without one; at least 2 when it started several).
int launchSize();

// Runs every item in this process, in order (also what processWorkers() is without a launcher).
std::unique_ptr<WorkDistributor> makeSerialDistributor();

// The result of running `work(item)` here: its bytes, or its failure (exit code and message).
WorkItemResult runWorkItem(const WorkDistributor::Work& work, std::size_t item, int rank);

// Throws the failed item's error as it was thrown where it ran: InputError and NumericalError
// with their fields, anything else as std::runtime_error with its message. Every rank has the
// same results, so every rank throws the same: the error is marked shared (failureIsShared),
// and the CLI ends MPI normally instead of aborting the job.
[[noreturn]] void rethrowFailure(const WorkItemResult& failed);
bool failureIsShared();

// The first failed result, or nullptr.
const WorkItemResult* firstFailure(const std::vector<WorkItemResult>& results);

}  // namespace weft
