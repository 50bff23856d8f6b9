#pragma once
// Particle insertion methods (by name: lattice, random_packing, rate, csv_file), one file each.
// insert() is called once at start-up (time 0, dt 0) and then every step; one-shot methods
// insert at the first call, rate-based ones over their time window.
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "core/registry.hpp"
#include "core/serialize.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/insertion/size_distribution.hpp"
#include "dem/particles.hpp"
#include "dem/random.hpp"

namespace gf::dem {

class OverlapGrid;

struct InsertionContext {
  ParticleSet& particles;  // new particles are appended here
  std::int64_t& nextId;
  const Domain& domain;
  /// Adds to `grid` the particles already in the run whose centre satisfies `near`, so that new
  /// ones are placed without overlap. On one rank these are the set's own particles; under MPI the
  /// particles every rank owns (a collective call: the inserters' states are the same on every
  /// rank, so every rank asks at the same moment).
  std::function<void(const std::function<bool(const Vec3&)>& near, OverlapGrid& grid)> addExisting;
};

/// The smallest sphere an insertion can make (material index and diameter, m): the DEM step is
/// checked against its Rayleigh time before the run starts, rate-based insertions included.
struct SmallestInserted {
  int material = -1;  // -1: the insertion makes no particles
  double diameter = 0.0;
};

class Inserter {
 public:
  virtual ~Inserter() = default;
  /// Inserts the particles due in (time, time + dt]; returns how many.
  virtual std::size_t insert(InsertionContext& ctx, double time, double dt) = 0;
  virtual SmallestInserted smallest() const = 0;
  /// The coarse-graining factor of the particles it makes (key coarse_graining; 0: not given, the
  /// coupling's coarse_grain_factor applies) and their material.
  virtual double coarseGraining() const { return 0.0; }
  virtual int material() const { return -1; }
  virtual void save(BinaryWriter& out) const = 0;
  virtual void load(BinaryReader& in) = 0;
};

/// Keys every insertion method shares: material, size distribution, initial velocity, seed.
struct InsertionCommon {
  int material = 0;
  double density = 2500.0;
  std::unique_ptr<SizeDistribution> size;
  Vec3 velocity;
  /// Coarse-graining factor alpha (seed 003 eq. 3.34): each particle is a parcel of alpha^3
  /// primary particles of diameter d / alpha (coupling/coarse_graining.hpp); 0: not given.
  double coarseGraining = 0.0;
  Random rng;
  /// Set by the System before constructing inserters (the registry passes only Params).
  static const ContactTable*& table();
  explicit InsertionCommon(Params& p);
  SmallestInserted smallest() const { return {material, size->minDiameter()}; }
};

/// Uniform grid of spheres for overlap checks during insertion.
class OverlapGrid {
 public:
  explicit OverlapGrid(double cellSize) : h_(cellSize) {}
  void add(const Vec3& x, double r);
  /// True if a sphere at x with radius r overlaps any stored sphere.
  bool overlaps(const Vec3& x, double r) const;

 private:
  std::int64_t key(int i, int j, int k) const {
    return (static_cast<std::int64_t>(i) * 2000003 + j) * 2000003 + k;
  }
  double h_;
  std::unordered_map<std::int64_t, std::vector<std::pair<Vec3, double>>> cells_;
};

}  // namespace gf::dem
