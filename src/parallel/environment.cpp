#include "parallel/environment.hpp"

#include <chrono>
#include <cstdlib>
#include <stdexcept>

namespace gf::parallel {

namespace {
bool gInitialised = false;
}  // namespace

Environment& Environment::instance() {
  // A function-local static: constructed on first use, destroyed at exit (after main's objects,
  // so every solver has released its hypre objects before MPI_Finalize).
  static Environment environment;
  return environment;
}

bool Environment::initialised() { return gInitialised; }

bool Environment::launched() {
  // OpenMPI's mpirun, PMIx launchers (OpenMPI 4, Slurm), MPICH/Hydra and Slurm's srun.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "SLURM_NTASKS"})
    if (std::getenv(name)) return true;
  return false;
}

int Environment::launchedRank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return 0;
}

Environment::Environment() {
  int already = 0;
  MPI_Initialized(&already);
  if (!already) {
    const auto started = std::chrono::steady_clock::now();
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
      throw std::runtime_error("MPI_Init_thread failed");
    initSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    ownsMpi_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  gInitialised = true;
}

Environment::~Environment() {
  for (auto it = finalizers_.rbegin(); it != finalizers_.rend(); ++it) (*it)();
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (ownsMpi_ && !finalized) MPI_Finalize();
}

void Environment::abortAll(int exitCode) const {
  MPI_Abort(MPI_COMM_WORLD, exitCode);
  std::exit(exitCode);  // (MPI_Abort does not return)
}

double Environment::sum(double local) const {
  if (size_ == 1) return local;
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, communicator());
  return global;
}

}  // namespace gf::parallel
