#pragma once
// ParaView-readable VTK XML output: particles as PolyData-free UnstructuredGrid (.vtu, one vertex
// per particle), cell fields as ImageData (.vti), and .pvd collections with physical times.
// Arrays are written in binary (base64, UInt64 headers), so files are compact yet plain XML.
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/vec3.hpp"

namespace gf::io {

/// A named array for VTK output: n tuples of `components` doubles, or int64 values.
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<double> real;        // used when !isInteger
  std::vector<std::int64_t> integer;  // used when isInteger
  bool isInteger = false;
};

/// Base64 of raw bytes (RFC 4648) and its inverse.
std::string base64Encode(const void* data, std::size_t size);
std::vector<unsigned char> base64Decode(const std::string& text);

/// The per-particle arrays a particle file holds, as views of the caller's arrays (one entry per
/// particle in each). io knows no solver type, so that every part of the code may write output.
struct ParticleArrays {
  std::span<const std::int64_t> id;
  std::span<const std::int32_t> type;
  std::span<const double> radius;            // m
  std::span<const Vec3> position;            // m
  std::span<const Vec3> velocity;            // m/s
  std::span<const Vec3> angularVelocity;     // rad/s
  std::span<const Vec3> force;               // N
};

/// Particle file: points = centres; point data id, type, radius, velocity, angular_velocity, force.
/// Throws gf::Error if the arrays differ in length.
std::string particlesVtu(const ParticleArrays& particles);
/// The same for any structure of arrays with these members (dem::ParticleSet).
template <class ParticleStorage>
std::string particlesVtu(const ParticleStorage& p) {
  return particlesVtu(ParticleArrays{p.id, p.type, p.radius, p.position, p.velocity, p.angularVelocity, p.force});
}
/// The interior values of a cell-centred field, in VTK order (x fastest).
VtkArray cellArray(const std::string& name, const Field& field);
/// Cell-centred fields on a grid (interior cells only).
std::string cellFieldsVti(const CartesianGrid& grid, const std::vector<VtkArray>& cellArrays);
/// One rank's piece of a grid split among ranks: `grid` is the rank's box of cells, which starts at
/// global cell `offset` of the whole grid `whole` (the piece's extent is written in the whole
/// grid's index space, as .pvti readers expect).
std::string cellFieldsVtiPiece(const CartesianGrid& grid, const std::array<int, 3>& offset, const CartesianGrid& whole,
                               const std::vector<VtkArray>& cellArrays);

/// The parallel files that bind one piece per rank into one data set for ParaView: particles
/// (.pvtu, the arrays of particlesVtu) and cell fields (.pvti; `extents` per piece: offset and
/// cell counts in the whole grid). `pieces` are file names relative to the parallel file.
std::string particlesPvtu(const std::vector<std::string>& pieces);
std::string cellFieldsPvti(const CartesianGrid& whole, const std::vector<std::string>& pieces,
                           const std::vector<std::array<int, 6>>& extents, const std::vector<VtkArray>& arrayKinds);

/// All DataArrays of a VTK XML file written by this module, decoded (for tests and post-processing).
std::map<std::string, VtkArray> readVtkArrays(const std::string& xml);

/// A .pvd collection (series of files with physical times), rewritten atomically on each add.
class PvdCollection {
 public:
  PvdCollection() = default;
  explicit PvdCollection(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& relativeFile);
  /// Drops entries after `time` (used when a run restarts from a checkpoint).
  void truncateAfter(double time);
  /// Re-reads an existing collection (restart).
  void load();
  const std::string& path() const { return path_; }
  std::size_t size() const { return entries_.size(); }

 private:
  void write() const;
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace gf::io
