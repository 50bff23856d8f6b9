#pragma once
// A closed triangle mesh (an STL file) as a fixed resolved body (resolved.bodies[].shape: stl,
// docs/resolved.md sec. 1-2): the fraction of each cell and face control volume it covers, for the
// same forcing and load sums as the analytic sphere and cylinder (forcing.hpp).
//
// The fraction comes from sub-cell samples: n per cell along each axis (resolved.bodies[].samples, even),
// at the centres of the n^3 sub-cells, each inside or outside the mesh by the parity of the mesh's
// crossings along a line parallel to x through it (a closed mesh: odd on the side towards -x inside),
// whatever the triangles' orientation. One line serves a whole row of samples: the crossings of the
// line are found once (the triangles binned by their y-z extent), sorted, and the row classified in
// one pass. The lines are shifted by a small generic offset in y and z (about 1e-7 of a sample
// spacing, irrational multiples) so that no line runs exactly through an edge or vertex of a mesh
// aligned with the grid; the edge functions are evaluated with the edge's vertices in a canonical
// order, so the two triangles sharing an edge agree on which side of it a line passes.
// The samples are counted per half cell, so that a cell (two half cells along each axis) and the
// control volume of a face (shifted by half a cell along its normal) are sums of eight counts; the
// counts are kept for this rank's box and one cell around it, once at start (the body is fixed).
// Fraction error: that of a midpoint rule for an indicator, about the sample spacing h / n over the
// cut cells' width; a box aligned with the sample grid is exact (tests/resolved/mesh_body_test.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "core/vec3.hpp"
#include "io/stl_reader.hpp"

namespace gf::resolved {

/// Volume enclosed by a closed triangle mesh, sum over the triangles of a . (b x c) / 6 (the
/// divergence theorem), as an absolute value (either orientation), m^3.
double meshVolume(const std::vector<io::Triangle>& triangles);
/// Centroid of the volume a closed mesh encloses (tetrahedra from the origin), m.
Vec3 meshCentroid(const std::vector<io::Triangle>& triangles);

/// x of the crossings of the line {(x, y, z): x real} with the triangles (sorted ascending). A
/// triangle whose projection on y-z has no area (parallel to x) is not crossed.
std::vector<double> lineCrossings(const std::vector<io::Triangle>& triangles, const std::vector<std::uint32_t>& which,
                                  double y, double z);

class MeshBody {
 public:
  /// Counts the samples of the cells of `grid` (this rank's) and one cell around it, `samples` per
  /// cell along each axis (even, >= 2).
  MeshBody(std::vector<io::Triangle> triangles, const CartesianGrid& grid, int samples);

  /// Fraction of the box [lo, hi] covered: a cell of the grid or a face's control volume (a box of
  /// one cell shifted by half a cell along some axes). 0 outside the counted region; a box not on
  /// the half-cell lattice is sampled directly (slower).
  double fraction(const Vec3& lo, const Vec3& hi) const;
  /// Whether the point is inside the mesh (the parity of the crossings towards -x).
  bool contains(const Vec3& p) const;
  /// Distance from p to the nearest point of the surface, m.
  double distance(const Vec3& p) const;

  const Vec3& lower() const { return lo_; }  // bounding box of the mesh
  const Vec3& upper() const { return hi_; }
  double volume() const { return volume_; }
  Vec3 centroid() const { return centroid_; }
  std::size_t triangleCount() const { return triangles_.size(); }

 private:
  /// The triangles whose y-z extent contains (y, z).
  const std::vector<std::uint32_t>& binOf(double y, double z) const;
  /// Inside flags of the points x0 + s dx, s = 0..count-1, on the line at (y, z).
  void classifyRow(double x0, double dx, int count, double y, double z, std::vector<std::uint8_t>& inside) const;

  std::vector<io::Triangle> triangles_;
  Vec3 lo_, hi_;
  double volume_ = 0.0;
  Vec3 centroid_;
  CartesianGrid grid_;
  int samples_ = 8;
  // Line shift (y, z), m.
  double shiftY_ = 0.0, shiftZ_ = 0.0;
  // Triangle bins over y-z: one per cell of the grid's spacing, over the mesh's extent.
  Vec3 binOrigin_;
  std::array<int, 2> bins_{0, 0};
  std::vector<std::vector<std::uint32_t>> binTriangles_;
  std::vector<std::uint32_t> noTriangles_;
  // Counts of inside samples per half cell: half cell H along axis a spans
  // [origin + H h / 2, origin + (H + 1) h / 2); H from first_[a], extent_[a] of them.
  std::array<int, 3> first_{0, 0, 0}, extent_{0, 0, 0};
  std::vector<std::uint32_t> counts_;
};

}  // namespace gf::resolved
