#pragma once
// Monitors: quantities sampled during a run and written as CSV columns (one file per monitor).
// A monitor is one file implementing Monitor and registered by name:
//   GF_REGISTER_MODEL(gf::Monitor, KineticEnergyMonitor, "kinetic_energy", "...");
// Its constructor reads its own keys from the case's monitor entry.
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "core/vec3.hpp"
#include "core/serialize.hpp"

namespace gf {

namespace dem {
class System;
struct ParticleSet;
}
namespace fluid {
class Solver;
}
namespace coupling {
class Coupler;
}
namespace resolved {
class FictitiousDomain;
}

/// What a monitor may look at: read-only views of the solver parts that exist in this run.
struct RunState {
  double time = 0.0;       // s
  long long step = 0;      // DEM steps done
  const dem::System* dem = nullptr;
  const fluid::Solver* fluid = nullptr;
  const coupling::Coupler* coupling = nullptr;
  Vec3 gravity;            // m/s^2, the case's
  /// Every particle of the run (under MPI gathered from all ranks on rank 0, whose monitors write
  /// the files; empty on the other ranks); null: the DEM's own (one rank). Read through
  /// monitoredParticles().
  const dem::ParticleSet* particles = nullptr;
  /// The resolved bodies' forcing (resolved CFD-DEM runs only; src/resolved).
  const resolved::FictitiousDomain* resolved = nullptr;
};

/// The particles a monitor that loops over particles reads (RunState::particles, else the DEM's).
/// (A template, so that this header needs no DEM header: instantiated where dem::System is known.)
template <class DemSystem = dem::System>
const dem::ParticleSet& monitoredParticles(const RunState& s) {
  return s.particles ? *s.particles : static_cast<const DemSystem*>(s.dem)->particles();
}

struct MonitorColumn {
  std::string name;
  std::string unit;
};

class Monitor {
 public:
  virtual ~Monitor() = default;
  virtual std::vector<MonitorColumn> columns() const = 0;
  virtual std::vector<double> sample(const RunState& state) = 0;
  /// The rows written at one sample time, each with the same time: one row, sample()'s, for most
  /// monitors; a profile along a line writes one row per cell (fluid_line_profile).
  virtual std::vector<std::vector<double>> sampleRows(const RunState& state) { return {sample(state)}; }
  /// Whether sample() reads the particles themselves (monitoredParticles): under MPI they are then
  /// gathered on rank 0 before the sample. Monitors of fields and of sums the DEM reduces say no.
  virtual bool readsParticles() const { return true; }
  /// Monitors that accumulate (e.g. mass through a plane) save and restore their state, so a
  /// restarted run writes the same numbers as an uninterrupted one.
  virtual void save(BinaryWriter& out) const {}
  virtual void load(BinaryReader& in) {}
};

}  // namespace gf
