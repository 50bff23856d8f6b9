#include "parallel/halo.hpp"

#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "parallel/environment.hpp"
#include "parallel/exchange.hpp"

namespace gf::parallel {

namespace {

/// A box of points [lo, hi) per axis in a field's local indices (ghosts negative or >= points).
struct PointBox {
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
  std::size_t count() const {
    std::size_t c = 1;
    for (int a = 0; a < 3; ++a) c *= static_cast<std::size_t>(hi[a] > lo[a] ? hi[a] - lo[a] : 0);
    return c;
  }
};

/// fn(flat index) over the points of b, x fastest (the same order on sender and receiver).
template <class Fn>
void forBox(const Field& f, const PointBox& b, Fn&& fn) {
  if (b.count() == 0) return;
  for (int k = b.lo[2]; k < b.hi[2]; ++k)
    for (int j = b.lo[1]; j < b.hi[1]; ++j) {
      const std::size_t base = f.index(b.lo[0], j, k);
      for (int i = 0; i < b.hi[0] - b.lo[0]; ++i) fn(base + static_cast<std::size_t>(i));
    }
}

/// Per-axis ranges of one field on this rank (see halo.hpp: classes and ownership).
struct Axes {
  int g = 0;
  std::array<int, 3> points{}, own{};
  std::array<bool, 3> lowShared{}, upShared{};
  std::array<int, 3> stagger{};

  Axes(const Field& f, const Decomposition& d) : g(f.grid().ghosts), points(f.points()) {
    const auto cells = f.grid().cells;
    if (d.gridded() && cells != d.cellCount())
      throw std::invalid_argument(fmt::format("halo: a field of {} x {} x {} cells on a rank whose box has {} x {} x {}",
                                              cells[0], cells[1], cells[2], d.cellCount()[0], d.cellCount()[1],
                                              d.cellCount()[2]));
    for (int a = 0; a < 3; ++a) {
      stagger[a] = static_cast<int>(f.staggering()) == a + 1 ? 1 : 0;
      lowShared[a] = d.side(a, -1) == Side::Shared;
      upShared[a] = d.side(a, +1) == Side::Shared;
      own[a] = points[a] - (upShared[a] ? stagger[a] : 0);
      if ((lowShared[a] || upShared[a]) && cells[a] < g + stagger[a])
        throw std::invalid_argument(
            fmt::format("halo: {} cells along {} on rank {}: a decomposed axis needs at least {} per rank (the ghost "
                        "layers{})",
                        cells[a], "xyz"[a], d.rank(), g + stagger[a], stagger[a] ? " and the shared face" : ""));
    }
  }

  /// The points of class e (ghosts owned by the rank at coords + e; e = 0: this rank's points).
  PointBox classBox(const std::array<int, 3>& e) const {
    PointBox b;
    for (int a = 0; a < 3; ++a) {
      if (e[a] < 0) {
        b.lo[a] = -g;
        b.hi[a] = 0;
      } else if (e[a] > 0) {
        b.lo[a] = own[a];
        b.hi[a] = points[a] + g;
      } else {
        b.lo[a] = lowShared[a] ? 0 : -g;
        b.hi[a] = upShared[a] ? own[a] : points[a] + g;
      }
    }
    return b;
  }

  /// This rank's points that the rank at coords + e holds as its ghosts of class -e.
  PointBox partnerBox(const std::array<int, 3>& e) const {
    PointBox b = classBox({0, 0, 0});
    for (int a = 0; a < 3; ++a) {
      if (e[a] > 0) {
        b.lo[a] = own[a] - g;
        b.hi[a] = own[a];
      } else if (e[a] < 0) {
        b.lo[a] = 0;
        b.hi[a] = g + stagger[a];
      }
    }
    return b;
  }
};

struct Direction {
  std::array<int, 3> e;
  int rank;
  int tag;  // the direction's index 0..26; the message from the rank at coords + e carries 26 - tag
};

/// The neighbour directions across Shared sides only (every non-zero component crosses a Shared side).
std::vector<Direction> sharedDirections(const Decomposition& d) {
  std::vector<Direction> out;
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        const std::array<int, 3> e{x, y, z};
        if (x == 0 && y == 0 && z == 0) continue;
        bool shared = true;
        for (int a = 0; a < 3; ++a)
          if (e[a] != 0 && d.side(a, e[a]) != Side::Shared) shared = false;
        if (!shared) continue;
        const auto c = d.coords();
        const int rank = d.rankAt({c[0] + x, c[1] + y, c[2] + z});
        out.push_back({e, rank, (x + 1) + 3 * (y + 1) + 9 * (z + 1)});
      }
  return out;
}

/// reverse = false: fillGhosts; true: sumGhosts.
void exchange(const std::vector<Field*>& fields, const Decomposition& d, bool reverse) {
  if (!d.distributed() || fields.size() == 0) return;
  const auto directions = sharedDirections(d);
  if (directions.empty()) return;
  std::vector<Axes> axes;
  axes.reserve(fields.size());
  for (Field* f : fields) axes.emplace_back(*f, d);

  const std::size_t nd = directions.size();
  std::vector<std::vector<double>> sendBuf(nd), recvBuf(nd);
  for (std::size_t q = 0; q < nd; ++q) {
    const auto& e = directions[q].e;
    std::size_t sendCount = 0, recvCount = 0;
    std::size_t fi = 0;
    for (Field* f : fields) {
      (void)f;
      const PointBox cls = axes[fi].classBox(e), partner = axes[fi].partnerBox(e);
      sendCount += (reverse ? cls : partner).count();
      recvCount += (reverse ? partner : cls).count();
      ++fi;
    }
    sendBuf[q].resize(sendCount);
    recvBuf[q].resize(recvCount);
  }

  const MPI_Comm comm = Environment::instance().communicator();
  std::vector<MPI_Request> requests(2 * nd, MPI_REQUEST_NULL);
  for (std::size_t q = 0; q < nd; ++q)
    MPI_Irecv(recvBuf[q].data(), static_cast<int>(recvBuf[q].size()), MPI_DOUBLE, directions[q].rank,
              26 - directions[q].tag, comm, &requests[q]);
  for (std::size_t q = 0; q < nd; ++q) {
    const auto& e = directions[q].e;
    double* out = sendBuf[q].data();
    std::size_t fi = 0;
    for (Field* f : fields) {
      double* data = f->data().data();
      if (reverse) {
        // The deposits in this direction's ghosts leave this rank: packed, then zeroed.
        forBox(*f, axes[fi].classBox(e), [&](std::size_t id) {
          *out++ = data[id];
          data[id] = 0.0;
        });
      } else {
        forBox(*f, axes[fi].partnerBox(e), [&](std::size_t id) { *out++ = data[id]; });
      }
      ++fi;
    }
    MPI_Isend(sendBuf[q].data(), static_cast<int>(sendBuf[q].size()), MPI_DOUBLE, directions[q].rank,
              directions[q].tag, comm, &requests[nd + q]);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);

  // Unpacked in the fixed direction order (sums: the same order on every run).
  for (std::size_t q = 0; q < nd; ++q) {
    const auto& e = directions[q].e;
    const double* in = recvBuf[q].data();
    std::size_t fi = 0;
    for (Field* f : fields) {
      double* data = f->data().data();
      if (reverse)
        forBox(*f, axes[fi].partnerBox(e), [&](std::size_t id) { data[id] += *in++; });
      else
        forBox(*f, axes[fi].classBox(e), [&](std::size_t id) { data[id] = *in++; });
      ++fi;
    }
  }
}

}  // namespace

void gatherField(const Field& local, const Decomposition& d, const CartesianGrid& wholeGrid, Field& whole) {
  if (!d.distributed()) {
    whole = local;
    return;
  }
  // This rank's class-0 points (x fastest), sent to rank 0 with their box in global indices.
  const Axes axes(local, d);
  const PointBox mine = axes.classBox({0, 0, 0});
  const auto offset = d.cellOffset();
  Bytes bytes;
  Packer pack(bytes);
  for (int a = 0; a < 3; ++a) {
    pack.put(mine.lo[a] + offset[a]);
    pack.put(mine.hi[a] + offset[a]);
  }
  forBox(local, mine, [&](std::size_t id) { pack.put(local.data()[id]); });
  const std::vector<Bytes> all = gatherToRoot(bytes);
  if (d.rank() != 0) {
    whole = Field();
    return;
  }
  whole = Field(wholeGrid, local.staggering());
  for (const Bytes& from : all) {
    Unpacker in(from);
    PointBox box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = in.get<int>();
      box.hi[a] = in.get<int>();
    }
    forBox(whole, box, [&](std::size_t id) { whole.data()[id] = in.get<double>(); });
  }
  // A periodic axis split among ranks: no rank's own points reach beyond the domain there (the
  // ends are cuts), so the whole grid's wrap-around points (ghosts, and the last face of a field
  // staggered along it) are copies of the other end, as one rank's periodic fill makes them.
  const int g = wholeGrid.ghosts;
  const auto& pts = whole.points();
  for (int a = 0; a < 3; ++a) {
    if (!(d.domain().periodic[a] && d.layout()[a] > 1)) continue;
    const int n = wholeGrid.cells[a];
    for (int k = -g; k < pts[2] + g; ++k)
      for (int j = -g; j < pts[1] + g; ++j)
        for (int i = -g; i < pts[0] + g; ++i) {
          std::array<int, 3> at{i, j, k};
          if (at[a] >= 0 && at[a] < n) continue;
          const std::size_t to = whole.index(i, j, k);
          at[a] = ((at[a] % n) + n) % n;
          whole.data()[to] = whole(at[0], at[1], at[2]);
        }
  }
}

void extractBox(const Field& whole, const Decomposition& d, Field& local) {
  const auto offset = d.distributed() ? d.cellOffset() : std::array<int, 3>{0, 0, 0};
  const int g = local.grid().ghosts;
  const auto& pts = local.points();
  for (int k = -g; k < pts[2] + g; ++k)
    for (int j = -g; j < pts[1] + g; ++j) {
      const std::size_t to = local.index(-g, j, k), from = whole.index(-g + offset[0], j + offset[1], k + offset[2]);
      for (int i = 0; i < pts[0] + 2 * g; ++i) local.data()[to + static_cast<std::size_t>(i)] = whole.data()[from + static_cast<std::size_t>(i)];
    }
}

void fillGhosts(Field& f, const Decomposition& d) { exchange(std::vector<Field*>{&f}, d, false); }
void fillGhosts(std::initializer_list<Field*> fields, const Decomposition& d) { exchange(std::vector<Field*>(fields), d, false); }
void fillGhosts(const std::vector<Field*>& fields, const Decomposition& d) { exchange(fields, d, false); }
void sumGhosts(Field& f, const Decomposition& d) { exchange(std::vector<Field*>{&f}, d, true); }
void sumGhosts(std::initializer_list<Field*> fields, const Decomposition& d) { exchange(std::vector<Field*>(fields), d, true); }
void sumGhosts(const std::vector<Field*>& fields, const Decomposition& d) { exchange(fields, d, true); }

}  // namespace gf::parallel
