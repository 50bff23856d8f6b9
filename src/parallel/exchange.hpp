#pragma once
// The communication verbs of the particle side: byte buffers to and from the neighbour ranks
// (ghosts, migration, forward updates), gathers of small records from every rank, and the
// reductions behind collective decisions (the rebuild vote, health checks). Callers pack their own
// records (src/dem knows what a particle carries); these functions only move bytes, so MPI stays
// in src/parallel. Every function here is collective over the ranks it names (exchange: the
// neighbour ranks, which must list each other; the rest: all ranks) and is called only by runs on
// more than one rank.
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace gf::parallel {

using Bytes = std::vector<char>;

/// Sends send[k] to ranks[k] and returns, per k, the bytes ranks[k] sent to this rank.
std::vector<Bytes> exchange(const std::vector<int>& ranks, const std::vector<Bytes>& send);
/// Sends send[r] to rank r, for every rank r (send.size() = ranks; this rank's own entry and empty
/// buffers travel nowhere), and returns, indexed by rank, the bytes each rank sent to this one. No
/// rank needs to know beforehand who sends to it: the sizes go round in one MPI_Alltoall, then only
/// the non-empty buffers travel. For moves to any rank (a migration after a rebalancing).
std::vector<Bytes> exchangeWithAny(const std::vector<Bytes>& send);
/// As exchange(), when each side knows how many bytes it receives from ranks[k] (receiveBytes[k]):
/// one message round instead of two (the ghost updates between list builds).
std::vector<Bytes> exchangeKnownSizes(const std::vector<int>& ranks, const std::vector<Bytes>& send,
                                      const std::vector<std::size_t>& receiveBytes);
/// Every rank's bytes, indexed by rank.
std::vector<Bytes> allgather(const Bytes& local);
/// Rank 0's bytes on every rank.
Bytes broadcastFromRoot(const Bytes& local);
/// Element-wise sums over all ranks (every rank passes the same length).
std::vector<long long> sumOverRanks(const std::vector<long long>& local);
/// Element by element, in one collective.
std::vector<double> sumOverRanks(const std::vector<double>& local);
/// Every rank's bytes on rank 0, indexed by rank (empty on the other ranks).
std::vector<Bytes> gatherToRoot(const Bytes& local);
/// The reverse of gatherToRoot: rank 0 passes one buffer per rank (perRank[r] for rank r; ignored
/// elsewhere), every rank gets its own.
Bytes scatterFromRoot(const std::vector<Bytes>& perRank);
double maxOverRanks(double local);
double sumOverRanks(double local);
long long sumOverRanks(long long local);
bool anyOverRanks(bool local);
/// Every rank's value, indexed by rank.
std::vector<double> allgather(double local);

/// Appends trivially copyable values to a byte buffer and reads them back in the same order.
class Packer {
 public:
  explicit Packer(Bytes& out) : out_(out) {}
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }

 private:
  Bytes& out_;
};

class Unpacker {
 public:
  explicit Unpacker(const Bytes& in) : in_(in) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  bool done() const { return at_ >= in_.size(); }

 private:
  const Bytes& in_;
  std::size_t at_ = 0;
};

}  // namespace gf::parallel
