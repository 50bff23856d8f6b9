#include "fluid/solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "io/stl_reader.hpp"
#include "fluid/initial_condition.hpp"
#include "fluid/loops.hpp"
#include "fluid/solid_mesh.hpp"
#include "parallel/halo.hpp"
#include "parallel/reductions.hpp"

namespace gf::fluid {

namespace {
int axisFromName(const std::string& s) { return s == "x" ? 0 : (s == "y" ? 1 : 2); }
constexpr const char* kComponentNames[3] = {"velocity_x", "velocity_y", "velocity_z"};
}  // namespace

Solver::Solver(Params& root, const Domain& domain, const Vec3& gravity, const parallel::Decomposition& decomposition)
    : decomposition_(std::make_shared<const parallel::Decomposition>(decomposition)), domain_(domain), gravity_(gravity) {
  Params fluid = root.section({"fluid", "-", "incompressible (volume-averaged) Navier-Stokes solver"});
  readParams(fluid, domain);
  coupling_ = CouplingFields(grid_);
  bc_.voidFraction = &coupling_.voidFraction;
  for (int c = 0; c < 3; ++c) {
    const auto st = static_cast<Staggering>(c + 1);
    u_[c] = Field(grid_, st);
    uOld_[c] = Field(grid_, st);
    guessError_[c] = Field(grid_, st);
    conv_[c] = Field(grid_, st);
    convOld_[c] = Field(grid_, st);
    rhs_[c] = Field(grid_, st);
    precY_[c] = Field(grid_, st);
    precZ_[c] = Field(grid_, st);
  }
  p_ = Field(grid_);
  phi_ = Field(grid_);
  epsOlder_ = Field(grid_, Staggering::Cell, 1.0);
  epsStep_ = Field(grid_, Staggering::Cell, 1.0);
  scalar_ = Field(grid_);
  blocked_.assign(p_.data().size(), 0);
  markBlocked(fluid);
  buildUnknownMasks();
  std::size_t maxSize = 0;
  for (int c = 0; c < 3; ++c) maxSize = std::max(maxSize, u_[c].data().size());
  for (auto& v : krylov_) v.assign(maxSize, 0.0);  // r, rhat, p, v, s, t, 1/diag
  poissonRhs_.assign(grid_.interiorCellCount(), 0.0);
  poissonX_.assign(grid_.interiorCellCount(), 0.0);

  Params init = fluid.section({"initial", "-", "initial condition"});
  const InitialCondition initial = readInitialCondition(init, rho_);  // fluid/initial_condition.hpp
  setVelocity(initial.velocity);
  setPressure(initial.pressure);
  setScalar([&](const Vec3&) { return initial.scalar; });
  readVof(fluid);  // fluid.vof (fluid/vof_step.cpp)
}

void Solver::readParams(Params& fluid, const Domain& domain) {
  rho_ = fluid.real({"density", "kg/m^3", "fluid density", Range::positive()}, 1000.0);
  mu_ = fluid.real({"viscosity", "Pa s", "dynamic viscosity", Range::nonNegative()}, 1e-3);
  const Vec3 cells = fluid.vec3({"cells", "-", "grid cells per direction [nx, ny, nz]; nz = 1 is 2D"}, Vec3{16, 16, 16});
  grid_.ghosts = 2;
  grid_.origin = domain.min;
  for (int a = 0; a < 3; ++a) {
    const double n = cells[a];
    if (!fluid.documenting() && (n < 1 || n != std::floor(n) || n > 1e5))
      fluid.fail("cells", fmt::format("{:g} cells along axis {}", n, a), "a positive integer per direction");
    grid_.cells[a] = fluid.documenting() ? 16 : static_cast<int>(n);
    grid_.spacing[a] = (domain.max[a] - domain.min[a]) / grid_.cells[a];
  }
  twoD_ = grid_.cells[2] == 1;
  const std::array<int, 3> globalCells = grid_.cells;
  globalGrid_ = grid_;
  const parallel::Decomposition& given = *decomposition_;
  if (given.distributed() && !fluid.documenting()) {
    if (given.explicitBoxes())
      fluid.fail("cells", fmt::format("a grid on {} explicit boxes", given.ranks()),
                 "a Cartesian layout of the ranks (the fluid grid is split into boxes of whole cells)");
    // This rank's box of cells (a layout without the grid's cuts: rebuilt with them).
    try {
      const parallel::Decomposition withCells(domain, given.layout(), given.ranks(), given.rank(), globalCells);
      if (given.gridded()) {
        // (its cuts may be uneven: a rebalanced layout, app/simulation.cpp)
        for (int a = 0; a < 3; ++a)
          if (given.cellCuts()[static_cast<std::size_t>(a)].back() != globalCells[static_cast<std::size_t>(a)])
            throw std::invalid_argument("the decomposition was built for another grid than fluid.cells");
      } else {
        decomposition_ = std::make_shared<const parallel::Decomposition>(withCells);
      }
    } catch (const std::invalid_argument& e) {
      fluid.fail("cells", fmt::format("[{}, {}, {}] on {} ranks ({})", globalCells[0], globalCells[1], globalCells[2],
                                      given.ranks(), e.what()),
                 "a grid that the decomposition " + given.describe() + " splits");
    }
    for (int a = 0; a < 3; ++a) {
      grid_.cells[a] = decomposition_->cellCount()[a];
      grid_.origin[a] = domain.min[a] + decomposition_->cellOffset()[a] * grid_.spacing[a];
    }
  }
  model_ = fluid.choice({"model", "-", "volume-averaged momentum form: A (-eps grad p) or B (-grad p)"}, {"A", "B"}, "A") ==
                   "A"
               ? MomentumModel::A
               : MomentumModel::B;
  scheme_ = fluid.choice({"convection", "-",
                          "convection scheme: central (2nd order) or van_leer (TVD); with fluid.vof the momentum "
                          "moves upwind with the phases' mass fluxes"},
                         {"central", "van_leer"}, "van_leer") == "central"
                ? ConvectionScheme::Central
                : ConvectionScheme::VanLeer;
  cfl_ = fluid.real({"cfl", "-", "Courant number used by stableTimeStep", Range{0.0, 2.0, false, true}}, 0.5);
  cflLimit_ = fluid.real({"cfl_limit", "-", "Courant number above which checkHealth stops the run", Range::positive()}, 1.0);
  momentumTolerance_ = fluid.real(
      {"momentum_tolerance", "-", "relative residual of the implicit momentum (Helmholtz) solves", Range::positive()},
      1e-8);
  momentumMaxIterations_ = static_cast<int>(
      fluid.integer({"momentum_max_iterations", "-", "iteration cap of the momentum solves", Range::atLeast(1)}, 200));
  Params pressure = fluid.section({"pressure", "-", "pressure Poisson solver (preconditioned CG)"});
  hyprePressure_ =
      pressure.choice({"solver", "-",
                       "multigrid: grainflow's multigrid-preconditioned CG (threaded, the fastest on one process; on "
                       "several ranks it solves the whole grid on rank 0 up to gather_cells cells, and hypre takes "
                       "larger grids); hypre: hypre's structured PCG preconditioned by PFMG on every rank "
                       "(initialises MPI)"},
                      {"multigrid", "hypre"}, "multigrid") == "hypre";
  const auto gatherCells = pressure.integer(
      {"gather_cells", "-",
       "on several ranks with solver: multigrid, the largest grid (cells in all) whose pressure is gathered onto "
       "rank 0 and solved there by the multigrid (two messages per solve instead of a message round per "
       "sweep; the bits of a one-rank run); larger grids go through hypre",
       Range::atLeast(0)},
      262144);
  if (decomposition_->distributed() && !hyprePressure_) {
    const long long wholeCells = static_cast<long long>(globalCells[0]) * globalCells[1] * globalCells[2];
    if (wholeCells <= gatherCells) {
      gatheredPressure_ = true;
    } else {
      // The multigrid works on a whole grid: a decomposed grid's pressure goes through hypre.
      hyprePressure_ = true;
      if (decomposition_->rank() == 0)
        spdlog::info("fluid.pressure.solver: the grid has {} cells, more than fluid.pressure.gather_cells = {}; the "
                     "pressure of this run on {} ranks goes through hypre",
                     wholeCells, gatherCells, decomposition_->ranks());
    }
  }
  pressureTolerance_ = pressure.real({"tolerance", "-", "relative residual ||b - A x|| / ||b||", Range::positive()}, 1e-8);
  pressureMaxIterations_ =
      static_cast<int>(pressure.integer({"max_iterations", "-", "iteration cap", Range::atLeast(1)}, 200));
  correctors_ = static_cast<int>(fluid.integer(
      {"correctors", "-",
       "pressure projections per step: 1 = incremental projection; N > 1 adds PISO-style correctors (momentum "
       "residual with the new pressure, one Jacobi update, projection again) that remove the splitting error "
       "of the implicit viscous and drag terms",
       Range{1.0, 20.0, true, true}},
      1));

  Params drive = fluid.section({"driving", "-", "mean pressure gradient or flow rate along a periodic axis"});
  const std::string mode = drive.choice({"mode", "-", "none | pressure_gradient | flow_rate"},
                                        {"none", "pressure_gradient", "flow_rate"}, "none");
  driveAxis_ = axisFromName(drive.choice({"axis", "-", "driving axis"}, {"x", "y", "z"}, "x"));
  drive_ = drive.real({"pressure_gradient", "Pa/m", "imposed -dp/dx (mode pressure_gradient); initial guess otherwise"}, 0.0);
  bulkVelocity_ = drive.real({"bulk_velocity", "m/s", "imposed mean superficial velocity (mode flow_rate)"}, 0.0);
  driveMode_ = mode == "none" ? DrivingMode::None
                              : (mode == "pressure_gradient" ? DrivingMode::PressureGradient : DrivingMode::FlowRate);
  if (driveMode_ == DrivingMode::None) drive_ = 0.0;
  if (!fluid.documenting() && driveMode_ == DrivingMode::FlowRate && !domain.periodic[driveAxis_])
    drive.fail("mode", "flow_rate along a non-periodic axis", "a periodic driving axis");

  Params sc = fluid.section({"scalar", "-", "passive scalar (temperature, species)"});
  scalarEnabled_ = sc.boolean({"enabled", "-", "transport a passive scalar"}, false);
  scalarDiffusivity_ = sc.real({"diffusivity", "m^2/s", "scalar diffusivity", Range::nonNegative()}, 0.0);
  scalarSource_ = sc.real({"source", "1/s", "uniform volumetric source (scalar units per second)"}, 0.0);

  std::array<bool, 3> periodic = domain.periodic;
  bc_ = Boundaries::read(fluid, periodic, twoD_);
  if (decomposition_->distributed()) bc_.decompose(decomposition_, domain.min, globalCells);
}

void Solver::markBlocked(Params& fluid) {
  for (Params& b : fluid.list({"blocked", "-", "solid (blocked) regions: boxes, cylinders and closed STL meshes"})) {
    const std::string shape =
        b.choice({"shape", "-", "box, cylinder or stl (cells whose centre is inside a closed triangle mesh)"},
                 {"box", "cylinder", "stl"});
    const Vec3 lo = b.vec3({"min", "m", "box lower corner"}, Vec3{});
    const Vec3 hi = b.vec3({"max", "m", "box upper corner"}, Vec3{});
    const Vec3 centre = b.vec3({"centre", "m", "cylinder: a point on the axis"}, Vec3{});
    const int axis = axisFromName(b.choice({"axis", "-", "cylinder axis direction"}, {"x", "y", "z"}, "z"));
    const double radius = b.real({"radius", "m", "cylinder radius"}, 0.0);
    const std::string file =
        b.text({"file", "-", "stl: path of a closed ASCII or binary STL mesh (relative to the case file)"}, "");
    const double scale =
        b.real({"scale", "-", "stl: factor applied to the coordinates (e.g. 0.001 for mm)", Range::positive()}, 1.0);
    const Vec3 offset = b.vec3({"offset", "m", "stl: translation applied after scaling"}, Vec3{});
    if (b.documenting()) continue;
    std::optional<SolidMesh> mesh;
    if (shape == "stl") {
      std::filesystem::path path(file);
      if (path.is_relative()) path = std::filesystem::path(b.fileName()).parent_path() / path;
      try {
        auto triangles = io::readStl(path.string());
        for (auto& t : triangles)
          for (Vec3& v : t) v = scale * v + offset;
        mesh.emplace(std::move(triangles));
      } catch (const Error& e) {
        b.fail("file", "'" + file + "'", std::string("a readable STL file (") + e.what() + ")");
      }
    }
    // (on a decomposed grid also the ghost cells across shared sides: the faces on a cut and the
    // stencils next to it see the neighbour's blocked cells)
    int first[3], end[3];
    for (int a = 0; a < 3; ++a) {
      first[a] = bc_.shared(a, 0) ? -grid_.ghosts : 0;
      end[a] = grid_.cells[a] + (bc_.shared(a, 1) ? grid_.ghosts : 0);
    }
    for (int k = first[2]; k < end[2]; ++k)
      for (int j = first[1]; j < end[1]; ++j)
        for (int i = first[0]; i < end[0]; ++i) {
          const Vec3 x = grid_.cellCentre(i, j, k);
          bool inside;
          if (shape == "box") {
            inside = x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
          } else if (shape == "cylinder") {
            double r2 = 0.0;
            for (int a = 0; a < 3; ++a)
              if (a != axis) r2 += (x[a] - centre[a]) * (x[a] - centre[a]);
            inside = r2 <= radius * radius;
          } else {
            inside = mesh->contains(x);
          }
          if (inside) blocked_[p_.index(i, j, k)] = 1;
        }
  }
}

void Solver::buildUnknownMasks() {
  for (int c = 0; c < 3; ++c) {
    const Field& u = u_[c];
    unknown_[c].assign(u.data().size(), 0);
    unknownList_[c].clear();
    unknownLineStart_[c].clear();
    if (twoD_ && c == 2) continue;
    const auto& pts = u.points();
    const int n = grid_.cells[c];
    for (int k = 0; k < pts[2]; ++k)
      for (int j = 0; j < pts[1]; ++j) {
        unknownLineStart_[c].push_back(static_cast<std::int64_t>(unknownList_[c].size()));
        for (int i = 0; i < pts[0]; ++i) {
          const int idx[3] = {i, j, k};
          const int f = idx[c];
          if (f == n) continue;
          // (face 0 across a shared side is this rank's; face n there is the upper rank's face 0)
          if (f == 0 && bc_.physical(c, 0)) continue;
          int lo[3] = {i, j, k};
          lo[c] = f == 0 ? (bc_.periodic(c) ? n - 1 : -1) : f - 1;
          if (blocked_[p_.index(lo[0], lo[1], lo[2])] || (f < n && blocked_[p_.index(i, j, k)])) continue;
          const std::size_t id = u.index(i, j, k);
          unknown_[c][id] = 1;
          unknownList_[c].push_back(static_cast<std::int64_t>(id));
        }
      }
    unknownLineStart_[c].push_back(static_cast<std::int64_t>(unknownList_[c].size()));
  }
  // Whether any rank has unknowns of a component (a rank without any still takes part in the
  // others' reductions): decided once, here.
  const parallel::RankReductionScope ranks(*decomposition_);
  for (int c = 0; c < 3; ++c) anyUnknowns_[c] = maxAcrossRanks(unknownList_[c].empty() ? 0.0 : 1.0) > 0.0;
}

void Solver::fillAllGhosts() {
  // After a step's projection only the axes from the first inlet / moving wall on need a refill
  // (the others' ghosts are functions of the unchanged interior values: the same numbers), and p's
  // ghosts none (a 2 x 30 x 90 bed: the x sides are 60 % of the ghost fill work).
  const int firstAxis = ghostsFresh_ ? firstTimeDependentVelocityAxis(bc_) : 0;
  const bool fresh = ghostsFresh_;
  // A decomposed grid: the ghosts across the cuts of every field below in one exchange (one
  // message per neighbour), then each field's fill without its own exchange (the same values:
  // the fills change no point that the exchange sends and the others' fills overwrite).
  const bool batch = bc_.distributed();
  if (batch) {
    std::vector<Field*> fields{&coupling_.voidFraction, &u_[0], &u_[1], &u_[2]};
    if (!fresh) fields.push_back(&p_);
    for (Field* f : {&coupling_.voidFractionOld, &epsOlder_, &coupling_.dragCoefficient}) fields.push_back(f);
    for (int c = 0; c < 3; ++c) {
      fields.push_back(&coupling_.forceDensity[c]);
      fields.push_back(&coupling_.particleVelocity[c]);
    }
    if (scalarEnabled_) fields.push_back(&scalar_);
    parallel::fillGhosts(fields, *decomposition_);
  }
  // Small grids: on a plane team, each member the ghosts of its planes (every field in the
  // order below: the same values).
  forCellPlanes(ghostTeam_, [&](const PlaneSlab* slab) {
    auto planesOf = [&](const Field& f) {
      GhostPlanes planes = slab ? slab->ghostPlanes(f.points()) : GhostPlanes{};
      planes.exchange = !batch;
      return planes;
    };
    auto cells = [&](Field& f, CellGhostKind kind) { fillCellGhostsPlanes(f, bc_, kind, planesOf(f)); };
    cells(coupling_.voidFraction, CellGhostKind::ZeroGradient);  // first: superficial inlets use it
    for (int c = 0; c < 3; ++c) fillVelocityGhostsPlanes(u_[c], c, bc_, GhostMode::Full, planesOf(u_[c]), firstAxis);
    if (!fresh) cells(p_, CellGhostKind::Pressure);
    // eps_old, eps_older, F and u_p are read only at momentum unknown faces (cell on each side:
    // a ghost only across a periodic boundary); K also at pressure outlet faces.
    cells(coupling_.voidFractionOld, CellGhostKind::PeriodicOnly);
    cells(epsOlder_, CellGhostKind::PeriodicOnly);
    cells(coupling_.dragCoefficient, CellGhostKind::ZeroGradient);
    for (int c = 0; c < 3; ++c) {
      cells(coupling_.forceDensity[c], CellGhostKind::PeriodicOnly);
      cells(coupling_.particleVelocity[c], CellGhostKind::PeriodicOnly);
    }
    if (scalarEnabled_) cells(scalar_, CellGhostKind::Scalar);
  });
  ghostsFresh_ = false;  // the step changes u and p
}

void Solver::setVelocity(const std::function<Vec3(const Vec3&)>& f) {
  healthCheckedAt_ = -1;
  for (int c = 0; c < 3; ++c) {
    Field& u = u_[c];
    const auto& pts = u.points();
    for (int k = 0; k < pts[2]; ++k)
      for (int j = 0; j < pts[1]; ++j)
        for (int i = 0; i < pts[0]; ++i) {
          Vec3 x = grid_.cellCentre(i, j, k);
          x[c] -= 0.5 * grid_.spacing[c];
          const std::size_t id = u.index(i, j, k);
          u.data()[id] = unknown_[c][id] ? f(x)[c] : 0.0;
        }
    // Outlet faces start as their neighbours (they are not momentum unknowns).
    for (int s = 0; s < 2; ++s) {
      if (!isOutlet(bc_.at(c, s).type)) continue;
      const int n = grid_.cells[c];
      for (int k = 0; k < pts[2]; ++k)
        for (int j = 0; j < pts[1]; ++j)
          for (int i = 0; i < pts[0]; ++i) {
            int idx[3] = {i, j, k};
            if (idx[c] != (s == 0 ? 0 : n)) continue;
            int nb[3] = {i, j, k};
            nb[c] = s == 0 ? 1 : n - 1;
            u(i, j, k) = u(nb[0], nb[1], nb[2]);
          }
    }
    fillVelocityGhosts(u, c, bc_, GhostMode::Full);
    uOld_[c] = u;
    std::fill(guessError_[c].data().begin(), guessError_[c].data().end(), 0.0);
  }
}

void Solver::setPressure(const std::function<double(const Vec3&)>& f) {
  healthCheckedAt_ = -1;
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) p_(i, j, k) = f(grid_.cellCentre(i, j, k));
  fillCellGhosts(p_, bc_, CellGhostKind::Pressure);
}

void Solver::setScalar(const std::function<double(const Vec3&)>& f) {
  healthCheckedAt_ = -1;
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) scalar_(i, j, k) = f(grid_.cellCentre(i, j, k));
  fillCellGhosts(scalar_, bc_, CellGhostKind::Scalar);
}

void Solver::step(double dt) {
  if (vof_) return stepVof(dt);  // several fluids (fluid/vof_step.cpp)
  ScopedPhase timer(timers_, Phase::Fluid);
  const parallel::RankReductionScope ranks(*decomposition_);
  const SerialFluidScope serial(grid_.interiorCellCount() < kSerialCellsBelow);
  bc_.time = time_ + dt;  // prescribed (ramped) boundary velocities at the new time level
  bc_.voidFraction = &coupling_.voidFraction;  // (the solver may have been moved)
  fillAllGhosts();
  const auto& eps = coupling_.voidFraction.data();
  const auto& epsOld = coupling_.voidFractionOld.data();
  const auto& K = coupling_.dragCoefficient.data();
  // eps = eps_old = 1 and K = 0 everywhere (ghosts included)? Scanned in fixed chunks, each
  // stopping at its first non-uniform value (a boolean: the same answer for any thread count).
  constexpr std::size_t kChunk = 16384;
  const std::size_t chunks = (eps.size() + kChunk - 1) / kChunk;
  std::vector<std::uint8_t> chunkUniform(chunks, 1);
  parallelForAbove(static_cast<std::int64_t>(chunks), 8, [&](std::int64_t q) {
    const std::size_t end = std::min(eps.size(), (static_cast<std::size_t>(q) + 1) * kChunk);
    for (std::size_t i = static_cast<std::size_t>(q) * kChunk; i < end; ++i)
      if (!(eps[i] == 1.0 && epsOld[i] == 1.0 && K[i] == 0.0)) {
        chunkUniform[static_cast<std::size_t>(q)] = 0;
        break;
      }
  });
  bool uniform = true;
  for (std::uint8_t u : chunkUniform) uniform = uniform && u != 0;
  // (on every rank: the solvers' paths, and their reductions, depend on it)
  if (decomposition_->distributed()) uniform = maxAcrossRanks(uniform ? 0.0 : 1.0) == 0.0;
  uniformCoupling_ = uniform;
  if (steps_ == 0) {
    epsOlder_ = coupling_.voidFractionOld;
    epsOlderOnes_ = uniform;
  }
  // Variable-step BDF2 (BDF1 on the first step) and matching extrapolation of convection.
  double g0 = 1.0, g1 = 1.0, g2 = 0.0, e1 = 1.0, e2 = 0.0;
  if (steps_ > 0 && dtPrev_ > 0.0) {
    const double w = dt / dtPrev_;
    g0 = (1.0 + 2.0 * w) / (1.0 + w);
    g1 = 1.0 + w;
    g2 = w * w / (1.0 + w);
    e1 = 1.0 + w;
    e2 = w;
  }
  stats_ = StepStatistics{};
  if (!predictMomentumTeam(dt, g0, g1, g2, e1, e2)) {
    computeConvection(conv_);
    for (int c = 0; c < (twoD_ ? 2 : 3); ++c) assembleMomentum(c, dt, g0, g1, g2, e1, e2);
    // Each solve also moves u^n into uOld_ (u^{n-1} of the next step).
    for (int c = 0; c < 3; ++c) stats_.momentumIterations += solveHelmholtz(c, dt, g0);
  }
  if (predictorHook_) predictorHook_(u_, dt, g0);  // direct forcing of resolved bodies (setPredictorHook)
  balanceOutflow(dt);
  {
    ScopedPhase pt(timers_, Phase::PressureSolve);
    project(dt, g0);
  }
  if (correctors_ > 1) {
    firstIncrement_ = poissonX_;  // the initial guess of the next step's first projection
    for (int corr = 1; corr < correctors_; ++corr) {
      stats_.momentumResidual = correctMomentum(dt, g0);
      balanceOutflow(dt);
      ScopedPhase pt(timers_, Phase::PressureSolve);
      std::fill(poissonX_.begin(), poissonX_.end(), 0.0);
      project(dt, g0);
    }
    poissonX_.swap(firstIncrement_);
  }
  if (driveMode_ == DrivingMode::FlowRate) controlFlowRate(dt, g0);
  for (int c = 0; c < 3; ++c) convOld_[c].data().swap(conv_[c].data());
  // eps_older <- eps_old (a copy of the whole field: skipped while both are 1 everywhere)
  if (!(uniform && epsOlderOnes_)) {
    epsOlder_ = coupling_.voidFractionOld;
    epsOlderOnes_ = uniform;
  }
  // eps_step <- eps (the pair eps_step, eps_older is the one this step's continuity equation used)
  if (!(uniform && epsStepOnes_)) {
    epsStep_ = coupling_.voidFraction;
    epsStepOnes_ = uniform;
  }
  finishStep(dt);
}

void Solver::finishStep(double dt) {
  epsStepKept_ = true;
  dtPrev_ = dt;
  lastDt_ = dt;
  time_ += dt;
  ++steps_;
  if (scalarEnabled_) advanceScalar(dt);
}

double Solver::stableTimeStep() const {
  const parallel::RankReductionScope ranks(*decomposition_);
  const int nx = grid_.cells[0], ny = grid_.cells[1], nz = grid_.cells[2];
  double rate = 0.0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double r = 0.0;
        for (int c = 0; c < (twoD_ ? 2 : 3); ++c) {
          int hi[3] = {i, j, k};
          hi[c] += 1;
          r += 0.5 * std::abs(u_[c](i, j, k) + u_[c](hi[0], hi[1], hi[2])) / grid_.spacing[c];
        }
        rate = std::max(rate, r);
      }
  rate = maxAcrossRanks(rate);
  return rate > 0.0 ? cfl_ / rate : std::numeric_limits<double>::max();
}

void Solver::cellVelocity(Field out[3], CellGhosts ghosts) const {
  // Called by the coupling every fluid step: small grids loop serially, as in step(), or on a
  // plane team (each member its planes and their ghosts).
  const SerialFluidScope serial(grid_.interiorCellCount() < kSerialCellsBelow);
  for (int c = 0; c < 3; ++c)
    if (out[c].data().size() != p_.data().size()) out[c] = Field(grid_);
  forCellPlanes(cellVelocityTeam_, [&](const PlaneSlab* slab) {
    for (int c = 0; c < 3; ++c) {
      Field& o = out[c];
      const Field& u = u_[c];
      const auto s = u.stride(c);
      auto line = [&](std::int64_t line) {
        const int j = static_cast<int>(line % grid_.cells[1]), k = static_cast<int>(line / grid_.cells[1]);
        for (int i = 0; i < grid_.cells[0]; ++i) {
          const std::size_t f = u.index(i, j, k);
          o(i, j, k) = 0.5 * (u.data()[f] + u.data()[f + s]);
        }
      };
      cellLinesAndGhosts(slab, o, line, ghosts);
    }
  });
}

void Solver::pressureGradient(Field out[3], CellGhosts ghosts) const {
  const SerialFluidScope serial(grid_.interiorCellCount() < kSerialCellsBelow);
  for (int c = 0; c < 3; ++c)
    if (out[c].data().size() != p_.data().size()) out[c] = Field(grid_);
  forCellPlanes(pressureGradientTeam_, [&](const PlaneSlab* slab) {
    for (int c = 0; c < 3; ++c) {
      Field& o = out[c];
      const auto s = p_.stride(c);
      const double invH = 1.0 / grid_.spacing[c];
      // The mean driving gradient (-dp/dx = drive_, applied as a body force) is part of grad p: the
      // particles must feel it too (e.g. the buoyancy of a suspension in a periodic box).
      const double mean = (driveMode_ != DrivingMode::None && driveAxis_ == c) ? -drive_ : 0.0;
      const int n = grid_.cells[c];
      // Ghosts of zero normal gradient (walls, inlets, slip, outflow) and blocked neighbours carry
      // no pressure information: there the gradient is one-sided from the other neighbour (a
      // central difference with the mirrored value would halve it, e.g. the hydrostatic gradient,
      // i.e. the buoyancy of particles in the cells next to a wall). Pressure-outlet ghosts are
      // Dirichlet images and keep the central difference.
      const bool mirrorLow = bc_.physical(c, 0) && bc_.at(c, 0).type != BoundaryType::PressureOutlet;
      const bool mirrorHigh = bc_.physical(c, 1) && bc_.at(c, 1).type != BoundaryType::PressureOutlet;
      // Raw pointers and a line's base index hoisted; the three differences computed and one
      // selected (the same value as the branches it replaces: every neighbour index is inside the
      // ghost layers; no FP trap is enabled), so the 2-cell lines of a thin bed do not mispredict.
      const double* const pd = (vof_ ? pTotal_ : p_).data().data();  // (VOF: p, not p*)
      const std::uint8_t* const blocked = blocked_.data();
      double* const od = o.data().data();
      const bool zero = twoD_ && c == 2;
      const int nx = grid_.cells[0], ny = grid_.cells[1];
      auto line = [&, pd, blocked, od, zero, nx, ny, s, invH, mean, n, mirrorLow, mirrorHigh, c](std::int64_t line) {
        const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
        const std::size_t base = p_.index(0, j, k);
        const int lineAlong = c == 1 ? j : k;
        for (int i = 0; i < nx; ++i) {
          const std::size_t id = base + static_cast<std::size_t>(i);
          const int along = c == 0 ? i : lineAlong;
          const bool noPlus = blocked[id + s] || (mirrorHigh && along == n - 1);
          const bool noMinus = blocked[id - s] || (mirrorLow && along == 0);
          const double central = 0.5 * (pd[id + s] - pd[id - s]) * invH;
          const double forward = (pd[id + s] - pd[id]) * invH;
          const double backward = (pd[id] - pd[id - s]) * invH;
          const double g = !noPlus ? (!noMinus ? central : forward) : (!noMinus ? backward : 0.0);
          od[id] = zero ? 0.0 : g + mean;
        }
      };
      cellLinesAndGhosts(slab, o, line, ghosts);
    }
  });
}

template <class Body>
void Solver::forCellPlanes(TeamTuner& tuner, Body&& body) const {
  // A team where the planes can be split with their ghost fills (>= 2 planes per member, z not
  // periodic); otherwise one call with no slab (loops threaded as usual).
  const int team = teamSize();
  if (team <= 1 || bc_.periodic(2) || grid_.cells[2] < 2 * team) return body(static_cast<const PlaneSlab*>(nullptr));
  runPlaneTeam(tuner, team, grid_.cells[2], [&](const PlaneSlab& slab) { body(&slab); });
}

template <class Line>
void Solver::cellLinesAndGhosts(const PlaneSlab* slab, Field& out, Line&& line, CellGhosts ghosts) const {
  // line(l) for the cell lines of the slab's planes (all: threaded loop), then (CellGhosts::Filled)
  // the zero-gradient ghosts of those planes.
  const auto lines = static_cast<std::int64_t>(grid_.cells[1]) * grid_.cells[2];
  const bool fill = ghosts == CellGhosts::Filled;
  if (slab) {
    forLines(lines, slab->lineBegin(grid_.cells), slab->lineEnd(grid_.cells), line);
    if (fill) fillCellGhostsPlanes(out, bc_, CellGhostKind::ZeroGradient, slab->ghostPlanes(grid_.cells));
  } else {
    parallelFor(lines, line);
    if (fill) fillCellGhosts(out, bc_, CellGhostKind::ZeroGradient);
    // (a decomposed grid: the ghosts across the cuts are the neighbours' interior cells, which
    // the readers of the interior interpolate near a cut; exchanged with CellGhosts::Left too)
    else if (bc_.distributed() && ghosts == CellGhosts::Left) parallel::fillGhosts(out, *decomposition_);
  }
}

std::vector<NamedCellField> Solver::cellFields() const {
  std::vector<NamedCellField> out;
  out.reserve(6);
  Field v[3];
  cellVelocity(v);
  for (int c = 0; c < 3; ++c) out.push_back({kComponentNames[c], "m/s", std::move(v[c])});
  out.push_back({"pressure", "Pa", pressure()});
  out.push_back({"void_fraction", "-", coupling_.voidFraction});
  if (vof_) {
    for (std::size_t i = 0; i < phases_.size(); ++i) out.push_back({"alpha_" + phases_[i].name, "-", alpha_[i]});
    out.push_back({"mixture_density", "kg/m^3", rhoCell_});
    out.push_back({"modified_pressure", "Pa", p_});
  }
  if (scalarEnabled_) out.push_back({"scalar", "-", scalar_});
  return out;
}

bool Solver::healthyFast() const {
  // checkHealth's tests as branch-free line loops, each array read once: every value finite (|v| <=
  // DBL_MAX is false for NaN and inf), and every cell's CFL number within cfl_limit with
  // a relative margin of 1e-12, which covers the rounding of multiplying by 1 / spacing instead of
  // dividing as checkHealth does (a few ulps): near the limit, checkHealth's own loops decide.
  const int nx = grid_.cells[0], ny = grid_.cells[1], nz = grid_.cells[2];
  const int dims = twoD_ ? 2 : 3;
  constexpr double kMax = std::numeric_limits<double>::max();
  unsigned bad = 0;
  // (After a step the CFL loop below reads every point of the dims components: a NaN or inf
  // there makes its rate NaN or inf, which fails the test as well.)
  for (int c = 0; c < 3; ++c) {
    if (lastDt_ > 0.0 && c < dims) continue;
    const Field& u = u_[c];
    const auto& pts = u.points();
    for (int k = 0; k < pts[2]; ++k)
      for (int j = 0; j < pts[1]; ++j) {
        const double* line = u.data().data() + u.index(0, j, k);
        for (int i = 0; i < pts[0]; ++i) bad |= !(std::abs(line[i]) <= kMax);
      }
  }
  if (bad) return false;
  double invH[3];
  for (int c = 0; c < 3; ++c) invH[c] = 0.5 / grid_.spacing[c];
  const double rateLimit = lastDt_ > 0.0 ? cflLimit_ / lastDt_ / (1.0 + 1e-12) : kMax;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const double* P = p_.data().data() + p_.index(0, j, k);
      for (int i = 0; i < nx; ++i) bad |= !(std::abs(P[i]) <= kMax);
      if (scalarEnabled_) {
        const double* S = scalar_.data().data() + scalar_.index(0, j, k);
        for (int i = 0; i < nx; ++i) bad |= !(std::abs(S[i]) <= kMax);
      }
      if (lastDt_ > 0.0) {
        const double* U[3];
        std::ptrdiff_t s[3];
        for (int c = 0; c < 3; ++c) {
          U[c] = u_[c].data().data() + u_[c].index(0, j, k);
          s[c] = u_[c].stride(c);
        }
        for (int i = 0; i < nx; ++i) {
          double r = std::abs(U[0][i] + U[0][i + s[0]]) * invH[0] + std::abs(U[1][i] + U[1][i + s[1]]) * invH[1];
          if (dims == 3) r += std::abs(U[2][i] + U[2][i + s[2]]) * invH[2];
          bad |= !(r <= rateLimit);
        }
      }
      if (bad) return false;
    }
  return true;
}

void Solver::checkHealth(long long step, double time) const {
  // The fluid changes only in step(): one scan per fluid step is enough (the app may call this
  // after every DEM substep).
  if (healthCheckedAt_ == steps_) return;
  // A fast scan first, line by line with pointers (the loops below index every point through
  // Field::operator(): with the default health_check_interval 1 they cost a few per cent of a
  // fluid-only run); only if it finds a fault do those loops run, to report the first one.
  if (healthyFast()) {
    healthCheckedAt_ = steps_;
    return;
  }
  auto fail = [&](const std::string& quantity, int i, int j, int k, const Vec3& x, const std::string& detail) {
    throw DivergenceError(step, time, quantity, fmt::format("fluid cell ({}, {}, {})", i, j, k), x, detail);
  };
  for (int c = 0; c < 3; ++c) {
    const Field& u = u_[c];
    const auto& pts = u.points();
    for (int k = 0; k < pts[2]; ++k)
      for (int j = 0; j < pts[1]; ++j)
        for (int i = 0; i < pts[0]; ++i)
          if (!std::isfinite(u(i, j, k))) {
            Vec3 x = grid_.cellCentre(i, j, k);
            x[c] -= 0.5 * grid_.spacing[c];
            fail(std::string("fluid ") + kComponentNames[c], i, j, k, x, fmt::format("value {}", u(i, j, k)));
          }
  }
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) {
        if (!std::isfinite(p_(i, j, k)))
          fail("fluid pressure", i, j, k, grid_.cellCentre(i, j, k), fmt::format("value {}", p_(i, j, k)));
        if (scalarEnabled_ && !std::isfinite(scalar_(i, j, k)))
          fail("fluid scalar", i, j, k, grid_.cellCentre(i, j, k), fmt::format("value {}", scalar_(i, j, k)));
        if (lastDt_ > 0.0) {
          double r = 0.0;
          for (int c = 0; c < (twoD_ ? 2 : 3); ++c) {
            int hi[3] = {i, j, k};
            hi[c] += 1;
            r += 0.5 * std::abs(u_[c](i, j, k) + u_[c](hi[0], hi[1], hi[2])) / grid_.spacing[c];
          }
          const double cfl = r * lastDt_;
          if (cfl > cflLimit_)
            fail("fluid CFL number", i, j, k, grid_.cellCentre(i, j, k),
                 fmt::format("CFL {:.3g} > cfl_limit {:.3g} with dt = {:.3g} s", cfl, cflLimit_, lastDt_));
        }
      }
  healthCheckedAt_ = steps_;
}

void Solver::save(BinaryWriter& out) const {
  // The whole grid's arrays (ghosts included) in the layout of one rank: on a decomposed grid
  // gathered on rank 0, whose writer the checkpoint takes (a restart on any rank count reads the
  // same arrays and takes its box of them).
  const parallel::Decomposition& d = *decomposition_;
  Field whole;
  auto putField = [&](const Field& f) {
    if (!d.distributed()) return out.putVector(f.data());
    parallel::gatherField(f, d, globalGrid_, whole);
    out.putVector(whole.data());
  };
  out.putString("fluid-v2");
  out.put(globalGrid_.cells);
  out.put(time_);
  out.put(dtPrev_);
  out.put(lastDt_);
  out.put(steps_);
  out.put(drive_);
  for (int c = 0; c < 3; ++c) {
    putField(u_[c]);
    putField(uOld_[c]);
    putField(guessError_[c]);
    putField(convOld_[c]);
    putField(coupling_.forceDensity[c]);
    putField(coupling_.particleVelocity[c]);
  }
  putField(p_);
  putField(epsOlder_);
  putField(scalar_);
  putField(coupling_.voidFraction);
  putField(coupling_.voidFractionOld);
  putField(coupling_.dragCoefficient);
  if (!d.distributed()) {
    out.putVector(poissonX_);  // last pressure increment: initial guess of the next solve
  } else {
    // (the box's cells as a cell field, gathered, written as the whole grid's cells)
    Field increment(grid_);
    const int nx = grid_.cells[0], ny = grid_.cells[1];
    for (int k = 0; k < grid_.cells[2]; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          increment(i, j, k) = poissonX_[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k)];
    parallel::gatherField(increment, d, globalGrid_, whole);
    std::vector<double> cells;
    if (d.rank() == 0) {
      cells.reserve(globalGrid_.interiorCellCount());
      for (int k = 0; k < globalGrid_.cells[2]; ++k)
        for (int j = 0; j < globalGrid_.cells[1]; ++j)
          for (int i = 0; i < globalGrid_.cells[0]; ++i) cells.push_back(whole(i, j, k));
    }
    out.putVector(cells);
  }
  if (vof_) {
    out.putString("vof-v1");
    for (const Field& a : alpha_) putField(a);
    out.putVector(phaseOutflow_);
  }
}

void Solver::load(BinaryReader& in) {
  if (in.getString() != "fluid-v2") throw CheckpointError("fluid checkpoint: unknown section tag");
  if (in.get<std::array<int, 3>>() != globalGrid_.cells)
    throw CheckpointError("fluid checkpoint: grid size differs from the case file");
  time_ = in.get<double>();
  bc_.time = time_;
  dtPrev_ = in.get<double>();
  lastDt_ = in.get<double>();
  steps_ = in.get<long long>();
  drive_ = in.get<double>();
  // The whole grid's arrays (save()); on a decomposed grid this rank takes its box of them.
  const parallel::Decomposition& d = *decomposition_;
  auto readInto = [&](Field& f) {
    auto v = in.getVector<double>();
    if (!d.distributed()) {
      if (v.size() != f.data().size()) throw CheckpointError("fluid checkpoint: field size mismatch");
      f.data() = std::move(v);
      return;
    }
    Field whole(globalGrid_, f.staggering());
    if (v.size() != whole.data().size()) throw CheckpointError("fluid checkpoint: field size mismatch");
    whole.data() = std::move(v);
    parallel::extractBox(whole, d, f);
  };
  for (int c = 0; c < 3; ++c) {
    readInto(u_[c]);
    readInto(uOld_[c]);
    readInto(guessError_[c]);
    readInto(convOld_[c]);
    readInto(coupling_.forceDensity[c]);
    readInto(coupling_.particleVelocity[c]);
  }
  readInto(p_);
  ghostsFresh_ = false;
  readInto(epsOlder_);
  epsOlderOnes_ = false;
  epsStepKept_ = false;
  readInto(scalar_);
  readInto(coupling_.voidFraction);
  readInto(coupling_.voidFractionOld);
  readInto(coupling_.dragCoefficient);
  auto guess = in.getVector<double>();
  if (guess.size() != globalGrid_.interiorCellCount())
    throw CheckpointError("fluid checkpoint: pressure increment size mismatch");
  if (!d.distributed()) {
    poissonX_ = std::move(guess);
  } else {
    const auto off = d.cellOffset();
    const int nx = grid_.cells[0], ny = grid_.cells[1], NX = globalGrid_.cells[0], NY = globalGrid_.cells[1];
    for (int k = 0; k < grid_.cells[2]; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          poissonX_[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k)] =
              guess[static_cast<std::size_t>(i + off[0]) +
                    static_cast<std::size_t>(NX) * (j + off[1] + static_cast<std::size_t>(NY) * (k + off[2]))];
  }
  poissonKey_ = -1.0;
  healthCheckedAt_ = -1;
  if (vof_) {
    if (in.getString() != "vof-v1") throw CheckpointError("fluid checkpoint: no phase fractions (fluid.vof)");
    for (Field& a : alpha_) readInto(a);
    phaseOutflow_ = in.getVector<double>();
    if (phaseOutflow_.size() != phases_.size()) throw CheckpointError("fluid checkpoint: phase count differs");
    const vof::Sides sides = vofSides();
    std::vector<Field*> fields;
    for (Field& a : alpha_) fields.push_back(&a);
    vofGhostFill(sides)(fields);
    updateMixture();
  }
}

}  // namespace gf::fluid
