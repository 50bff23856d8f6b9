#include "parallel/reductions.hpp"

#include "parallel/environment.hpp"

namespace gf::parallel {

namespace {
double sum(double local) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, Environment::instance().communicator());
  return global;
}
std::pair<double, double> sum2(std::pair<double, double> local) {
  double in[2] = {local.first, local.second}, out[2] = {0.0, 0.0};
  MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_SUM, Environment::instance().communicator());
  return {out[0], out[1]};
}
double max(double local) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, Environment::instance().communicator());
  return global;
}
const RankReductions kAllRanks{&sum, &sum2, &max};
}  // namespace

const RankReductions& allRankReductions() { return kAllRanks; }

RankReductionScope::RankReductionScope(const Decomposition& d) : previous_(rankReductions()) {
  if (d.distributed()) {
    setRankReductions(&kAllRanks);
    installed_ = true;
  }
}

RankReductionScope::~RankReductionScope() {
  if (installed_) setRankReductions(previous_);
}

}  // namespace gf::parallel
