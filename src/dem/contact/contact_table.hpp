#pragma once
// Materials and the composed contact model of a case (sections `materials` and `contact`),
// resolved into a dense table of per-pair coefficients indexed by material type.
#include <memory>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "dem/contact/contact_law.hpp"

namespace gf::dem {

/// Name of the built-in rigid wall material (infinite E; default for walls without `material`).
inline constexpr const char* kRigidMaterial = "rigid";

class ContactTable {
 public:
  ContactTable() = default;
  /// Reads `materials` and `contact` from the case root.
  explicit ContactTable(Params& root);

  const std::vector<Material>& materials() const { return materials_; }
  /// Index of a material by name, or -1.
  int materialIndex(const std::string& name) const;
  /// Reads a material name key from `p` and returns its index (error names the valid ones).
  int readMaterial(Params& p, const Key& k, const std::string& defaultName = "") const;

  const PairCoefficients& pair(int a, int b) const { return table_[a * count_ + b]; }
  const PairCoefficients* data() const { return table_.data(); }
  int count() const { return count_; }

  NormalLaw normalLaw() const { return normalLaw_; }
  RollingLaw rollingLaw() const { return rollingLaw_; }
  CohesionLaw cohesionLaw() const { return cohesionLaw_; }

  /// Sets the table directly (tests, benchmarks): recomputes all pairs with the given laws.
  void configure(std::vector<Material> materials, NormalLaw law, RollingLaw rolling, CohesionLaw cohesion,
                 const PairProperties& allPairs, double hookeStiffness = 1e4, double rollingDamping = 0.3);

 private:
  void computePair(int a, int b, const PairProperties& p);
  void addRigidMaterial();
  std::vector<Material> materials_;
  std::vector<PairCoefficients> table_;
  int count_ = 0;
  NormalLaw normalLaw_ = NormalLaw::HertzMindlin;
  RollingLaw rollingLaw_ = RollingLaw::None;
  CohesionLaw cohesionLaw_ = CohesionLaw::None;
  std::shared_ptr<ContactLawModel> lawModel_;
  double rollingDamping_ = 0.0;
};

/// E* and G* of a pair (Di Renzo & Di Maio 2004 eqs. 5, 15).
double effectiveYoungs(const Material& a, const Material& b);
double effectiveShear(const Material& a, const Material& b);

}  // namespace gf::dem
