#include "parallel/decomposition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gf::parallel {

Decomposition::Decomposition(const Domain& domain, Layout layout, int ranks, int rank, std::array<int, 3> cells)
    : domain_(domain), rank_(rank) {
  if (layout == Layout{0, 0, 0}) layout = autoLayout(domain, ranks, cells);
  for (int a = 0; a < 3; ++a)
    if (layout[a] < 1) throw std::invalid_argument(fmt::format("decomposition [{}, {}, {}]: every entry must be >= 1",
                                                               layout[0], layout[1], layout[2]));
  if (layout[0] * layout[1] * layout[2] != ranks)
    throw std::invalid_argument(fmt::format("decomposition [{}, {}, {}] makes {} boxes for {} ranks", layout[0],
                                            layout[1], layout[2], layout[0] * layout[1] * layout[2], ranks));
  layout_ = layout;
  const bool grid = cells[0] > 0 && cells[1] > 0 && cells[2] > 0;
  for (int a = 0; a < 3; ++a) {
    const int p = layout[a];
    cut_[a].resize(static_cast<std::size_t>(p) + 1);
    if (grid) {
      if (p > cells[a])
        throw std::invalid_argument(fmt::format("decomposition: {} ranks along {} but only {} cells", p, "xyz"[a],
                                                cells[a]));
      cellCut_[a].resize(static_cast<std::size_t>(p) + 1);
      const double h = (domain.max[a] - domain.min[a]) / cells[a];
      for (int k = 0; k <= p; ++k) {
        // Cells as evenly as possible: the first (cells % p) boxes get one cell more.
        const int base = cells[a] / p, extra = cells[a] % p;
        const int c = k * base + std::min(k, extra);
        cellCut_[a][static_cast<std::size_t>(k)] = c;
        cut_[a][static_cast<std::size_t>(k)] = k == p ? domain.max[a] : domain.min[a] + c * h;
      }
    } else {
      for (int k = 0; k <= p; ++k)
        cut_[a][static_cast<std::size_t>(k)] =
            k == p ? domain.max[a] : domain.min[a] + (domain.max[a] - domain.min[a]) * k / p;
    }
  }
  coords_ = coordsOf(rank);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int r = rankAt({coords_[0] + dx, coords_[1] + dy, coords_[2] + dz});
        if (r >= 0 && r != rank_) neighbours_.push_back(r);
      }
  std::sort(neighbours_.begin(), neighbours_.end());
  neighbours_.erase(std::unique(neighbours_.begin(), neighbours_.end()), neighbours_.end());
}

Decomposition::Decomposition(const Domain& domain, std::vector<Box> boxes, int rank, double reach)
    : domain_(domain), layout_{static_cast<int>(boxes.size()), 1, 1}, rank_(rank), explicit_(true),
      boxes_(std::move(boxes)) {
  const int n = static_cast<int>(boxes_.size());
  if (n < 1 || rank < 0 || rank >= n)
    throw std::invalid_argument(fmt::format("decomposition: {} boxes for rank {}", n, rank));
  // Tiling: every box inside the domain, no two overlapping, and their volumes adding up to the
  // domain's (to round-off): then every position of the domain lies in exactly one box.
  const Vec3 size = domain.size();
  const double whole = size.x * size.y * size.z;
  double volume = 0.0;
  for (int r = 0; r < n; ++r) {
    const Box& b = boxes_[static_cast<std::size_t>(r)];
    for (int a = 0; a < 3; ++a)
      if (!(b.lower[a] >= domain.min[a] && b.upper[a] <= domain.max[a] && b.lower[a] <= b.upper[a]))
        throw std::invalid_argument(
            fmt::format("decomposition: box of rank {} ([{}, {}] along {}) is not inside the domain", r, b.lower[a],
                        b.upper[a], "xyz"[a]));
    const Vec3 w = b.upper - b.lower;
    volume += w.x * w.y * w.z;
    for (int q = 0; q < r; ++q) {
      const Box& c = boxes_[static_cast<std::size_t>(q)];
      bool overlap = true;
      for (int a = 0; a < 3; ++a) overlap = overlap && b.lower[a] < c.upper[a] && c.lower[a] < b.upper[a];
      if (overlap) throw std::invalid_argument(fmt::format("decomposition: the boxes of ranks {} and {} overlap", q, r));
    }
  }
  if (std::abs(volume - whole) > 1e-9 * whole)
    throw std::invalid_argument(
        fmt::format("decomposition: the boxes cover {:.6g} of the domain's volume, not all of it", volume / whole));
  std::vector<int> all(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) all[static_cast<std::size_t>(r)] = r;
  buildTree(std::move(all));
  setReach(reach);
}

int Decomposition::buildTree(std::vector<int> boxes) {
  const int at = static_cast<int>(tree_.size());
  tree_.emplace_back();
  // A plane along which every box lies wholly on one side, with boxes on both: the cut of the
  // bisection that made them (the first found, axis by axis, at the boxes' lower faces).
  for (int a = 0; a < 3 && boxes.size() > 1; ++a)
    for (int candidate : boxes) {
      const double v = boxes_[static_cast<std::size_t>(candidate)].lower[a];
      std::vector<int> below, above;
      for (int b : boxes) {
        const Box& box = boxes_[static_cast<std::size_t>(b)];
        if (box.upper[a] <= v) below.push_back(b);
        else if (box.lower[a] >= v) above.push_back(b);
        else break;
      }
      if (below.empty() || below.size() + above.size() != boxes.size()) continue;
      const int left = buildTree(std::move(below));
      const int right = buildTree(std::move(above));
      Node& node = tree_[static_cast<std::size_t>(at)];
      node.axis = a;
      node.cut = v;
      node.left = left;
      node.right = right;
      return at;
    }
  tree_[static_cast<std::size_t>(at)].boxes = std::move(boxes);
  return at;
}

std::vector<Box> Decomposition::boxes() const {
  if (explicit_) return boxes_;
  std::vector<Box> all(static_cast<std::size_t>(ranks()));
  for (int r = 0; r < ranks(); ++r) all[static_cast<std::size_t>(r)] = {lower(r), upper(r)};
  return all;
}

void Decomposition::setReach(double reach) {
  reach_ = reach;
  if (!explicit_) return;
  // Ranks whose boxes come within `reach` of this one along every axis: the gap between the two
  // ranges, the smallest over the periodic images on periodic axes.
  const Box& mine = boxes_[static_cast<std::size_t>(rank_)];
  neighbours_.clear();
  for (int r = 0; r < ranks(); ++r) {
    if (r == rank_) continue;
    const Box& other = boxes_[static_cast<std::size_t>(r)];
    bool near = true;
    for (int a = 0; a < 3 && near; ++a) {
      auto gap = [&](double shift) {
        return std::max({0.0, other.lower[a] + shift - mine.upper[a], mine.lower[a] - other.upper[a] - shift});
      };
      double g = gap(0.0);
      if (domain_.periodic[a]) {
        const double length = domain_.max[a] - domain_.min[a];
        g = std::min({g, gap(-length), gap(length)});
      }
      near = g <= reach;
    }
    if (near) neighbours_.push_back(r);
  }
}

int Decomposition::explicitOwnerOf(const Vec3& x) const {
  // Positions outside the domain count as on its nearest face.
  Vec3 y = x;
  for (int a = 0; a < 3; ++a) y[a] = std::clamp(y[a], domain_.min[a], domain_.max[a]);
  auto holds = [&](int r) {
    const Box& b = boxes_[static_cast<std::size_t>(r)];
    for (int a = 0; a < 3; ++a) {
      const bool in = y[a] >= b.lower[a] && (y[a] < b.upper[a] || b.upper[a] == domain_.max[a]);
      if (!in) return false;
    }
    return true;
  };
  // The boxes tile the domain, so one box holds y: down the cut tree (a position on a cut plane
  // goes above it, as the boxes' ranges are half-open), then among the leaf's boxes.
  int node = 0;
  while (tree_[static_cast<std::size_t>(node)].axis >= 0) {
    const Node& n = tree_[static_cast<std::size_t>(node)];
    node = y[n.axis] < n.cut ? n.left : n.right;
  }
  const std::vector<int>& leaf = tree_[static_cast<std::size_t>(node)].boxes;
  for (int r : leaf)
    if (holds(r)) return r;
  return leaf.front();  // (round-off at a face: the leaf's first box)
}

Layout Decomposition::autoLayout(const Domain& domain, int ranks, std::array<int, 3> cells) {
  const Vec3 size = domain.size();
  const bool grid = cells[0] > 0 && cells[1] > 0 && cells[2] > 0;
  Layout best{0, 0, 0};
  double bestArea = std::numeric_limits<double>::infinity();
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px) continue;
    for (int py = 1; py <= ranks / px; ++py) {
      if ((ranks / px) % py) continue;
      const int pz = ranks / px / py;
      const Layout l{px, py, pz};
      bool fits = true;
      double area = 0.0;
      for (int a = 0; a < 3; ++a) {
        if (grid && l[a] > 1 && cells[a] < kMinCellsPerRank * l[a]) fits = false;
        const double face = size[(a + 1) % 3] * size[(a + 2) % 3];
        const int cuts = domain.periodic[a] ? (l[a] > 1 ? l[a] : 0) : l[a] - 1;
        area += cuts * face;
      }
      // Ties: the first layout in this loop's order (fewest ranks along x, then y); a fixed rule
      // keeps the choice the same on every rank.
      if (fits && area < bestArea * (1.0 - 1e-12)) {
        bestArea = area;
        best = l;
      }
    }
  }
  if (best[0] == 0)
    throw std::invalid_argument(fmt::format("no decomposition of {} ranks fits the grid of {} x {} x {} cells", ranks,
                                            cells[0], cells[1], cells[2]));
  return best;
}

int Decomposition::rankAt(std::array<int, 3> c) const {
  for (int a = 0; a < 3; ++a) {
    if (c[a] < 0 || c[a] >= layout_[a]) {
      if (!domain_.periodic[a]) return -1;
      c[a] = ((c[a] % layout_[a]) + layout_[a]) % layout_[a];
    }
  }
  return c[0] + layout_[0] * (c[1] + layout_[1] * c[2]);
}

std::array<int, 3> Decomposition::coordsOf(int rank) const {
  return {rank % layout_[0], (rank / layout_[0]) % layout_[1], rank / (layout_[0] * layout_[1])};
}

int Decomposition::ownerOf(const Vec3& x) const {
  if (explicit_) return explicitOwnerOf(x);
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const auto& cuts = cut_[a];
    // First cut above x, minus one: the box [cut_k, cut_k+1) holding x.
    const auto k = static_cast<int>(std::upper_bound(cuts.begin() + 1, cuts.end() - 1, x[a]) - (cuts.begin() + 1));
    c[a] = std::clamp(k, 0, layout_[a] - 1);
  }
  return c[0] + layout_[0] * (c[1] + layout_[1] * c[2]);
}

Vec3 Decomposition::lower(int rank) const {
  if (explicit_) return boxes_[static_cast<std::size_t>(rank)].lower;
  const auto c = coordsOf(rank);
  return {cut(0, c[0]), cut(1, c[1]), cut(2, c[2])};
}

Vec3 Decomposition::upper(int rank) const {
  if (explicit_) return boxes_[static_cast<std::size_t>(rank)].upper;
  const auto c = coordsOf(rank);
  return {cut(0, c[0] + 1), cut(1, c[1] + 1), cut(2, c[2] + 1)};
}

std::array<int, 3> Decomposition::cellOffset(int rank) const {
  if (!gridded()) return {0, 0, 0};
  const auto c = coordsOf(rank);
  return {cellCut_[0][static_cast<std::size_t>(c[0])], cellCut_[1][static_cast<std::size_t>(c[1])],
          cellCut_[2][static_cast<std::size_t>(c[2])]};
}

std::array<int, 3> Decomposition::cellCount(int rank) const {
  if (!gridded()) return {0, 0, 0};
  const auto c = coordsOf(rank);
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a)
    n[a] = cellCut_[a][static_cast<std::size_t>(c[a]) + 1] - cellCut_[a][static_cast<std::size_t>(c[a])];
  return n;
}

Side Decomposition::side(int axis, int dir) const {
  if (explicit_) {
    const Box& b = boxes_[static_cast<std::size_t>(rank_)];
    const bool onDomainFace = dir < 0 ? b.lower[axis] == domain_.min[axis] : b.upper[axis] == domain_.max[axis];
    if (!onDomainFace) return Side::Shared;
    if (!domain_.periodic[axis]) return Side::Physical;
    const bool whole = b.lower[axis] == domain_.min[axis] && b.upper[axis] == domain_.max[axis];
    return whole ? Side::Periodic : Side::Shared;
  }
  const int next = coords_[axis] + dir;
  if (next >= 0 && next < layout_[axis]) return Side::Shared;
  return domain_.periodic[axis] ? (layout_[axis] > 1 ? Side::Shared : Side::Periodic) : Side::Physical;
}

int Decomposition::neighbourAcross(int axis, int dir) const {
  if (explicit_) return -1;
  std::array<int, 3> c = coords_;
  c[axis] += dir;
  return rankAt(c);
}

Vec3 Decomposition::distanceToBox(const Vec3& x, int rank) const {
  const Vec3 lo = lower(rank), hi = upper(rank);
  Vec3 d;
  for (int a = 0; a < 3; ++a) {
    auto along = [&](double v) { return v < lo[a] ? lo[a] - v : (v > hi[a] ? v - hi[a] : 0.0); };
    double best = along(x[a]);
    if (domain_.periodic[a]) {
      const double length = domain_.max[a] - domain_.min[a];
      best = std::min({best, along(x[a] - length), along(x[a] + length)});
    }
    d[a] = best;
  }
  return d;
}

double Decomposition::smallestBoxWidth() const {
  double w = std::numeric_limits<double>::infinity();
  if (explicit_) {
    if (ranks() == 1) return w;
    for (const Box& b : boxes_)
      for (int a = 0; a < 3; ++a)
        if (!(b.lower[a] == domain_.min[a] && b.upper[a] == domain_.max[a])) w = std::min(w, b.upper[a] - b.lower[a]);
    return w;
  }
  for (int a = 0; a < 3; ++a)
    if (layout_[a] > 1)
      for (int k = 0; k < layout_[a]; ++k) w = std::min(w, cut(a, k + 1) - cut(a, k));
  return w;
}

std::string Decomposition::describe() const {
  if (explicit_) return fmt::format("{} boxes", ranks());
  return fmt::format("{} x {} x {}", layout_[0], layout_[1], layout_[2]);
}

Decomposition Decomposition::withCellCuts(const std::array<std::vector<int>, 3>& cuts) const {
  if (explicit_ || !gridded()) throw std::invalid_argument("decomposition: cell cuts need the Cartesian form with a grid");
  Decomposition d = *this;
  for (int a = 0; a < 3; ++a) {
    const std::vector<int>& c = cuts[static_cast<std::size_t>(a)];
    const std::vector<int>& old = cellCut_[static_cast<std::size_t>(a)];
    if (c.size() != old.size() || c.front() != 0 || c.back() != old.back() || !std::is_sorted(c.begin(), c.end()) ||
        std::adjacent_find(c.begin(), c.end()) != c.end())
      throw std::invalid_argument(fmt::format("decomposition: {} cell cuts along {} do not cut {} cells into {} boxes",
                                              c.size(), "xyz"[a], old.back(), layout_[a]));
    const double h = (domain_.max[a] - domain_.min[a]) / old.back();
    d.cellCut_[static_cast<std::size_t>(a)] = c;
    for (std::size_t k = 0; k < c.size(); ++k)
      d.cut_[static_cast<std::size_t>(a)][k] = k + 1 == c.size() ? domain_.max[a] : domain_.min[a] + c[k] * h;
  }
  return d;
}

std::vector<int> Decomposition::balancedCuts(const std::vector<double>& planeCost, int parts, int minCells) {
  const int n = static_cast<int>(planeCost.size());
  if (parts < 1 || n < parts * minCells)
    throw std::invalid_argument(fmt::format("decomposition: {} planes cannot be cut into {} parts of {} or more",
                                            n, parts, minCells));
  std::vector<double> running(static_cast<std::size_t>(n) + 1, 0.0);  // cost of planes [0, i)
  for (int i = 0; i < n; ++i) running[static_cast<std::size_t>(i) + 1] = running[static_cast<std::size_t>(i)] + planeCost[static_cast<std::size_t>(i)];
  const double total = running.back();
  std::vector<int> cuts{0};
  for (int k = 1; k < parts; ++k) {
    // within the planes that leave every part its minimum
    const int lo = cuts.back() + minCells, hi = n - (parts - k) * minCells;
    const double target = total * k / parts;
    int best = lo;
    for (int c = lo; c <= hi; ++c)
      if (std::abs(running[static_cast<std::size_t>(c)] - target) < std::abs(running[static_cast<std::size_t>(best)] - target))
        best = c;
    cuts.push_back(best);
  }
  cuts.push_back(n);
  return cuts;
}

}  // namespace gf::parallel
