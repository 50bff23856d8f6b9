#include "parallel/exchange.hpp"

#include <mpi.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "parallel/environment.hpp"

namespace gf::parallel {

namespace {
MPI_Comm world() { return Environment::instance().communicator(); }
constexpr int kSizeTag = 7101, kDataTag = 7102;
}  // namespace

std::vector<Bytes> exchange(const std::vector<int>& ranks, const std::vector<Bytes>& send) {
  const std::size_t n = ranks.size();
  if (send.size() != n) throw std::logic_error("parallel::exchange: one buffer per rank expected");
  // Sizes first, then the payloads (each message at most 2^31 bytes: ghost and migration
  // buffers of a neighbour pair are far smaller).
  std::vector<long long> sendSize(n), recvSize(n);
  std::vector<MPI_Request> requests(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    sendSize[k] = static_cast<long long>(send[k].size());
    MPI_Irecv(&recvSize[k], 1, MPI_LONG_LONG, ranks[k], kSizeTag, world(), &requests[k]);
  }
  for (std::size_t k = 0; k < n; ++k) MPI_Isend(&sendSize[k], 1, MPI_LONG_LONG, ranks[k], kSizeTag, world(), &requests[n + k]);
  MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
  std::vector<Bytes> received(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (recvSize[k] > std::numeric_limits<int>::max() || sendSize[k] > std::numeric_limits<int>::max())
      throw std::runtime_error("parallel::exchange: message above 2 GiB");
    received[k].resize(static_cast<std::size_t>(recvSize[k]));
    MPI_Irecv(received[k].data(), static_cast<int>(recvSize[k]), MPI_BYTE, ranks[k], kDataTag, world(), &requests[k]);
  }
  for (std::size_t k = 0; k < n; ++k)
    MPI_Isend(send[k].data(), static_cast<int>(sendSize[k]), MPI_BYTE, ranks[k], kDataTag, world(), &requests[n + k]);
  MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
  return received;
}

std::vector<Bytes> exchangeWithAny(const std::vector<Bytes>& send) {
  const Environment& env = Environment::instance();
  const int size = env.size(), me = env.rank();
  if (send.size() != static_cast<std::size_t>(size)) throw std::logic_error("parallel::exchangeWithAny: one buffer per rank expected");
  std::vector<long long> sendSize(static_cast<std::size_t>(size)), recvSize(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) sendSize[r] = r == me ? 0 : static_cast<long long>(send[r].size());
  MPI_Alltoall(sendSize.data(), 1, MPI_LONG_LONG, recvSize.data(), 1, MPI_LONG_LONG, world());
  std::vector<Bytes> received(static_cast<std::size_t>(size));
  std::vector<MPI_Request> requests;
  constexpr int kAnyTag = 7104;
  for (int r = 0; r < size; ++r) {
    if (recvSize[r] == 0) continue;
    if (recvSize[r] > std::numeric_limits<int>::max()) throw std::runtime_error("parallel::exchangeWithAny: message above 2 GiB");
    received[r].resize(static_cast<std::size_t>(recvSize[r]));
    requests.emplace_back();
    MPI_Irecv(received[r].data(), static_cast<int>(recvSize[r]), MPI_BYTE, r, kAnyTag, world(), &requests.back());
  }
  for (int r = 0; r < size; ++r) {
    if (sendSize[r] == 0) continue;
    if (sendSize[r] > std::numeric_limits<int>::max()) throw std::runtime_error("parallel::exchangeWithAny: message above 2 GiB");
    requests.emplace_back();
    MPI_Isend(send[r].data(), static_cast<int>(sendSize[r]), MPI_BYTE, r, kAnyTag, world(), &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return received;
}

Bytes broadcastFromRoot(const Bytes& local) {
  long long size = static_cast<long long>(local.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, world());
  if (size > std::numeric_limits<int>::max()) throw std::runtime_error("parallel::broadcastFromRoot: message above 2 GiB");
  Bytes out = Environment::instance().root() ? local : Bytes(static_cast<std::size_t>(size));
  MPI_Bcast(out.data(), static_cast<int>(size), MPI_BYTE, 0, world());
  return out;
}

std::vector<long long> sumOverRanks(const std::vector<long long>& local) {
  std::vector<long long> global(local.size());
  MPI_Allreduce(local.data(), global.data(), static_cast<int>(local.size()), MPI_LONG_LONG, MPI_SUM, world());
  return global;
}

std::vector<double> sumOverRanks(const std::vector<double>& local) {
  std::vector<double> global(local.size());
  MPI_Allreduce(local.data(), global.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM, world());
  return global;
}

std::vector<Bytes> exchangeKnownSizes(const std::vector<int>& ranks, const std::vector<Bytes>& send,
                                      const std::vector<std::size_t>& receiveBytes) {
  const std::size_t n = ranks.size();
  if (send.size() != n || receiveBytes.size() != n)
    throw std::logic_error("parallel::exchangeKnownSizes: one buffer and one size per rank expected");
  std::vector<Bytes> received(n);
  std::vector<MPI_Request> requests(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    if (receiveBytes[k] > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
        send[k].size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw std::runtime_error("parallel::exchangeKnownSizes: message above 2 GiB");
    received[k].resize(receiveBytes[k]);
    MPI_Irecv(received[k].data(), static_cast<int>(receiveBytes[k]), MPI_BYTE, ranks[k], kDataTag, world(), &requests[k]);
  }
  for (std::size_t k = 0; k < n; ++k)
    MPI_Isend(send[k].data(), static_cast<int>(send[k].size()), MPI_BYTE, ranks[k], kDataTag, world(), &requests[n + k]);
  MPI_Waitall(static_cast<int>(2 * n), requests.data(), MPI_STATUSES_IGNORE);
  return received;
}

std::vector<Bytes> allgather(const Bytes& local) {
  const int size = Environment::instance().size();
  int mine = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size) + 1, 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, world());
  for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + counts[r];
  Bytes all(static_cast<std::size_t>(offsets[size]));
  MPI_Allgatherv(local.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, world());
  std::vector<Bytes> out(static_cast<std::size_t>(size));
  for (int r = 0; r < size; ++r) out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r + 1]);
  return out;
}

Bytes scatterFromRoot(const std::vector<Bytes>& perRank) {
  const Environment& env = Environment::instance();
  const int size = env.size();
  std::vector<long long> counts(static_cast<std::size_t>(size), 0);
  if (env.root()) {
    if (perRank.size() != static_cast<std::size_t>(size))
      throw std::logic_error("parallel::scatterFromRoot: one buffer per rank expected");
    for (int r = 0; r < size; ++r) counts[r] = static_cast<long long>(perRank[r].size());
  }
  long long mine = 0;
  MPI_Scatter(counts.data(), 1, MPI_LONG_LONG, &mine, 1, MPI_LONG_LONG, 0, world());
  constexpr int kScatterTag = 7105;
  if (env.root()) {
    // Rank by rank, in chunks (no 2 GiB limit, as in gatherToRoot).
    std::vector<MPI_Request> requests;
    for (int r = 1; r < size; ++r)
      for (std::size_t at = 0; at < perRank[r].size();) {
        const int chunk = static_cast<int>(std::min<std::size_t>(perRank[r].size() - at, 1u << 30));
        requests.emplace_back();
        MPI_Isend(perRank[r].data() + at, chunk, MPI_BYTE, r, kScatterTag, world(), &requests.back());
        at += static_cast<std::size_t>(chunk);
      }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return perRank[0];
  }
  Bytes out(static_cast<std::size_t>(mine));
  for (std::size_t at = 0; at < out.size();) {
    const int chunk = static_cast<int>(std::min<std::size_t>(out.size() - at, 1u << 30));
    MPI_Recv(out.data() + at, chunk, MPI_BYTE, 0, kScatterTag, world(), MPI_STATUS_IGNORE);
    at += static_cast<std::size_t>(chunk);
  }
  return out;
}

std::vector<Bytes> gatherToRoot(const Bytes& local) {
  const Environment& env = Environment::instance();
  const int size = env.size();
  long long mine = static_cast<long long>(local.size());
  std::vector<long long> counts(static_cast<std::size_t>(size));
  MPI_Gather(&mine, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, 0, world());
  std::vector<Bytes> out;
  constexpr int kGatherTag = 7103;
  if (env.root()) {
    out.resize(static_cast<std::size_t>(size));
    out[0] = local;
    // Rank by rank (point to point: no 2 GiB limit on the total, as MPI_Gatherv's int offsets have).
    for (int r = 1; r < size; ++r) {
      out[r].resize(static_cast<std::size_t>(counts[r]));
      std::size_t at = 0;
      while (at < out[r].size()) {
        const int chunk = static_cast<int>(std::min<std::size_t>(out[r].size() - at, 1u << 30));
        MPI_Recv(out[r].data() + at, chunk, MPI_BYTE, r, kGatherTag, world(), MPI_STATUS_IGNORE);
        at += static_cast<std::size_t>(chunk);
      }
    }
  } else {
    std::size_t at = 0;
    while (at < local.size()) {
      const int chunk = static_cast<int>(std::min<std::size_t>(local.size() - at, 1u << 30));
      MPI_Send(local.data() + at, chunk, MPI_BYTE, 0, kGatherTag, world());
      at += static_cast<std::size_t>(chunk);
    }
  }
  return out;
}

double maxOverRanks(double local) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, world());
  return global;
}

double sumOverRanks(double local) {
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, world());
  return global;
}

long long sumOverRanks(long long local) {
  long long global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_LONG_LONG, MPI_SUM, world());
  return global;
}

bool anyOverRanks(bool local) {
  int mine = local ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_LOR, world());
  return any != 0;
}

std::vector<double> allgather(double local) {
  std::vector<double> all(static_cast<std::size_t>(Environment::instance().size()));
  MPI_Allgather(&local, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, world());
  return all;
}

}  // namespace gf::parallel
