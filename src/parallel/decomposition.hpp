#pragma once
// How the domain is split among the MPI ranks: one box per rank on a Cartesian layout of
// px x py x pz ranks (domain.decomposition). This is the one topology object every subsystem asks:
// the global box, the rank's own box and (on a grid) its cell offset, the neighbour ranks, and for
// each side of the rank's box whether it is a physical boundary, a periodic boundary of the
// domain, or shared with another rank.
//
// Cuts: with a fluid grid the boxes are whole cells (cut k along axis a at cell cellCut[a][k],
// cells split as evenly as possible); without one the boxes are equal slabs of the domain. A
// position belongs to the box whose half-open range [cut_k, cut_k+1) holds it (the last box of a
// bounded axis also holds its upper face), so ownership is a pure function of the position and
// the same on every rank.
//
// A second form holds explicit boxes, one per rank (from a recursive coordinate bisection of the
// particles: parallel/rebalance.hpp), which tile the domain. A position then belongs to the box
// whose half-open ranges [lower, upper) hold it (a box's upper face on the domain's upper face
// included), the neighbours are the ranks whose boxes come within a reach of this one (periodic
// images included; setReach), and there is no grid and no single rank across a face. The DEM asks
// both forms the same things (ownerOf, distanceToBox, neighbourRanks, smallestBoxWidth); the fluid
// works on the Cartesian form only.
//
// Pure data and arithmetic: no MPI here (the verbs that move data are in this directory's other
// files), so the layout can be built and tested for any rank count in one process.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/vec3.hpp"

namespace gf::parallel {

/// What lies beyond one face of a rank's box.
enum class Side { Physical, Periodic, Shared };

/// Cells a rank's box needs along a split axis of a grid: the two ghost layers and the shared face
/// (parallel/halo.hpp).
inline constexpr int kMinCellsPerRank = 3;

/// The layout asked for in the case: {0, 0, 0} = auto.
using Layout = std::array<int, 3>;

/// An axis-aligned box [lower, upper).
struct Box {
  Vec3 lower, upper;
};

class Decomposition {
 public:
  /// One rank owning an empty domain (replace before use).
  Decomposition() : Decomposition(Domain{}, {1, 1, 1}, 1, 0) {}
  /// `ranks` boxes on the layout `layout` ({0,0,0}: chosen by autoLayout), for the rank `rank`.
  /// `cells`: the fluid grid's cells per axis ({0,0,0}: no grid; equal slabs of the domain).
  /// Throws std::invalid_argument when the layout does not multiply to `ranks`, or an axis has
  /// more ranks than cells.
  Decomposition(const Domain& domain, Layout layout, int ranks, int rank, std::array<int, 3> cells = {0, 0, 0});
  /// Explicit boxes, boxes[r] for rank r, for the rank `rank`; neighbours within `reach` (m).
  /// Throws std::invalid_argument when the boxes do not tile the domain (a box outside it, two
  /// boxes overlapping, or volumes that do not add up to the domain's).
  Decomposition(const Domain& domain, std::vector<Box> boxes, int rank, double reach = 0.0);

  /// The layout with least halo surface for `ranks` ranks: among all px*py*pz = ranks with at
  /// least kMinCellsPerRank cells per rank along each split axis, the one whose cuts have the
  /// smallest total area (a cut across a periodic axis counts once per rank, a bounded one once per
  /// interior cut).
  static Layout autoLayout(const Domain& domain, int ranks, std::array<int, 3> cells = {0, 0, 0});

  const Domain& domain() const { return domain_; }
  const Layout& layout() const { return layout_; }
  /// Cartesian form: px x py x pz; explicit boxes: {ranks, 1, 1} (no layout).
  int ranks() const { return explicit_ ? static_cast<int>(boxes_.size()) : layout_[0] * layout_[1] * layout_[2]; }
  /// Whether this is the form of explicit boxes.
  bool explicitBoxes() const { return explicit_; }
  /// Every rank's box, indexed by rank (both forms).
  std::vector<Box> boxes() const;
  /// Explicit boxes: the neighbours become the ranks whose boxes come within `reach` of this one
  /// (periodic images included); the Cartesian form keeps its 26 neighbours. Every rank must pass
  /// the same reach (the neighbour lists then list each other).
  void setReach(double reach);
  double reach() const { return reach_; }
  int rank() const { return rank_; }
  bool distributed() const { return ranks() > 1; }
  /// This rank's position in the layout (Cartesian form; {0, 0, 0} for explicit boxes).
  const std::array<int, 3>& coords() const { return coords_; }

  /// Rank at layout coordinates c; periodic axes wrap, -1 beyond a bounded axis (Cartesian form).
  int rankAt(std::array<int, 3> c) const;
  std::array<int, 3> coordsOf(int rank) const;
  /// The rank whose box holds position x (positions outside a bounded axis go to the nearest box).
  int ownerOf(const Vec3& x) const;
  /// Box of a rank (this rank's by default).
  Vec3 lower(int rank) const;
  Vec3 upper(int rank) const;
  Vec3 lower() const { return lower(rank_); }
  Vec3 upper() const { return upper(rank_); }
  /// With a grid: the first global cell and the number of cells of a rank's box along each axis.
  std::array<int, 3> cellOffset(int rank) const;
  std::array<int, 3> cellCount(int rank) const;
  std::array<int, 3> cellOffset() const { return cellOffset(rank_); }
  std::array<int, 3> cellCount() const { return cellCount(rank_); }
  bool gridded() const { return !cellCut_[0].empty(); }

  /// What lies beyond the lower (dir = -1) or upper (dir = +1) face of this rank's box along axis.
  Side side(int axis, int dir) const;
  /// The rank across that face (-1 beyond a physical face; this rank itself across a periodic face
  /// of an axis with one rank). Explicit boxes: -1 (no single rank; ask neighbourRanks()).
  int neighbourAcross(int axis, int dir) const;
  /// The distinct other ranks among the 26 face, edge and corner neighbours (ascending); explicit
  /// boxes: the other ranks whose boxes come within reach() (ascending).
  const std::vector<int>& neighbourRanks() const { return neighbours_; }

  /// Per axis, the distance from x to the box of `rank` along that axis (0 inside its range), with
  /// the nearest periodic image on periodic axes. A particle whose three distances are below a
  /// cut-off may interact with particles owned by that rank.
  Vec3 distanceToBox(const Vec3& x, int rank) const;
  /// The smallest box width of any rank along any decomposed axis (m); +inf on one rank. Explicit
  /// boxes: along every axis that a box does not span whole.
  double smallestBoxWidth() const;

  /// With a grid (Cartesian form): the same layout and rank with the cell cuts `cuts` (per axis
  /// layout[a] + 1 ascending cell indices from 0 to the axis's cells; the boxes between them, the
  /// neighbours unchanged). Throws std::invalid_argument for cuts that do not fit the layout.
  Decomposition withCellCuts(const std::array<std::vector<int>, 3>& cuts) const;
  /// The cell cuts of each axis (Cartesian form with a grid).
  const std::array<std::vector<int>, 3>& cellCuts() const { return cellCut_; }
  /// Cuts of `planeCost.size()` cell planes into `parts` consecutive parts of at least `minCells`
  /// planes each whose costs are as even as the planes allow: cut k at the plane boundary where the
  /// running cost comes closest to k / parts of the total (0 and the plane count at the ends).
  /// Pure; the same result on every rank for the same costs.
  static std::vector<int> balancedCuts(const std::vector<double>& planeCost, int parts, int minCells);

  /// "2 x 1 x 1" for messages; "4 boxes" for explicit boxes.
  std::string describe() const;

 private:
  double cut(int axis, int k) const { return cut_[axis][static_cast<std::size_t>(k)]; }

  Domain domain_{};
  Layout layout_{1, 1, 1};
  int rank_ = 0;
  std::array<int, 3> coords_{0, 0, 0};
  std::array<std::vector<double>, 3> cut_{std::vector<double>{}, {}, {}};  // layout[a] + 1 coordinates
  std::array<std::vector<int>, 3> cellCut_{};  // layout[a] + 1 cell indices (gridded only)
  std::vector<int> neighbours_;
  // Explicit boxes (explicit_): one per rank, and the reach their neighbours were found with.
  bool explicit_ = false;
  std::vector<Box> boxes_;
  double reach_ = 0.0;
  int explicitOwnerOf(const Vec3& x) const;
  // A cut tree over the explicit boxes (ownerOf in O(log ranks)): a node splits its boxes by the
  // plane x[axis] = cut into those below (left) and those above (right); a leaf (axis -1) holds
  // boxes that no plane separates (one box, for the boxes of a bisection).
  struct Node {
    int axis = -1;
    double cut = 0.0;
    int left = -1, right = -1;
    std::vector<int> boxes;
  };
  std::vector<Node> tree_;
  int buildTree(std::vector<int> boxes);
};

}  // namespace gf::parallel
