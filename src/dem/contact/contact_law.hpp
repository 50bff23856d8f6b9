#pragma once
// Contact model composition (the LAMMPS granular habit): a normal/tangential law, a rolling
// resistance model and a cohesion model, each chosen by name in the case file and each one file.
// The models only fill per-material-pair coefficients; the force loop is compiled once per
// combination (contact_kernel.hpp) and picked before the loop, so no virtual call per contact.
#include <limits>
#include <string>

#include "core/params.hpp"
#include "core/registry.hpp"

namespace gf::dem {

enum class NormalLaw { HertzMindlin, Hooke };
enum class RollingLaw { None, ConstantTorque, Epsd };
enum class CohesionLaw { None, SimplifiedJkr };

struct Material {
  std::string name;
  double density = 2500.0;     // kg/m^3
  double youngsModulus = 1e7;  // Pa
  double poissonRatio = 0.3;   // -
  bool isBuiltInRigid = false;  // the 'rigid' wall material added when the case defines none
  // Optional per-material interaction values (NaN = not given); a pair uses the mean of its two
  // materials' values where given, else the `contact` default, unless `contact.pairs` sets it.
  double restitution = std::numeric_limits<double>::quiet_NaN();
  double friction = std::numeric_limits<double>::quiet_NaN();
  double rollingFriction = std::numeric_limits<double>::quiet_NaN();
  double cohesionEnergyDensity = std::numeric_limits<double>::quiet_NaN();
};

/// Interaction parameters of one material pair (read from the case).
struct PairProperties {
  double restitution = 0.5;            // -
  double friction = 0.5;               // sliding friction coefficient mu
  double rollingFriction = 0.0;        // rolling friction coefficient mu_r
  double cohesionEnergyDensity = 0.0;  // J/m^3 (simplified JKR)
};

/// Everything the force loop needs for one material pair (derived once at start-up).
struct PairCoefficients {
  double effectiveYoungs = 0.0;   // E* = 1/((1-nu_i^2)/E_i + (1-nu_j^2)/E_j), Pa
  double effectiveShear = 0.0;    // G* = 1/(2(2-nu_i)(1+nu_i)/E_i + ...), Pa
  double normalStiffness = 0.0;   // Hooke k_n, N/m
  double tangentialStiffness = 0.0;  // Hooke k_t, N/m
  double damping = 0.0;           // dimensionless alpha: F_d = alpha sqrt(m* dF/d(delta)-scale) v_n
  double tangentialDampingRatio = 1.0;  // gamma_t / gamma_n
  double friction = 0.0;
  double rollingFriction = 0.0;
  double rollingDamping = 0.0;    // eta_r of the EPSD model
  double cohesionEnergyDensity = 0.0;
  double restitution = 1.0;
};

class ContactLawModel {
 public:
  virtual ~ContactLawModel() = default;
  virtual NormalLaw law() const = 0;
  /// Fills the law-specific coefficients of a pair (stiffness, damping from e).
  virtual void fill(PairCoefficients& c, const Material& a, const Material& b, const PairProperties& p) const = 0;
};

class RollingModel {
 public:
  virtual ~RollingModel() = default;
  virtual RollingLaw law() const = 0;
  virtual double dampingRatio() const { return 0.0; }
};

class CohesionModel {
 public:
  virtual ~CohesionModel() = default;
  virtual CohesionLaw law() const = 0;
};

}  // namespace gf::dem
