#include "resolved/fictitious_domain.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "dem/contact_kernel.hpp"
#include "io/stl_reader.hpp"
#include "parallel/exchange.hpp"
#include "resolved/mesh_body.hpp"

namespace gf::resolved {

namespace {
/// Below this many cells per diameter a resolved body is refused; below kWarnCells a warning says the
/// result depends on the grid (seed 000 lines 519-527: 8 cells per diameter for grid-independent
/// settling).
constexpr double kMinCells = 4.0;
constexpr double kWarnCells = 8.0;
/// resolved.radius_offset's default, cells (docs/resolved.md: calibration on the Schaefer-Turek
/// cylinder, checked on the cylinder at Re 100 and the settling sphere).
constexpr double kDefaultRadiusOffset = 0.0;
}  // namespace

FictitiousDomain::FictitiousDomain(Params& root, fluid::Solver& fluid, dem::ParticleSet& particles,
                                   const Domain& domain, const Vec3& gravity, const dem::ContactTable* contacts)
    : gravity_(gravity), contacts_(contacts) {
  Params section = root.section(
      {"resolved", "-",
       "resolved CFD-DEM (fictitious domain, docs/resolved.md): every particle is a resolved sphere moved by the "
       "fluid's forcing; needs a 'fluid' section and excludes 'coupling'"});
  implicit_ = section.choice({"forcing", "-",
                               "forcing of the fixed bodies: implicit = their velocity imposed through a penalty term "
                               "inside the momentum predictor and the projection (accurate at any viscous number nu "
                               "dt / h^2); explicit = imposed on the predicted velocity before the projection, as seed "
                               "000 lines 471-510 (drag too low unless nu dt / h^2 << 1). Particles: always explicit "
                               "(docs/resolved.md)"},
                              {"implicit", "explicit"}, "implicit") == "implicit";
  particleImplicit_ = section.choice({"particle_forcing", "-",
                                       "forcing of the particles: explicit (seed 000 lines 471-510; needs nu dt / h^2 << "
                                       "1) or implicit (the penalty of the fixed bodies; unstable for light particles: "
                                       "the particle update lags the force by one step, docs/resolved.md)"},
                                      {"explicit", "implicit"}, "explicit") == "implicit";
  radiusOffsetCells_ = section.real(
      {"radius_offset", "cells",
       "the forcing covers the bodies with radii larger by this many cell sizes (the explicit forcing's no-slip "
       "condition is not exact near the surface: the body acts smaller than it is; docs/resolved.md)",
       Range::between(-1.0, 1.0)},
      kDefaultRadiusOffset);
  {
    Params lub = section.section(
        {"lubrication", "-",
         "short-range lubrication correction of the particles' normal approach to each other, to fixed spheres and "
         "to the DEM's walls: the squeeze-film force the grid does not resolve (docs/resolved.md sec. 4)"});
    lubrication_.enabled = lub.boolean({"enabled", "-", "add the lubrication correction"}, false);
    lubrication_.range = lub.real({"range", "-",
                                   "surface gap below which it acts, over the smaller diameter of the pair (the "
                                   "resolved part: about one cell, 0.05 to 0.125 at 8 cells per diameter)",
                                   Range::positive()},
                                  LubricationSettings{}.range);
    lubrication_.minGap = lub.real({"min_gap", "-",
                                    "gap over the same diameter below which the correction stays at its value there "
                                    "(roughness; the DEM contact takes over at touch)",
                                    Range::positive()},
                                   LubricationSettings{}.minGap);
    if (!lub.documenting() && lubrication_.minGap >= lubrication_.range)
      lub.fail("min_gap", fmt::format("{} (range {})", lubrication_.minGap, lubrication_.range),
               "a cut-off below resolved.lubrication.range");
  }
  std::vector<Params> entries = section.list(
      {"bodies", "-",
       "fixed bodies the fluid flows around (spheres; cylinders along z; closed STL meshes), optionally rotating"});
  for (Params& b : entries) {
    const std::string shape = b.choice(
        {"shape", "-",
         "sphere; cylinder (axis parallel to z, spanning the domain: a 2D body); stl (a closed triangle mesh, fixed in "
         "place)"},
        {"sphere", "cylinder", "stl"});
    const bool hasCentre = b.has("centre");
    const Vec3 centre = b.vec3({"centre", "m",
                                "centre, required for a sphere or cylinder (cylinder: a point of its axis; stl: the "
                                "point its torque is taken about, default the centroid of its volume)"},
                               Vec3{});
    const double radius = b.real({"radius", "m", "radius, required for a sphere or cylinder", Range::nonNegative()}, 0.0);
    const Vec3 omega = b.vec3({"angular_velocity", "rad/s",
                               "prescribed angular velocity about the centre (a cylinder: z component only; stl: the "
                               "velocity omega x r imposed on the mesh, which stays in place: a rotation only for a "
                               "body of revolution about that axis)"},
                              Vec3{});
    const std::string file =
        b.text({"file", "-", "stl: path of a closed ASCII or binary STL mesh (relative to the case file)"}, "");
    const double scale =
        b.real({"scale", "-", "stl: factor applied to the coordinates (e.g. 0.001 for mm)", Range::positive()}, 1.0);
    const Vec3 offset = b.vec3({"offset", "m", "stl: translation applied after scaling"}, Vec3{});
    const long long samples = b.integer(
        {"samples", "-",
         "stl: sub-cell samples per cell along each axis (even) from which each cell's solid fraction is counted",
         Range::between(2, 64)},
        8);
    // (the key is read for every shape, so that it is documented; an stl body takes its contacts
    // from a DEM stl wall of the same file, docs/resolved.md)
    const int material =
        contacts ? contacts->readMaterial(b, {"material", "-",
                                              "material of the body's contacts with the particles through the DEM's "
                                              "contact law (sphere, cylinder; 'rigid': infinitely stiff, the default)"},
                                          dem::kRigidMaterial)
                 : -1;
    const double referenceArea = b.real(
        {"reference_area", "m^2",
         "area A of the force coefficients of the monitor resolved_body_forces; 0: pi R^2 (sphere), 2 R L_z "
         "(cylinder), pi r^2 with r the radius of the sphere of the mesh's volume (stl)",
         Range::nonNegative()},
        0.0);
    if (b.documenting()) continue;
    FixedBody f;
    f.body.shape = shape == "sphere" ? Shape::Sphere : (shape == "cylinder" ? Shape::Cylinder : Shape::Mesh);
    f.body.centre = centre;
    f.body.radius = radius;
    f.body.angularVelocity = f.body.shape == Shape::Cylinder ? Vec3{0.0, 0.0, omega.z} : omega;
    if (f.body.shape != Shape::Cylinder && fluid.twoD())
      b.fail("shape", fmt::format("a{} {} on a 2D grid (fluid.cells with nz = 1)", shape == "stl" ? "n" : "", shape),
             "a cylinder, or a 3D grid");
    if (f.body.shape == Shape::Mesh) {
      if (samples % 2 != 0) b.fail("samples", std::to_string(samples), "an even number of samples per cell");
      if (file.empty()) b.fail("file", "nothing", "the path of a closed STL mesh (shape: stl)");
      std::filesystem::path path(file);
      if (path.is_relative()) path = std::filesystem::path(b.fileName()).parent_path() / path;
      std::vector<io::Triangle> triangles;
      try {
        triangles = io::readStl(path.string());
      } catch (const Error& e) {
        b.fail("file", "'" + file + "'", std::string("a readable STL file (") + e.what() + ")");
      }
      for (io::Triangle& t : triangles)
        for (Vec3& v : t) v = scale * v + offset;
      if (triangles.empty() || meshVolume(triangles) <= 0.0)
        b.fail("file", fmt::format("'{}': {} triangles enclosing no volume", file, triangles.size()),
               "a closed triangle mesh");
      f.body.mesh = std::make_shared<const MeshBody>(std::move(triangles), fluid.grid(), static_cast<int>(samples));
      f.body.radius = std::cbrt(3.0 * f.body.mesh->volume() / (4.0 * std::numbers::pi));
      if (!hasCentre) f.body.centre = f.body.mesh->centroid();
    } else {
      if (!hasCentre) b.fail("centre", "nothing", fmt::format("the centre of the {}", shape));
      if (!(radius > 0.0)) b.fail("radius", radius == 0.0 ? "nothing" : std::to_string(radius), "a positive radius");
    }
    // Resolution: a mesh by the diameter of the sphere of its volume.
    const double n = cellsPerDiameter(f.body.radius, fluid.grid().spacing, f.body.shape == Shape::Cylinder);
    const double h = f.body.shape == Shape::Cylinder ? std::max(fluid.grid().spacing.x, fluid.grid().spacing.y)
                                                     : std::max({fluid.grid().spacing.x, fluid.grid().spacing.y,
                                                                 fluid.grid().spacing.z});
    const char* sizeKey = f.body.shape == Shape::Mesh ? "scale" : "radius";
    if (n < kMinCells)
      b.fail(sizeKey,
             fmt::format("{}diameter {} m on cells of {} m is {:.3g} cells per diameter",
                         f.body.shape == Shape::Mesh ? "volume-equivalent " : "", 2.0 * f.body.radius, h, n),
             fmt::format("at least {} cells per diameter (diameter >= {} m), better {}", kMinCells, kMinCells * h,
                         kWarnCells));
    if (n < kWarnCells)
      spdlog::warn("{}: diameter {} m on cells of {} m is {:.3g} cells per diameter, below {}: forces depend on the grid",
                   b.path(sizeKey), 2.0 * f.body.radius, h, n, kWarnCells);
    f.referenceArea = referenceArea > 0.0 ? referenceArea
                      : f.body.shape == Shape::Cylinder
                          ? 2.0 * f.body.radius * domain.size().z
                          : std::numbers::pi * f.body.radius * f.body.radius;
    if (f.body.shape != Shape::Mesh) f.material = material;
    bodyContacts_ = bodyContacts_ || f.material >= 0;
    fixed_.push_back(f);
  }
  if (root.documenting()) return;

  const CartesianGrid& g = fluid.grid();
  box_.grid = g;
  box_.offset = fluid.cellOffset();
  box_.global = fluid.globalGrid().cells;
  box_.periodic = domain.periodic;
  box_.twoD = fluid.twoD();
  rho_ = fluid.density();
  radiusOffset_ = radiusOffsetCells_ * (fluid.twoD() ? std::max(g.spacing.x, g.spacing.y)
                                                     : std::max({g.spacing.x, g.spacing.y, g.spacing.z}));
  depth_ = domain.size().z;
  domainSize_ = domain.size();
  viscosity_ = fluid.viscosity();
  distributed_ = fluid.decomposition().distributed();

  // The particles at start: resolved enough, and clear of the fixed bodies.
  if (particles.size() > 0) {
    if (fluid.twoD())
      section.fail("bodies", fmt::format("{} particle(s) on a 2D grid (fluid.cells with nz = 1)", particles.size()),
                   "a 3D grid for resolved spheres");
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < particles.size(); ++i)
      if (particles.radius[i] < particles.radius[smallest]) smallest = i;
    const double r = particles.radius[smallest];
    const Vec3 h = g.spacing;
    const double hmax = std::max({h.x, h.y, h.z}), n = cellsPerDiameter(r, h, false);
    if (n < kMinCells) {
      Params fluidSection = root.section({"fluid"});
      fluidSection.fail(
          "cells",
          fmt::format("cells of {} m for particle {} of diameter {} m: {:.3g} cells per diameter",
                      hmax, particles.id[smallest], 2.0 * r, n),
          fmt::format("at least {} cells per diameter for resolved particles (cell size <= {} m), better {}", kMinCells,
                      2.0 * r / kMinCells, kWarnCells));
    }
    if (n < kWarnCells)
      spdlog::warn("resolved: particle {} of diameter {} m on cells of {} m is {:.3g} cells per diameter, below {}: "
                   "forces depend on the grid",
                   particles.id[smallest], 2.0 * r, hmax, n, kWarnCells);
    for (std::size_t b = 0; b < fixed_.size(); ++b) {
      const Body& body = fixed_[b].body;
      std::vector<std::int64_t> ids;
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if (body.shape == Shape::Mesh) {  // the centre inside, or the surface nearer than the radius
          const Vec3& x = particles.position[i];
          if (body.mesh->contains(x) || body.mesh->distance(x) < particles.radius[i]) ids.push_back(particles.id[i]);
          continue;
        }
        Vec3 d = particles.position[i] - body.centre;
        if (body.shape == Shape::Cylinder) d.z = 0.0;
        if (norm(d) < particles.radius[i] + body.radius) ids.push_back(particles.id[i]);
      }
      if (!ids.empty())
        entries[b].fail(body.shape == Shape::Mesh ? "file" : "centre",
                        fmt::format("particle(s) {} overlapping body {} at start", fmt::join(ids, ", "), b),
                        "particles clear of the fixed bodies at start");
    }
  }
  momentumColumn_ = particles.addColumn("resolved_fluid_momentum", Vec3{});
  angularColumn_ = particles.addColumn("resolved_fluid_angular_momentum", Vec3{});
  knownColumn_ = particles.addColumn("resolved_fluid_momentum_known", 0.0);
  addSubstepColumns(particles);
  particles.enableExternalForces();
  fluid.setPredictorHook([this](Field(&u)[3], double dt, double gamma0) { impose(u, dt, gamma0); });
}

Body FictitiousDomain::particleBody(const dem::ParticleSet& p, std::size_t i) const {
  Body b;
  b.shape = Shape::Sphere;
  b.centre = p.position[i];
  b.radius = p.radius[i];
  b.velocity = p.velocity[i];
  b.angularVelocity = p.angularVelocity[i];
  return b;
}

void FictitiousDomain::impose(Field (&u)[3], double dt, double gamma0) {
  // Bodies one after the other (a face two bodies cover takes the later one's velocity in the
  // proportion it covers). Fixed bodies first, then particles in the set's order: deterministic.
  // (fixed bodies with the implicit forcing are held by their penalty instead: setPenalty)
  std::size_t k = 0;
  for (const FixedBody& f : fixed_) {
    if (!implicit_) forcingSums_[k] = imposeRigidMotion(forcingBody(f.body), box_, u, rho_, gamma0, dt);
    ++k;
  }
  if (!particleImplicit_)
    for (const Body& b : particleBodies_) forcingSums_[k++] = imposeRigidMotion(forcingBody(b), box_, u, rho_, gamma0, dt);
}

void FictitiousDomain::fluidStep(fluid::Solver& fluid, dem::ParticleSet& particles, double dt) {
  const std::size_t nf = fixed_.size();
  // The particles this rank owns, as bodies at the start of the step (positions and velocities at
  // time n: the fluid sees the bodies where the DEM left them).
  std::vector<std::size_t> owned;
  particleBodies_.clear();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.isGhost(i)) continue;
    owned.push_back(i);
    particleBodies_.push_back(particleBody(particles, i));
  }
  const std::size_t n = nf + owned.size();
  forcingSums_.assign(n, FaceSums{});
  // The explicit forcing holds the no-slip condition to O(nu dt / h^2) only (docs/resolved.md).
  const double h = std::min({box_.grid.spacing.x, box_.grid.spacing.y, box_.twoD ? box_.grid.spacing.y : box_.grid.spacing.z});
  const double viscousNumber = fluid.viscosity() / rho_ * dt / (h * h);
  if (!viscousWarned_ && ((!particleImplicit_ && !owned.empty()) || (!implicit_ && nf > 0)) && viscousNumber > 0.1) {
    spdlog::warn("resolved: the explicit forcing with nu dt / h^2 = {:.3g} > 0.1 lets fluid through the bodies (drag "
                 "too low); a fluid step below {:.3g} s keeps it at 0.02 (docs/resolved.md)",
                 viscousNumber, 0.02 * h * h * rho_ / fluid.viscosity());
    viscousWarned_ = true;
  }

  // Implicit forcing: the penalty K and the K-weighted body velocity of the cells the bodies cover
  // (the fluid solver's implicit drag term), for the BDF2 step of a constant dt (gamma0 = 3/2; 1 on
  // the first step).
  const double gamma0 = fluid.stepsDone() > 0 ? 1.5 : 1.0;
  const double diagonal = predictorDiagonal(rho_, fluid.viscosity(), gamma0, dt, box_.grid.spacing, box_.twoD);
  if (implicit_ || particleImplicit_) setPenalty(fluid, diagonal);

  // The fluid momentum inside a particle that has no value from a last step (the first step; a new
  // particle), from the velocity before this step: the rigid-body correction of its first step is
  // then taken too (without it that step's rho I^{n+1} / dt would be lost from the momentum balance
  // of fluid and particle). (A fixed body's first step keeps no correction: it is held whatever its
  // load, and the fluid of a starting stream inside it would show as a spike.)
  const std::array<const Field*, 3> uBefore{&fluid.velocity(0), &fluid.velocity(1), &fluid.velocity(2)};
  {
    auto& momentum = particles.vec3Columns[momentumColumn_].values;
    auto& angular = particles.vec3Columns[angularColumn_].values;
    auto& known = particles.doubleColumns[knownColumn_].values;
    for (std::size_t q = 0; q < owned.size(); ++q) {
      const std::size_t i = owned[q];
      if (known[i] != 0.0) continue;
      const Body b = forcingBody(particleBodies_[q]);
      const FaceSums s =
          particleImplicit_ ? penaltyMomentumInside(b, box_, uBefore, diagonal) : fluidMomentumInside(b, box_, uBefore);
      momentum[i] = s.momentum;
      angular[i] = s.angularMomentum;
      known[i] = 1.0;
    }
  }

  fluid.step(dt);  // predictor, projection (explicit forcing: impose, through the hook, between them)

  const std::array<const Field*, 3> u{&fluid.velocity(0), &fluid.velocity(1), &fluid.velocity(2)};
  if (implicit_)
    for (std::size_t b = 0; b < nf; ++b)
      forcingSums_[b] = implicitForcingLoad(forcingBody(fixed_[b].body), box_, u, diagonal);
  if (particleImplicit_)
    for (std::size_t q = 0; q < owned.size(); ++q)
      forcingSums_[nf + q] = implicitForcingLoad(forcingBody(particleBodies_[q]), box_, u, diagonal);

  // The first (BDF1) fluid step: the BDF2 steps after it carry on half of its momentum change again
  // (with no force after it, M^{n+1} - M^n = (M^n - M^{n-1}) / 3, a series adding up to 1/2), so the
  // fluid ends up with 3/2 of the first step's forcing impulse: the bodies get 3/2 of that step's
  // forcing load. The balance of the BDF2 steps is Q^{n+1} - Q^n = dt F, Q = (3 M^{n+1} - M^n) / 2,
  // and Q^1 = M^0 + 3/2 (M^1 - M^0): with this the fluid's Q plus the particles' momentum (less the
  // fluid inside them, the rigid-body correction) is constant from the start (tests/resolved,
  // docs/resolved.md sec. 3).
  if (gamma0 != 1.5)
    for (FaceSums& s : forcingSums_) {
      s.force *= 1.5 / gamma0;
      s.torque *= 1.5 / gamma0;
    }

  // Fluid momentum inside each body after the projection: the rigid-body correction rho dI/dt
  // (Kempe & Froehlich 2012 eq. 8), I from this step and the last.
  std::vector<FaceSums> inside(n);
  for (std::size_t b = 0; b < nf; ++b) inside[b] = fluidMomentumInside(forcingBody(fixed_[b].body), box_, u);
  for (std::size_t q = 0; q < owned.size(); ++q)
    inside[nf + q] = particleImplicit_ ? penaltyMomentumInside(forcingBody(particleBodies_[q]), box_, u, diagonal)
                                       : fluidMomentumInside(forcingBody(particleBodies_[q]), box_, u);

  if (distributed_) {
    // The fixed bodies' sums over the ranks' cells and faces. (The particle sums are per rank-owned
    // particle: a particle's cells on other ranks are missing, and the app refuses resolved
    // particles on several ranks until the sums are keyed by id across the ranks.)
    std::vector<double> flat;
    flat.reserve(12 * nf);
    for (std::size_t b = 0; b < nf; ++b)
      for (const Vec3* v : {&forcingSums_[b].force, &forcingSums_[b].torque, &inside[b].momentum, &inside[b].angularMomentum})
        for (int a = 0; a < 3; ++a) flat.push_back((*v)[a]);
    flat = parallel::sumOverRanks(flat);
    std::size_t k = 0;
    for (std::size_t b = 0; b < nf; ++b)
      for (Vec3* v : {&forcingSums_[b].force, &forcingSums_[b].torque, &inside[b].momentum, &inside[b].angularMomentum})
        for (int a = 0; a < 3; ++a) (*v)[a] = flat[k++];
  }

  // Load = forcing + rigid-body correction - rho V g (buoyancy: the fluid carries gravity, so the
  // forcing inside a body at rest in a fluid at rest is zero and the hydrostatic pressure's share
  // of the stress integral, seed eq. 2.22, is added here).
  auto loadOf = [&](const Body& body, const FaceSums& forcing, const FaceSums& now, const Vec3& before,
                    const Vec3& angularBefore, bool known) {
    BodyLoad l;
    l.force = forcing.force - rho_ * bodyVolume(body, depth_) * gravity_;
    l.torque = forcing.torque;
    if (known) {
      l.force += rho_ * (now.momentum - before) / dt;
      l.torque += rho_ * (now.angularMomentum - angularBefore) / dt;
    }
    return l;
  };
  for (std::size_t b = 0; b < nf; ++b) {
    FixedBody& f = fixed_[b];
    f.load = loadOf(f.body, forcingSums_[b], inside[b], f.fluidMomentum, f.fluidAngularMomentum, fixedKnown_);
    f.fluidMomentum = inside[b].momentum;
    f.fluidAngularMomentum = inside[b].angularMomentum;
  }
  fixedKnown_ = true;
  particles.enableExternalForces();
  auto& momentum = particles.vec3Columns[momentumColumn_].values;
  auto& angular = particles.vec3Columns[angularColumn_].values;
  auto& known = particles.doubleColumns[knownColumn_].values;
  for (std::size_t q = 0; q < owned.size(); ++q) {
    const std::size_t i = owned[q];
    const BodyLoad l = loadOf(particleBodies_[q], forcingSums_[nf + q], inside[nf + q], momentum[i], angular[i],
                              known[i] != 0.0);
    particles.externalForce[i] = l.force;
    particles.externalTorque[i] = l.torque;
    momentum[i] = inside[nf + q].momentum;
    angular[i] = inside[nf + q].angularMomentum;
    known[i] = 1.0;
  }
  if (!owned.empty()) particles.hasExternalTorques = true;
  if (substepForceColumn_ != dem::ParticleSet::kNoColumn) {  // (the external force holds none of them now)
    for (Vec3& f : particles.vec3Columns[substepForceColumn_].values) f = Vec3{};
    for (Vec3& t : particles.vec3Columns[substepTorqueColumn_].values) t = Vec3{};
  }
}

void FictitiousDomain::addSubstepColumns(dem::ParticleSet& particles) {
  if (!lubrication_.enabled && !bodyContacts_) return;
  substepForceColumn_ = particles.addColumn("resolved_substep_force", Vec3{});
  substepTorqueColumn_ = particles.addColumn("resolved_substep_torque", Vec3{});
  for (std::size_t b = 0; b < fixed_.size(); ++b) {
    if (fixed_[b].material < 0) continue;
    fixed_[b].historyColumn = particles.addColumn(fmt::format("resolved_body_{}_tangential_history", b), Vec3{});
    fixed_[b].rollingColumn = particles.addColumn(fmt::format("resolved_body_{}_rolling_history", b), Vec3{});
  }
}

void FictitiousDomain::beforeDemStep(dem::ParticleSet& particles, double dt,
                                     const std::vector<dem::WallPrimitive>& walls) {
  if (substepForceColumn_ == dem::ParticleSet::kNoColumn || !particles.hasExternalForces) return;
  std::vector<std::size_t> owned;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (!particles.isGhost(i)) owned.push_back(i);
  std::vector<Vec3> force(particles.size()), torque(particles.size());
  if (lubrication_.enabled) lubricationForces(particles, owned, dt, walls, force);
  if (bodyContacts_) bodyContactForces(particles, owned, dt, force, torque);
  auto& appliedForce = particles.vec3Columns[substepForceColumn_].values;
  auto& appliedTorque = particles.vec3Columns[substepTorqueColumn_].values;
  for (std::size_t i : owned) {
    particles.externalForce[i] += force[i] - appliedForce[i];
    particles.externalTorque[i] += torque[i] - appliedTorque[i];
    appliedForce[i] = force[i];
    appliedTorque[i] = torque[i];
  }
  if (bodyContacts_) particles.hasExternalTorques = true;
}

void FictitiousDomain::bodyContactForces(dem::ParticleSet& p, const std::vector<std::size_t>& owned, double dt,
                                         std::vector<Vec3>& force, std::vector<Vec3>& torque) {
  const dem::ContactTable& table = *contacts_;
  dem::dispatchLaws(table.normalLaw(), table.rollingLaw(), table.cohesionLaw(), [&]<dem::NormalLaw N, dem::RollingLaw R,
                                                                                     dem::CohesionLaw C>() {
    for (const FixedBody& fb : fixed_) {
      if (fb.material < 0) continue;
      const Body& body = fb.body;
      auto& history = p.vec3Columns[fb.historyColumn].values;
      auto& rolling = p.vec3Columns[fb.rollingColumn].values;
      for (std::size_t i : owned) {
        Vec3 d = p.position[i] - body.centre;
        if (body.shape == Shape::Cylinder) d.z = 0.0;  // (axis along z)
        const double dist = norm(d), ri = p.radius[i];
        const double overlap = ri + body.radius - dist;
        if (!(overlap > 0.0) || dist <= 0.0) {
          history[i] = Vec3{};
          rolling[i] = Vec3{};
          continue;
        }
        // As a DEM wall contact (dem/wall_contact_forces.hpp): the body's surface point, moving with
        // its rigid velocity; R* of the two curvatures (a cylinder: that of its cross-section).
        dem::ContactGeometry g;
        g.normal = d / dist;
        g.overlap = overlap;
        const Vec3 contactPoint = p.position[i] - (dist - body.radius) * g.normal;
        g.relativeVelocity = p.velocity[i] - ri * cross(p.angularVelocity[i], g.normal) - rigidVelocity(body, contactPoint);
        g.relativeAngularVelocity = p.angularVelocity[i] - body.angularVelocity;
        g.effectiveRadius = reducedRadius(ri, body.radius);
        g.effectiveMass = p.mass[i];
        g.rollingInertia = 1.4 * p.mass[i] * ri * ri;
        const dem::ContactResult c = dem::contactForce<N, R, C>(table.pair(p.type[i], fb.material), g, history[i],
                                                               R == dem::RollingLaw::Epsd ? &rolling[i] : nullptr, dt);
        force[i] += c.force;
        torque[i] += c.rollingTorque - ri * cross(g.normal, c.tangential);
      }
    }
  });
}

void FictitiousDomain::lubricationForces(const dem::ParticleSet& p, const std::vector<std::size_t>& owned, double dt,
                                         const std::vector<dem::WallPrimitive>& walls, std::vector<Vec3>& out) const {
  const double mu = viscosity_;
  // The gap h between two surfaces and the normal n (towards particle i); c and F of lubrication.hpp.
  auto force = [&](double ri, double rj, double gap, double smallerDiameter, double vn, double reducedMass) {
    const double c = lubricationCoefficient(mu, reducedRadius(ri, rj), gap, lubrication_.range * smallerDiameter,
                                            lubrication_.minGap * smallerDiameter);
    return lubricationForce(c, vn, reducedMass, dt);
  };
  // Particle pairs (all pairs: resolved particles are few, one rank), minimum image along periodic axes.
  for (std::size_t a = 0; a < owned.size(); ++a) {
    const std::size_t i = owned[a];
    for (std::size_t b = a + 1; b < owned.size(); ++b) {
      const std::size_t j = owned[b];
      Vec3 d = p.position[i] - p.position[j];
      for (int ax = 0; ax < 3; ++ax)
        if (box_.periodic[ax]) d[ax] -= domainSize_[ax] * std::round(d[ax] / domainSize_[ax]);
      const double dist = norm(d);
      const double ri = p.radius[i], rj = p.radius[j];
      const double smaller = 2.0 * std::min(ri, rj);
      if (dist <= 0.0 || dist - ri - rj >= lubrication_.range * smaller) continue;
      const Vec3 n = d / dist;
      const double vn = dot(p.velocity[i] - p.velocity[j], n);
      const double f = force(ri, rj, dist - ri - rj, smaller, vn, p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]));
      out[i] += f * n;
      out[j] -= f * n;
    }
  }
  // Fixed spheres (at rest or rotating about their centre: no normal velocity of their surface).
  for (const FixedBody& fb : fixed_) {
    if (fb.body.shape != Shape::Sphere) continue;
    for (std::size_t i : owned) {
      const Vec3 d = p.position[i] - fb.body.centre;
      const double dist = norm(d), ri = p.radius[i];
      const double gap = dist - ri - fb.body.radius;
      if (dist <= 0.0 || gap >= lubrication_.range * 2.0 * ri) continue;
      const Vec3 n = d / dist;
      out[i] += force(ri, fb.body.radius, gap, 2.0 * ri, dot(p.velocity[i], n), p.mass[i]) * n;
    }
  }
  // DEM walls, at rest: per wall its nearest primitive (the triangles of a mesh share edges).
  for (std::size_t i : owned) {
    const double ri = p.radius[i];
    std::unordered_map<std::int32_t, dem::WallDistance> nearest;
    for (const dem::WallPrimitive& w : walls) {
      if (!w.active) continue;
      const dem::WallDistance wd = dem::distanceToPrimitive(w, p.position[i]);
      if (wd.distance - ri >= lubrication_.range * 2.0 * ri) continue;
      const auto it = nearest.find(w.wall);
      if (it == nearest.end() || wd.distance < it->second.distance) nearest[w.wall] = wd;
    }
    for (const auto& [wall, wd] : nearest) {
      const double vn = dot(p.velocity[i], wd.normal);
      out[i] += force(ri, std::numeric_limits<double>::infinity(), wd.distance - ri, 2.0 * ri, vn, p.mass[i]) * wd.normal;
    }
  }
}

void FictitiousDomain::setPenalty(fluid::Solver& fluid, double diagonal) {
  CouplingFields& fields = fluid.couplingFields();
  Field& K = fields.dragCoefficient;
  if (!penaltyCellsKnown_) {  // (first step, or after a restart: the fields came from the checkpoint)
    K.fill(0.0);
    for (int c = 0; c < 3; ++c) fields.particleVelocity[c].fill(0.0);
    penaltyCellsKnown_ = true;
  }
  for (std::size_t q : penaltyCells_) {  // the last step's cells back to K = 0
    K.data()[q] = 0.0;
    for (int c = 0; c < 3; ++c) fields.particleVelocity[c].data()[q] = 0.0;
  }
  penaltyCells_.clear();
  auto add = [&](const Body& body) {
    forEachCoveredCell(forcingBody(body), box_, [&](int i, int j, int k, const Vec3& x, double phi) {
      const std::size_t q = K.index(i, j, k);
      if (K.data()[q] == 0.0) penaltyCells_.push_back(q);
      const double k1 = penaltyCoefficient(phi, diagonal);
      const Vec3 ub = rigidVelocity(body, x);
      K.data()[q] += k1;
      for (int c = 0; c < 3; ++c) fields.particleVelocity[c].data()[q] += k1 * ub[c];  // (sum K u_b, divided below)
    });
  };
  if (implicit_)
    for (const FixedBody& f : fixed_) add(f.body);
  if (particleImplicit_)
    for (const Body& b : particleBodies_) add(b);
  for (std::size_t q : penaltyCells_)
    for (int c = 0; c < 3; ++c) fields.particleVelocity[c].data()[q] /= K.data()[q];
}

BodyLoad FictitiousDomain::particleLoad(const dem::ParticleSet& particles, std::int64_t id) const {
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.id[i] == id && !particles.isGhost(i) && particles.hasExternalForces)
      return {particles.externalForce[i], particles.externalTorque[i]};
  return {};
}

void FictitiousDomain::save(BinaryWriter& out, const dem::ParticleSet& particles) const {
  out.put<std::uint8_t>(fixedKnown_ ? 1 : 0);
  out.put<std::uint64_t>(fixed_.size());
  for (const FixedBody& f : fixed_) {
    out.put(f.fluidMomentum);
    out.put(f.fluidAngularMomentum);
    out.put(f.load.force);
    out.put(f.load.torque);
  }
  std::vector<std::int64_t> ids;
  std::vector<Vec3> m, a;
  std::vector<double> k;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.isGhost(i)) continue;
    ids.push_back(particles.id[i]);
    m.push_back(particles.vec3Columns[momentumColumn_].values[i]);
    a.push_back(particles.vec3Columns[angularColumn_].values[i]);
    k.push_back(particles.doubleColumns[knownColumn_].values[i]);
  }
  out.putVector(ids);
  out.putVector(m);
  out.putVector(a);
  out.putVector(k);
}

void FictitiousDomain::load(BinaryReader& in, dem::ParticleSet& particles) {
  penaltyCells_.clear();
  penaltyCellsKnown_ = false;
  fixedKnown_ = in.get<std::uint8_t>() != 0;
  const auto n = in.get<std::uint64_t>();
  if (n != fixed_.size()) throw Error("checkpoint: resolved bodies differ from the case");
  for (FixedBody& f : fixed_) {
    f.fluidMomentum = in.get<Vec3>();
    f.fluidAngularMomentum = in.get<Vec3>();
    f.load.force = in.get<Vec3>();
    f.load.torque = in.get<Vec3>();
  }
  const auto ids = in.getVector<std::int64_t>();
  const auto m = in.getVector<Vec3>();
  const auto a = in.getVector<Vec3>();
  const auto k = in.getVector<double>();
  momentumColumn_ = particles.addColumn("resolved_fluid_momentum", Vec3{});
  angularColumn_ = particles.addColumn("resolved_fluid_angular_momentum", Vec3{});
  knownColumn_ = particles.addColumn("resolved_fluid_momentum_known", 0.0);
  addSubstepColumns(particles);
  std::unordered_map<std::int64_t, std::size_t> where;
  for (std::size_t q = 0; q < ids.size(); ++q) where[ids[q]] = q;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const auto it = where.find(particles.id[i]);
    if (it == where.end()) continue;
    particles.vec3Columns[momentumColumn_].values[i] = m[it->second];
    particles.vec3Columns[angularColumn_].values[i] = a[it->second];
    particles.doubleColumns[knownColumn_].values[i] = k[it->second];
  }
}

}  // namespace gf::resolved
