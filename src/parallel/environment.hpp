#pragma once
// The process's MPI environment: initialised once, finalised at exit, and the communicator that
// the distributed components (the hypre pressure solve, later the domain decomposition) work on.
//
// MPI is initialised on the first call of Environment::instance(), not at program start: a
// singleton MPI_Init (a run without mpirun) costs about 0.3 s with OpenMPI, which every `grainflow`
// command would otherwise pay. A run without mpirun that uses no distributed component therefore
// behaves exactly as a build without MPI. Under mpirun every rank reaches the same first use (the
// same case file, the same code path), so the lazy initialisation is collective as MPI requires.
//
// MPI calls belong in src/parallel (and in the hypre solver, which hands the communicator to hypre);
// the rest of the code asks this object for the rank, the size and the communicator.
#include <mpi.h>

#include <functional>
#include <vector>

namespace gf::parallel {

class Environment {
 public:
  /// The environment, with MPI initialised (MPI_THREAD_FUNNELED: only the thread that calls MPI,
  /// outside OpenMP regions, talks to other ranks). MPI is finalised when the program exits.
  static Environment& instance();
  /// Whether MPI has been initialised in this process (instance() has been called), without doing so.
  static bool initialised();
  /// Whether an MPI launcher (mpirun, mpiexec, srun) started this process, read from its
  /// environment variables, without initialising MPI.
  static bool launched();
  /// The rank the launcher gave this process (from its environment variables, without
  /// initialising MPI); 0 when not launched.
  static int launchedRank();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  /// The communicator of all ranks of the run (MPI_COMM_WORLD).
  MPI_Comm communicator() const { return MPI_COMM_WORLD; }
  /// Wall time of the MPI initialisation, s.
  double initSeconds() const { return initSeconds_; }
  /// fn runs at exit before MPI_Finalize (libraries built on MPI release their state), in the
  /// reverse order of registration.
  void atFinalize(std::function<void()> fn) { finalizers_.push_back(std::move(fn)); }

  /// Stops every rank of the run with this exit code (MPI_Abort): for an error that struck one
  /// rank while the others may wait for it.
  [[noreturn]] void abortAll(int exitCode) const;
  /// Sum of a value over all ranks (the value itself on one rank).
  double sum(double local) const;

  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

 private:
  Environment();
  ~Environment();

  int rank_ = 0, size_ = 1;
  bool ownsMpi_ = false;  // this object called MPI_Init (and calls MPI_Finalize)
  double initSeconds_ = 0.0;
  std::vector<std::function<void()>> finalizers_;
};

}  // namespace gf::parallel
