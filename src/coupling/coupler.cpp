#include "coupling/coupler.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include "coupling/loops.hpp"
#include "coupling/deposit.hpp"
#include "coupling/forces.hpp"
#include "coupling/smoothing.hpp"

namespace gf::coupling {
namespace {

CouplerSettings readSettings(Params& s) {
  CouplerSettings c;
  const std::string interp = s.choice({"interpolation", "-", "fluid quantities at particles: cell value, trilinear, "
                                                             "or the void-fraction stencil"},
                                      {"cell", "trilinear", "stencil"}, "trilinear");
  c.interpolation = interp == "cell" ? InterpolationMode::Cell
                    : interp == "trilinear" ? InterpolationMode::Trilinear
                                            : InterpolationMode::Stencil;
  c.exchange = s.choice({"exchange", "-", "drag given to the fluid explicitly (force density) or semi-implicitly "
                                          "(coefficient K and mean particle velocity)"},
                        {"explicit", "implicit"}, "implicit") == "explicit"
                   ? ExchangeScheme::Explicit
                   : ExchangeScheme::SemiImplicit;
  c.smoothingLength = s.real({"smoothing_length", "m", "smoothing length l of the implicit diffusion of eps "
                                                       "(D = l^2/dt); 0 = off", Range::nonNegative()},
                             0.0);
  c.smoothExchangeFields = s.boolean({"smooth_exchange_fields", "-", "also smooth force density and K with l"}, false);
  c.minVoidFraction = s.real({"min_void_fraction", "-", "lower bound on eps (volume above it is reported as clipped)",
                              Range::between(0.0, 0.99)},
                             0.1);
  c.minRelaxationToIntervalRatio =
      s.real({"min_relaxation_to_interval_ratio", "-",
              "warn when particle relaxation time / coupling interval is below this (seed 000 eq. 5.30)",
              Range::positive()},
             10.0);
  c.coarseGraining.factor = s.real({"coarse_grain_factor", "-", "parcel diameter / primary particle diameter k "
                                                                "(a parcel holds k^3 particles)", Range::atLeast(1.0)},
                                   1.0);
  Params f = s.section({"forces", "", "fluid forces on particles, each on or off"});
  ForceSwitches& w = c.forces;
  w.drag = f.boolean({"drag", "-", "drag force beta_p (u_f - u_p)"}, true);
  w.pressureGradient = f.boolean({"pressure_gradient", "-", "-V_p grad p"}, true);
  w.viscousStress = f.boolean({"viscous_stress", "-", "V_p div(tau)"}, true);
  w.buoyancy = f.boolean({"buoyancy", "-", "-rho_f V_p g (only if the fluid pressure excludes the hydrostatic part)"},
                         false);
  w.virtualMass = f.boolean({"virtual_mass", "-", "C_vm rho_f V_p d(u_f - u_p)/dt"}, false);
  w.virtualMassCoefficient =
      f.real({"virtual_mass_coefficient", "-", "C_vm (0.5 for a sphere)", Range::nonNegative()}, 0.5);
  w.saffmanMeiLift = f.boolean({"saffman_mei_lift", "-", "Saffman shear lift with Mei's correction"}, false);
  w.magnusLift = f.boolean({"magnus_lift", "-", "Magnus lift (Rubinow-Keller)"}, false);
  w.fluidTorque = f.boolean({"fluid_torque", "-", "torque -pi mu d^3 (omega_p - curl(u)/2)"}, false);
  return c;
}

}  // namespace

Coupler::Coupler(Params& root, const CartesianGrid& grid, const std::array<bool, 3>& periodic, const Vec3& gravity,
                 ExchangeModel model)
    : topology_{grid, periodic}, gravity_(gravity) {
  Params s = root.section({"coupling", "", "unresolved CFD-DEM coupling (docs/coupling.md)"});
  settings_ = readSettings(s);
  settings_.model = model;
  drag_ = Registry<DragLaw>::instance().create(s, {"drag_law", "-", "drag law (docs/coupling.md)"}, "di_felice");
  scheme_ = Registry<VoidFractionScheme>::instance().create(
      s, {"void_fraction", "-", "void-fraction scheme, also the kernel that distributes forces"}, "divided");
  if (!s.documenting()) {
    settings_.dragLaw = s.text({"drag_law", "-"}, "di_felice");
    settings_.voidFraction = s.text({"void_fraction", "-"}, "divided");
  }
  for (auto& f : scratch_) f = Field(grid);
  for (int a = 0; a < 3; ++a) {
    vorticity_[a] = Field(grid);
    divTau_[a] = Field(grid);
  }
}

void Coupler::fillGhosts(Field& f) const {
  const auto& n = topology_.grid.cells;
  const int g = topology_.grid.ghosts;
  // periodic: wrapped image; wall: nearest interior cell (zero normal gradient)
  auto source = [&](int i, int a) { return topology_.periodic[a] ? topology_.mapIndex(i, a) : std::clamp(i, 0, n[a] - 1); };
  for (int k = -g; k < n[2] + g; ++k)
    for (int j = -g; j < n[1] + g; ++j) {
      const bool interiorRow = j >= 0 && j < n[1] && k >= 0 && k < n[2];
      const int sj = source(j, 1), sk = source(k, 2);
      for (int i = -g; i < n[0] + g; ++i) {
        if (interiorRow && i == 0) i = n[0];  // skip the interior of the row
        f(i, j, k) = f(source(i, 0), sj, sk);
      }
    }
}

void Coupler::computeVoidFraction(const dem::ParticleSet& particles, CouplingFields& fields) {
  fields.voidFractionOld.data() = fields.voidFraction.data();
  scheme_->buildStencils(particles, topology_, stencils_);
  stencilsReady_ = true;
  const std::size_t n = particles.size();
  std::vector<double> volume(n);
  for (std::size_t p = 0; p < n; ++p) volume[p] = force::sphereVolume(2.0 * particles.radius[p]);
  Field& solid = scratch_[0];
  depositToFields(stencils_, volume.data(), 1, {&solid});
  particleVolume_ = 0.0;
  for (double v : volume) particleVolume_ += v;
  const auto& c = topology_.grid.cells;
  const double cellVolume = topology_.grid.cellVolume();
  depositedVolume_ = 0.0;
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i) {
        depositedVolume_ += solid(i, j, k);
        solid(i, j, k) /= cellVolume;  // solid fraction
      }
  smoothField(topology_, settings_.smoothingLength, solid);
  clippedVolume_ = 0.0;
  Field& eps = fields.voidFraction;
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i) {
        const double e = 1.0 - solid(i, j, k);
        if (e < settings_.minVoidFraction) clippedVolume_ += (settings_.minVoidFraction - e) * cellVolume;
        eps(i, j, k) = std::max(e, settings_.minVoidFraction);
      }
  fillGhosts(eps);
}

template <InterpolationMode Mode>
void Coupler::sampleFluid(const FluidView& fluid, const CouplingFields& fields, const dem::ParticleSet& particles) {
  const ForceSwitches& w = settings_.forces;
  const bool needVorticity = w.saffmanMeiLift || w.magnusLift || w.fluidTorque;
  const bool needDivTau = w.viscousStress;
  const Field* divTau[3];
  for (int a = 0; a < 3; ++a)
    divTau[a] = fluid.viscousStressDivergence[a] ? fluid.viscousStressDivergence[a] : &divTau_[a];
  const Field* const velocity[3] = {fluid.velocity[0], fluid.velocity[1], fluid.velocity[2]};
  const Field* const gradP[3] = {fluid.pressureGradient[0], fluid.pressureGradient[1], fluid.pressureGradient[2]};
  const Field* const vort[3] = {&vorticity_[0], &vorticity_[1], &vorticity_[2]};
  const Field* const eps[1] = {&fields.voidFraction};
  const double dPrimFactor = 1.0 / settings_.coarseGraining.factor;
  const double epsFloor = std::max(settings_.minVoidFraction, 1e-6);
  forEachIndex(static_cast<std::int64_t>(particles.size()), 64, [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    const Vec3 x = particles.position[p];
    SampleWeights sw;
    sampleWeights<Mode>(topology_, stencils_, p, x, sw);
    double v3[3], v1[1];
    sampleFields<3>(sw, velocity, v3);
    fluidVelocityAtParticle_[p] = {v3[0], v3[1], v3[2]};
    sampleFields<1>(sw, eps, v1);
    voidFractionAtParticle_[p] = std::clamp(v1[0], epsFloor, 1.0);
    if (w.pressureGradient) {
      sampleFields<3>(sw, gradP, v3);
      gradPAtParticle_[p] = {v3[0], v3[1], v3[2]};
    }
    if (needDivTau) {
      sampleFields<3>(sw, divTau, v3);
      divTauAtParticle_[p] = {v3[0], v3[1], v3[2]};
    }
    if (needVorticity) {
      sampleFields<3>(sw, vort, v3);
      vorticityAtParticle_[p] = {v3[0], v3[1], v3[2]};
    }
    slip_[p] = fluidVelocityAtParticle_[p] - particles.velocity[p];
    const double dPrim = 2.0 * particles.radius[p] * dPrimFactor;
    reynolds_[p] = fluid.density * norm(slip_[p]) * dPrim / fluid.viscosity;
  });
}

void Coupler::alignPreviousSlip(const dem::ParticleSet& particles) {
  // slip of each current particle at the previous coupling step (matched by id); a particle
  // without history gets its current slip, i.e. no virtual-mass force in its first step
  if (particles.id == previousId_) return;
  std::unordered_map<std::int64_t, std::size_t> oldIndex;
  oldIndex.reserve(previousId_.size());
  for (std::size_t q = 0; q < previousId_.size(); ++q) oldIndex.emplace(previousId_[q], q);
  std::vector<Vec3> aligned(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const auto it = oldIndex.find(particles.id[p]);
    aligned[p] = it == oldIndex.end() ? slip_[p] : previousSlip_[it->second];
  }
  previousSlip_ = std::move(aligned);
  previousId_ = particles.id;
}

void Coupler::computeForcesFromSamples(const FluidView& fluid, dem::ParticleSet& particles) {
  const ForceSwitches& w = settings_.forces;
  const double k3 = settings_.coarseGraining.fluidForceScale();
  const double dPrimFactor = 1.0 / settings_.coarseGraining.factor;
  const bool modelB = settings_.model == ExchangeModel::B;
  const double rho = fluid.density, mu = fluid.viscosity;
  if (w.virtualMass && !(fluid.timeStep > 0.0))
    throw std::invalid_argument("coupling: virtual mass force needs FluidView::timeStep > 0");
  if (w.virtualMass) alignPreviousSlip(particles);
  forEachIndex(static_cast<std::int64_t>(particles.size()), 64, [&](std::int64_t ip) {
    const auto p = static_cast<std::size_t>(ip);
    const double d = 2.0 * particles.radius[p];
    const double dPrim = d * dPrimFactor;
    const double volume = force::sphereVolume(d);  // parcel volume = k^3 primary volumes
    const Vec3 slip = slip_[p];
    beta_[p] = w.drag ? k3 * particleDragCoefficient(mu, dPrim, correction_[p]) : 0.0;
    const Vec3 fDrag = force::drag(beta_[p], slip);
    Vec3 exchangedOther{}, particleOnly{};
    if (w.pressureGradient) {
      const Vec3 f = force::pressureGradient(volume, gradPAtParticle_[p]);
      (modelB ? exchangedOther : particleOnly) += f;
    }
    if (w.viscousStress) {
      const Vec3 f = force::viscousStress(volume, divTauAtParticle_[p]);
      (modelB ? exchangedOther : particleOnly) += f;
    }
    if (w.buoyancy) particleOnly += force::buoyancy(rho, volume, gravity_);
    if (w.virtualMass)
      exchangedOther += force::virtualMass(w.virtualMassCoefficient, rho, volume, slip,
                                           previousSlip_[p], fluid.timeStep);
    const Vec3 relOmega = force::relativeRotation(particles.angularVelocity[p], vorticityAtParticle_[p]);
    if (w.saffmanMeiLift) exchangedOther += k3 * force::saffmanMeiLift(rho, mu, dPrim, slip, vorticityAtParticle_[p]);
    if (w.magnusLift) exchangedOther += k3 * force::magnusLift(rho, dPrim, relOmega, slip);
    dragForce_[p] = fDrag;
    otherExchangedForce_[p] = exchangedOther;
    particles.externalForce[p] = fDrag + exchangedOther + particleOnly;
    particles.externalTorque[p] = w.fluidTorque ? k3 * force::rotationalTorque(mu, dPrim, relOmega) : Vec3{};
  });
}

void Coupler::computeParticleForces(const FluidView& fluid, const CouplingFields& fields,
                                    dem::ParticleSet& particles) {
  const std::size_t n = particles.size();
  if (!stencilsReady_ || stencils_.size() != n)
    throw std::logic_error("coupling: computeVoidFraction must run before computeParticleForces (particle count changed)");
  lastFluid_ = fluid;
  const ForceSwitches& w = settings_.forces;
  for (int a = 0; a < 3; ++a) {
    if (!fluid.velocity[a]) throw std::invalid_argument("coupling: FluidView::velocity is not set");
    if (w.pressureGradient && !fluid.pressureGradient[a])
      throw std::invalid_argument("coupling: FluidView::pressureGradient is not set (needed by forces.pressure_gradient)");
  }
  if (w.saffmanMeiLift || w.magnusLift || w.fluidTorque) {
    computeVorticity(topology_, fluid.velocity, vorticity_);
    for (auto& f : vorticity_) fillGhosts(f);
  }
  if (w.viscousStress && !fluid.viscousStressDivergence[0]) {
    computeViscousStressDivergence(topology_, fluid.velocity, fluid.viscosity, divTau_);
    for (auto& f : divTau_) fillGhosts(f);
  }
  for (auto* v : {&fluidVelocityAtParticle_, &slip_, &gradPAtParticle_, &divTauAtParticle_, &vorticityAtParticle_,
                  &dragForce_, &otherExchangedForce_})
    v->assign(n, Vec3{});
  for (auto* v : {&voidFractionAtParticle_, &reynolds_, &correction_, &beta_}) v->assign(n, 0.0);
  switch (settings_.interpolation) {  // dispatched once; the loops inside are monomorphic
    case InterpolationMode::Cell: sampleFluid<InterpolationMode::Cell>(fluid, fields, particles); break;
    case InterpolationMode::Trilinear: sampleFluid<InterpolationMode::Trilinear>(fluid, fields, particles); break;
    case InterpolationMode::Stencil: sampleFluid<InterpolationMode::Stencil>(fluid, fields, particles); break;
  }
  drag_->evaluate(n, reynolds_.data(), voidFractionAtParticle_.data(), correction_.data());
  computeForcesFromSamples(fluid, particles);
  previousId_ = particles.id;
  previousSlip_ = slip_;
  forcesReady_ = true;
}

void Coupler::realignToParticles(const dem::ParticleSet& particles) {
  if (particles.id == previousId_) return;
  // The DEM reordered (or inserted / removed) particles since computeParticleForces: move the
  // per-particle exchange data to the new order by id; new particles exchange nothing.
  std::unordered_map<std::int64_t, std::size_t> oldIndex;
  oldIndex.reserve(previousId_.size());
  for (std::size_t q = 0; q < previousId_.size(); ++q) oldIndex.emplace(previousId_[q], q);
  const std::size_t n = particles.size();
  std::vector<Vec3> drag(n), other(n), slip(n);
  std::vector<double> beta(n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const auto it = oldIndex.find(particles.id[p]);
    if (it == oldIndex.end()) continue;
    drag[p] = dragForce_[it->second];
    other[p] = otherExchangedForce_[it->second];
    slip[p] = slip_[it->second];
    beta[p] = beta_[it->second];
  }
  dragForce_ = std::move(drag);
  otherExchangedForce_ = std::move(other);
  slip_ = std::move(slip);
  beta_ = std::move(beta);
  previousSlip_ = slip_;
  previousId_ = particles.id;
}

void Coupler::fillFluidSources(const dem::ParticleSet& particles, CouplingFields& fields) {
  if (!forcesReady_) throw std::logic_error("coupling: computeParticleForces must run before fillFluidSources");
  if (stencils_.size() != particles.size())
    throw std::logic_error("coupling: computeVoidFraction must run on the current particle set before fillFluidSources");
  realignToParticles(particles);
  fillFluidSources(fields);
}

void Coupler::fillFluidSources(CouplingFields& fields) {
  if (!forcesReady_ || dragForce_.size() != stencils_.size())
    throw std::logic_error("coupling: computeParticleForces must run before fillFluidSources (same particle set)");
  const bool implicit = settings_.exchange == ExchangeScheme::SemiImplicit;
  depositExchange(fields, implicit);
  if (settings_.smoothExchangeFields && settings_.smoothingLength > 0.0) smoothExchange(fields, implicit);
  for (auto& f : fields.forceDensity) fillGhosts(f);
  fillGhosts(fields.dragCoefficient);
  for (auto& f : fields.particleVelocity) fillGhosts(f);
  updateMomentumBalance(fields, implicit);
}

void Coupler::depositExchange(CouplingFields& fields, bool implicit) {
  const std::size_t n = stencils_.size();
  // channels: 0-2 explicit force on the fluid; implicit adds 3: beta, 4-6: beta (u_p - u_f@p)
  const int channels = implicit ? 7 : 3;
  std::vector<double> values(n * channels);
  for (std::size_t p = 0; p < n; ++p) {
    const Vec3 explicitOnFluid = implicit ? -otherExchangedForce_[p] : -(otherExchangedForce_[p] + dragForce_[p]);
    double* v = values.data() + p * channels;
    for (int a = 0; a < 3; ++a) v[a] = explicitOnFluid[a];
    if (implicit) {
      v[3] = beta_[p];
      for (int a = 0; a < 3; ++a) v[4 + a] = -beta_[p] * slip_[p][a];
    }
  }
  std::vector<Field*> targets;
  for (int ch = 0; ch < channels; ++ch) targets.push_back(&scratch_[ch]);
  depositToFields(stencils_, values.data(), channels, targets);

  const auto& c = topology_.grid.cells;
  const double cellVolume = topology_.grid.cellVolume();
  const Field* const* u = lastFluid_.velocity;
  for (int a = 0; a < 3; ++a) fields.forceDensity[a].fill(0.0);
  fields.dragCoefficient.fill(0.0);
  for (int a = 0; a < 3; ++a) fields.particleVelocity[a].fill(0.0);
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i) {
        for (int a = 0; a < 3; ++a) fields.forceDensity[a](i, j, k) = scratch_[a](i, j, k) / cellVolume;
        if (!implicit) continue;
        const double kv = scratch_[3](i, j, k);  // sum w beta
        fields.dragCoefficient(i, j, k) = kv / cellVolume;
        // K u_p_avg V = sum w beta (u_p + u_c - u_f@p): the mean particle velocity corrected by the
        // interpolation defect, so that K (u_c - u_p_avg) V equals the particles' drag exactly.
        for (int a = 0; a < 3; ++a)
          fields.particleVelocity[a](i, j, k) = kv > 0.0 ? (*u[a])(i, j, k) + scratch_[4 + a](i, j, k) / kv : 0.0;
      }
}

void Coupler::smoothExchange(CouplingFields& fields, bool implicit) const {
  const double l = settings_.smoothingLength;
  for (auto& f : fields.forceDensity) smoothField(topology_, l, f);
  if (!implicit) return;
  // smooth K and K u_p (momentum-conserving), then divide
  Field& k = fields.dragCoefficient;
  for (auto& up : fields.particleVelocity) {
    for (std::size_t q = 0; q < up.data().size(); ++q) up.data()[q] *= k.data()[q];
    smoothField(topology_, l, up);
  }
  smoothField(topology_, l, k);
  for (auto& up : fields.particleVelocity)
    for (std::size_t q = 0; q < up.data().size(); ++q) up.data()[q] = k.data()[q] > 0.0 ? up.data()[q] / k.data()[q] : 0.0;
}

void Coupler::updateMomentumBalance(const CouplingFields& fields, bool implicit) {
  // Newton's third law: particles' exchanged forces + fluid sources (explicit - K (u - u_p)) = 0.
  Vec3 onParticles{}, onFluid{};
  exchangedForceScale_ = 0.0;
  for (std::size_t p = 0; p < dragForce_.size(); ++p) {
    const Vec3 f = dragForce_[p] + otherExchangedForce_[p];
    onParticles += f;
    exchangedForceScale_ += norm(f);
  }
  const auto& c = topology_.grid.cells;
  const double cellVolume = topology_.grid.cellVolume();
  const Field* const* u = lastFluid_.velocity;
  for (int k = 0; k < c[2]; ++k)
    for (int j = 0; j < c[1]; ++j)
      for (int i = 0; i < c[0]; ++i)
        for (int a = 0; a < 3; ++a) {
          double s = fields.forceDensity[a](i, j, k);
          if (implicit)
            s -= fields.dragCoefficient(i, j, k) * ((*u[a])(i, j, k) - fields.particleVelocity[a](i, j, k));
          onFluid[a] += s * cellVolume;
        }
  balanceError_ = onParticles + onFluid;
}

CouplingIntervalCheck Coupler::checkCouplingInterval(double demTimeStep, int demStepsPerFluidStep,
                                                     const dem::ParticleSet& particles, const FluidView& fluid,
                                                     double slip) const {
  // the fastest-relaxing particle: smallest rho_p d_prim^2
  double best = -1.0, d = 0.0, rhoP = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double dp = 2.0 * particles.radius[p] / settings_.coarseGraining.factor;
    const double rp = particles.mass[p] / force::sphereVolume(2.0 * particles.radius[p]);
    if (best < 0.0 || rp * dp * dp < best) {
      best = rp * dp * dp;
      d = dp;
      rhoP = rp;
    }
  }
  if (best < 0.0) return {};
  return gf::coupling::checkCouplingInterval(demTimeStep, demStepsPerFluidStep, rhoP, d, fluid.density,
                                             fluid.viscosity, slip, settings_.minRelaxationToIntervalRatio);
}

void Coupler::save(BinaryWriter& out) const {
  out.putVector(previousId_);
  out.putVector(previousSlip_);
}

void Coupler::load(BinaryReader& in) {
  previousId_ = in.getVector<std::int64_t>();
  previousSlip_ = in.getVector<Vec3>();
  if (previousId_.size() != previousSlip_.size())
    throw CheckpointError("checkpoint is corrupt: coupling state arrays have different lengths");
}

}  // namespace gf::coupling
