// The MPI environment (parallel/environment.hpp): MPI is initialised on first use only (a run
// without mpirun and without a distributed component never starts MPI), and rank, size and the
// reductions agree with the launcher (ctest also runs these under mpirun -n 2).
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "parallel/environment.hpp"

namespace gf::parallel {
namespace {

TEST(Environment, InitialisedOnFirstUseOnly) {
  // (each ctest test is its own process: nothing has touched MPI before this line)
  EXPECT_FALSE(Environment::initialised());
  Environment& env = Environment::instance();
  EXPECT_TRUE(Environment::initialised());
  EXPECT_EQ(&env, &Environment::instance());
}

TEST(Environment, RankAndSizeMatchTheLauncher) {
  const Environment& env = Environment::instance();
  int expected = 1;
  if (const char* size = std::getenv("OMPI_COMM_WORLD_SIZE")) expected = std::stoi(size);
  EXPECT_EQ(Environment::launched(), std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
                                         std::getenv("PMI_SIZE") != nullptr || std::getenv("SLURM_NTASKS") != nullptr);
  EXPECT_EQ(env.size(), expected);
  EXPECT_GE(env.rank(), 0);
  EXPECT_LT(env.rank(), env.size());
  EXPECT_EQ(env.root(), env.rank() == 0);
  int size = 0;
  MPI_Comm_size(env.communicator(), &size);
  EXPECT_EQ(size, env.size());
  // sum over the ranks: 1 per rank, and 0 + 1 + ... + (size - 1)
  EXPECT_EQ(env.sum(1.0), env.size());
  EXPECT_EQ(env.sum(env.rank()), env.size() * (env.size() - 1) / 2);
}

TEST(Environment, SingletonInitialisationIsCheap) {
  // A singleton MPI_Init (no mpirun) costs about 0.3 s with OpenMPI: the reason it is lazy. The
  // bound only catches a hang or a launcher timeout.
  const Environment& env = Environment::instance();
  EXPECT_LT(env.initSeconds(), 10.0);
}

}  // namespace
}  // namespace gf::parallel
