#include "fluid/gathered_pressure.hpp"

#include <cstring>
#include <stdexcept>

#include "parallel/environment.hpp"
#include "parallel/exchange.hpp"
#include "parallel/reductions.hpp"

namespace gf::fluid {
namespace {

using parallel::Bytes;

void appendValues(Bytes& out, const double* v, std::size_t count) {
  const std::size_t at = out.size();
  out.resize(at + count * sizeof(double));
  if (count) std::memcpy(out.data() + at, v, count * sizeof(double));
}

template <class T>
void appendValue(Bytes& out, const T& v) {
  parallel::Packer(out).put(v);
}

// The bytes of `count` doubles in a received buffer (not necessarily aligned: read with memcpy),
// position kept by the caller.
const char* valuesAt(const Bytes& in, std::size_t& at, std::size_t count) {
  if (at + count * sizeof(double) > in.size()) throw std::logic_error("GatheredPressure: short message");
  const char* v = in.data() + at;
  at += count * sizeof(double);
  return v;
}

std::size_t cellsOf(const std::array<int, 3>& n) { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }

// Visits the points of a box's array of shape `local` placed at `offset` in a global array of
// shape `global` (x fastest): body(localIndex, globalIndex), one grid line at a time.
template <class Body>
void forBoxLines(const std::array<int, 3>& local, const std::array<int, 3>& offset, const std::array<int, 3>& global,
                 Body&& body) {
  for (int k = 0; k < local[2]; ++k)
    for (int j = 0; j < local[1]; ++j) {
      const std::size_t l = static_cast<std::size_t>(local[0]) * (j + static_cast<std::size_t>(local[1]) * k);
      const std::size_t g = static_cast<std::size_t>(offset[0]) +
                            static_cast<std::size_t>(global[0]) *
                                (static_cast<std::size_t>(offset[1] + j) +
                                 static_cast<std::size_t>(global[1]) * static_cast<std::size_t>(offset[2] + k));
      body(l, g, static_cast<std::size_t>(local[0]));
    }
}

}  // namespace

void GatheredPressure::setup(const PressureBox& box, const std::array<bool, 3>& periodic,
                             const std::array<std::vector<double>, 3>& T, const std::array<bool, 6>& dirichlet) {
  box_ = box;
  Bytes mine;
  appendValue(mine, box);
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = box.n;
    fn[a] += 1;
    if (T[a].size() != cellsOf(fn)) throw std::logic_error("GatheredPressure::setup: face array of the wrong size");
    appendValues(mine, T[a].data(), T[a].size());
  }
  const std::vector<Bytes> all = parallel::gatherToRoot(mine);
  if (!parallel::Environment::instance().root()) return;
  boxes_.assign(all.size(), PressureBox{});
  std::array<std::vector<double>, 3> whole;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = box.global;
    fn[a] += 1;
    whole[a].assign(cellsOf(fn), 0.0);
  }
  for (std::size_t r = 0; r < all.size(); ++r) {
    parallel::Unpacker in(all[r]);
    boxes_[r] = in.get<PressureBox>();
    std::size_t at = sizeof(PressureBox);
    for (int a = 0; a < 3; ++a) {
      std::array<int, 3> fn = boxes_[r].n, gn = box.global;
      fn[a] += 1;
      gn[a] += 1;
      const char* v = valuesAt(all[r], at, cellsOf(fn));
      // A face on a cut is in both boxes, with the same coefficient (each rank computes it from
      // the same cells through the ghost layers): the later box writes it again.
      forBoxLines(fn, boxes_[r].lower, gn, [&](std::size_t l, std::size_t g, std::size_t count) {
        std::memcpy(whole[a].data() + g, v + l * sizeof(double), count * sizeof(double));
      });
    }
  }
  const parallel::ThisRankOnlyScope local;  // (rank 0 solves alone)
  poisson_.setup(box.global, periodic, whole, dirichlet);
  x_.assign(cellsOf(box.global), 0.0);
  b_.assign(cellsOf(box.global), 0.0);
}

PoissonResult GatheredPressure::solve(std::vector<double>& x, const std::vector<double>& b, double tol,
                                      int maxIterations) {
  const std::size_t count = cellsOf(box_.n);
  if (x.size() != count || b.size() != count) throw std::logic_error("GatheredPressure::solve: vectors of the wrong size");
  Bytes mine;
  mine.reserve(2 * count * sizeof(double));
  appendValues(mine, x.data(), count);
  appendValues(mine, b.data(), count);
  const std::vector<Bytes> all = parallel::gatherToRoot(mine);
  std::vector<Bytes> replies;
  PoissonResult result;
  if (parallel::Environment::instance().root()) {
    for (std::size_t r = 0; r < all.size(); ++r) {
      const std::size_t n = cellsOf(boxes_[r].n);
      std::size_t at = 0;
      const char* xr = valuesAt(all[r], at, n);
      const char* br = valuesAt(all[r], at, n);
      forBoxLines(boxes_[r].n, boxes_[r].lower, box_.global, [&](std::size_t l, std::size_t g, std::size_t len) {
        std::memcpy(x_.data() + g, xr + l * sizeof(double), len * sizeof(double));
        std::memcpy(b_.data() + g, br + l * sizeof(double), len * sizeof(double));
      });
    }
    {
      const parallel::ThisRankOnlyScope local;
      result = poisson_.solve(x_, b_, tol, maxIterations);
    }
    replies.resize(all.size());
    for (std::size_t r = 0; r < all.size(); ++r) {
      Bytes& out = replies[r];
      appendValue(out, result);
      out.resize(sizeof(PoissonResult) + cellsOf(boxes_[r].n) * sizeof(double));
      char* xr = out.data() + sizeof(PoissonResult);
      forBoxLines(boxes_[r].n, boxes_[r].lower, box_.global, [&](std::size_t l, std::size_t g, std::size_t len) {
        std::memcpy(xr + l * sizeof(double), x_.data() + g, len * sizeof(double));
      });
    }
  }
  const Bytes reply = parallel::scatterFromRoot(replies);
  result = parallel::Unpacker(reply).get<PoissonResult>();
  std::memcpy(x.data(), reply.data() + sizeof(PoissonResult), count * sizeof(double));
  return result;
}

}  // namespace gf::fluid
