#include "SerialDistributor.h"

#include <weft/distributed/WorkDistributor.h>

#ifdef WEFT_HAS_MPI
#include "MpiDistributor.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

namespace weft {
namespace {

// The launcher's word on how many processes this run is and which one this is: Open MPI's
// mpirun, PMI/PMIx launchers (MPICH's hydra, Slurm's srun --mpi=pmi2|pmix). {0, 1} without a
// launcher. Slurm's own variables are not read: a batch script's shell has them too, and is not
// one of the job's ranks. PMIx names the rank but not the size: 2 stands for "several" there,
// and MPI says how many once it starts.
struct Launch {
  int rank = 0;
  int size = 1;
  bool launched = false;
};

int environmentInteger(const char* name, int fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return *end == '\0' && v >= 0 && v < (1L << 30) ? static_cast<int>(v) : fallback;
}

Launch launchFromEnvironment() {
  const char* sizes[][2] = {{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
                            {"PMI_SIZE", "PMI_RANK"},
                            {"PMIX_SIZE", "PMIX_RANK"}};
  for (const auto& names : sizes) {
    const int size = environmentInteger(names[0], -1);
    if (size < 1) continue;
    return {environmentInteger(names[1], 0), size, true};
  }
  if (std::getenv("PMIX_RANK")) return {environmentInteger("PMIX_RANK", 0), 2, true};
  return {};
}

std::unique_ptr<WorkDistributor>& processDistributor() {
  static std::unique_ptr<WorkDistributor> distributor;
  return distributor;
}

#ifdef WEFT_HAS_MPI
bool startedMpi = false;
#endif

}  // namespace

bool builtWithMpi() {
#ifdef WEFT_HAS_MPI
  return true;
#else
  return false;
#endif
}

WorkDistributor& processWorkers() {
  std::unique_ptr<WorkDistributor>& distributor = processDistributor();
  if (distributor) return *distributor;
  const Launch launch = launchFromEnvironment();
#ifdef WEFT_HAS_MPI
  if (launch.launched && launch.size > 1) {
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
      throw std::runtime_error("MPI_Init_thread failed");
    startedMpi = true;
    if (provided < MPI_THREAD_SERIALIZED) {
      // The hand-out thread on rank 0 needs it; every MPI Weft supports (Open MPI, MPICH) has it.
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    distributor = std::make_unique<MpiDistributor>();
    return *distributor;
  }
#endif
  if (launch.launched && launch.size > 1) {
    if (launch.rank != 0) throw QuietExit{0};
    std::fprintf(stderr,
                 "warning: launched as %d processes, but this weft was built without MPI: rank 0 "
                 "runs the whole job serially, the other processes exit\n",
                 launch.size);
  }
  distributor = makeSerialDistributor();
  return *distributor;
}

int launchRank() {
  return launchFromEnvironment().rank;
}
int launchSize() {
  return launchFromEnvironment().size;
}

void endProcessWorkers(int exitCode, bool quiet) {
#ifdef WEFT_HAS_MPI
  if (!startedMpi) return;
  if (exitCode != 0 && !quiet && processDistributor() && processDistributor()->size() > 1) {
    std::fflush(stderr);
    std::fflush(stdout);
    MPI_Abort(MPI_COMM_WORLD, exitCode);
  }
  processDistributor().reset();  // frees its communicator before MPI ends
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
#else
  (void)exitCode, (void)quiet;
#endif
}

}  // namespace weft
