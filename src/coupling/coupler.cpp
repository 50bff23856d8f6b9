#include "coupling/coupler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <omp.h>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

#include <spdlog/spdlog.h>

#include "coupling/deposit.hpp"
#include "coupling/drag/dispatch.hpp"
#include "coupling/drag/filtered.hpp"
#include "coupling/drag/yin_sundaresan.hpp"
#include "coupling/loops.hpp"
#include "coupling/forces.hpp"
#include "coupling/smoothing.hpp"
#include "parallel/exchange.hpp"
#include "parallel/halo.hpp"

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
  c.fluxVelocity = s.choice({"velocity_reconstruction", "-",
                             "fluid velocity of a cell as the particles see it: 'flux' = mean superficial flux of its "
                             "two faces / eps of the cell (per axis, from the fluid's face-mean cell velocity and the "
                             "eps of the cell and its neighbours; same as 'face_mean' where eps is uniform), "
                             "'face_mean' = the fluid's cell velocity (mean of the face velocities) as given"},
                            {"flux", "face_mean"}, "face_mean") == "flux";
  c.exchange = s.choice({"exchange", "-", "drag given to the fluid explicitly (force density) or semi-implicitly "
                                          "(coefficient K and mean particle velocity)"},
                        {"explicit", "implicit"}, "implicit") == "explicit"
                   ? ExchangeScheme::Explicit
                   : ExchangeScheme::SemiImplicit;
  const Key smoothingKey{"smoothing_length", "m",
                         "smoothing length l of the implicit diffusion of eps (D = l^2/dt); 0 = off; auto = the "
                         "seed 003 law: l/d32 of Tab. 4.15 at the coarse-graining factor (8.06 up to 25, 10.3 at 33, "
                         "17.0 at 50, linear in between and beyond), scaled by (1e-3 / <phi_p>)^(1/3) (eq. 4.10), "
                         "<phi_p> and the Sauter mean parcel diameter d32 of the particles at the first coupling "
                         "step; the length chosen is printed",
                         Range::nonNegative()};
  if (!s.documenting() && s.isWord("smoothing_length", "auto")) {
    s.choice(smoothingKey, {"auto"});
    c.smoothingAuto = true;
  } else {
    c.smoothingLength = s.real(smoothingKey, 0.0);
  }
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
  c.substepFluidFields =
      s.choice({"substep_fluid_fields", "-",
                "fluid forces over the DEM substeps of a coupling step (time.coupling_interval > 1): 'held' = "
                "computed once from the new fluid state and the particles at the start of the interval, held "
                "(seed 000 Base Case, CFDEM); 'interpolated' = recomputed before every substep from the current "
                "particles, with fluid velocity and pressure gradient linear in time between the previous and the "
                "new fluid step (seed 000 Case II); the fluid receives the substeps' mean exchange"},
               {"held", "interpolated"}, "held") == "interpolated"
          ? SubstepFluidFields::Interpolated
          : SubstepFluidFields::Held;
  if (c.substepFluidFields == SubstepFluidFields::Interpolated && c.interpolation == InterpolationMode::Stencil)
    s.fail("substep_fluid_fields", "interpolated with interpolation: stencil",
           "interpolation 'cell' or 'trilinear' with interpolated substep fields (the stencils are those of the "
           "particle positions at the start of the coupling step)");
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

constexpr std::size_t kNewParticle = static_cast<std::size_t>(-1);

/// For each id of `current`, its index in `previous`, or kNewParticle (a checkpoint's coupling state
/// is matched to the restored particles by id; ids are unique).
std::vector<std::size_t> previousIndexById(const std::vector<std::int64_t>& previous,
                                           const std::vector<std::int64_t>& current) {
  std::unordered_map<std::int64_t, std::size_t> oldIndex;
  oldIndex.reserve(previous.size());
  for (std::size_t q = 0; q < previous.size(); ++q) oldIndex.emplace(previous[q], q);
  std::vector<std::size_t> from(current.size(), kNewParticle);
  for (std::size_t p = 0; p < current.size(); ++p) {
    const auto it = oldIndex.find(current[p]);
    if (it != oldIndex.end()) from[p] = it->second;
  }
  return from;
}

}  // namespace

Coupler::Coupler(Params& root, const CartesianGrid& grid, const std::array<bool, 3>& periodic, const Vec3& gravity,
                 ExchangeModel model, const parallel::Decomposition* decomposition)
    : topology_(decomposition && decomposition->distributed() ? GridTopology(grid, *decomposition)
                                                              : GridTopology(grid, periodic)),
      gravity_(gravity) {
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
  settings_.dragCorrection =
      s.choice({"drag_correction", "-",
                "correction on top of the drag law: none, or filtered = the filtered drag of Radl & Sundaresan "
                "(2014) for grids too coarse to resolve clusters, with the parcel correction c_corr(alpha) at the "
                "coarse-graining factor (seed 003 eqs. 3.29-3.36; filter size = cube root of the cell volume; "
                "drag_law beetstra or beetstra_polydisperse only, the law it was fitted to)"},
               {"none", "filtered"}, "none") == "filtered"
          ? DragCorrection::Filtered
          : DragCorrection::None;
  {
    Params f = s.section({"filtered_drag", "", "parameters of drag_correction: filtered"});
    FilteredDragSettings& fd = settings_.filteredDrag;
    fd.primaryDiameter = f.real({"primary_diameter", "m",
                                 "primary particle diameter d_prim of Fr_prim and L_char (seed 003 eqs. 3.30-3.31); "
                                 "0 = the Sauter mean primary diameter of the particles at the first coupling step",
                                 Range::nonNegative()},
                                0.0);
    fd.parcelA = f.real({"parcel_a", "-", "a of the parcel correction c_corr = a + (1 - a) exp(-k (alpha - 1)) "
                                          "(seed 003 eq. 3.36)", Range::between(0.0, 1.0)},
                        0.0);
    fd.parcelK = f.real({"parcel_k", "-", "k of the parcel correction c_corr (seed 003 eq. 3.36)", Range::nonNegative()},
                        0.05);
  }
  if (!s.documenting() && settings_.dragCorrection == DragCorrection::Filtered &&
      settings_.dragLaw != "beetstra" && settings_.dragLaw != "beetstra_polydisperse")
    s.fail("drag_correction", "filtered with drag_law: " + settings_.dragLaw,
           "drag_law: beetstra or beetstra_polydisperse with drag_correction: filtered (the filtered correction of "
           "Radl & Sundaresan 2014 was fitted to Beetstra drag, seed 003 sec. 3.1.4), or drag_correction: none");
  solidFraction_ = Field(grid);
  for (int a = 0; a < 3; ++a) {
    vorticity_[a] = Field(grid);
    divTau_[a] = Field(grid);
  }
  // the cells stencils reach: interior rows (deposits zero and sum only these); on a decomposed
  // grid also the ghost rows, whose sums go to the neighbours (sumDepositGhosts)
  const auto& n = grid.cells;
  const int g = grid.ghosts;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j) interiorRuns_.push_back({topology_.flat(0, j, k), static_cast<std::size_t>(n[0])});
  if (!topology_.distributed()) {
    deposit_.runs = interiorRuns_;
  } else {
    for (int k = -g; k < n[2] + g; ++k)
      for (int j = -g; j < n[1] + g; ++j)
        deposit_.runs.push_back({topology_.flat(-g, j, k), static_cast<std::size_t>(n[0] + 2 * g)});
  }
  // ghost cell -> its source (periodic: wrapped image; wall: nearest interior cell, i.e. zero
  // normal gradient), listed once so that fillGhosts is one gather; a ghost cell beyond a side
  // shared with a neighbour rank is the neighbour's (parallel::fillGhosts)
  const GridTopology& t = topology_;
  auto source = [&](int i, int a) { return t.periodic[a] ? t.mapIndex(i, a) : std::clamp(i, 0, n[a] - 1); };
  auto beyondCut = [&](int i, int a) { return (i < 0 && t.shared[a][0]) || (i >= n[a] && t.shared[a][1]); };
  for (int k = -g; k < n[2] + g; ++k)
    for (int j = -g; j < n[1] + g; ++j)
      for (int i = -g; i < n[0] + g; ++i) {
        if (grid.isInterior(i, j, k) || beyondCut(i, 0) || beyondCut(j, 1) || beyondCut(k, 2)) continue;
        ghostTarget_.push_back(solidFraction_.index(i, j, k));
        ghostSource_.push_back(solidFraction_.index(source(i, 0), source(j, 1), source(k, 2)));
      }
}

void Coupler::fillGhosts(Field& f) const {
  // (this rank's own sides first: the neighbours' corner and edge ghosts come from theirs)
  double* d = f.data().data();
  for (std::size_t q = 0; q < ghostTarget_.size(); ++q) d[ghostTarget_[q]] = d[ghostSource_[q]];
  if (topology_.distributed()) parallel::fillGhosts(f, *topology_.decomposition);
}

void Coupler::sumDepositGhosts(int channels) {
  if (!topology_.distributed()) return;
  // each channel as a field (every cell: the deposit's runs cover the ghost rows too), the
  // neighbours' ghost deposits added to this rank's cells, then back into the interleaved sums
  const std::size_t cells = solidFraction_.data().size();
  const auto c = static_cast<std::size_t>(channels);
  if (channelFields_.size() < c) channelFields_.resize(c);
  std::vector<Field*> fields;
  for (std::size_t ch = 0; ch < c; ++ch) {
    Field& f = channelFields_[ch];
    if (f.data().size() != cells) f = Field(topology_.grid);
    fields.push_back(&f);
  }
  double* merged = deposit_.merged.data();
  forEachIndex(static_cast<std::int64_t>(cells), 4 * channels, [&](std::int64_t q) {
    for (std::size_t ch = 0; ch < c; ++ch) fields[ch]->data()[static_cast<std::size_t>(q)] = merged[q * channels + ch];
  });
  parallel::sumGhosts(fields, *topology_.decomposition);
  forEachIndex(static_cast<std::int64_t>(cells), 4 * channels, [&](std::int64_t q) {
    for (std::size_t ch = 0; ch < c; ++ch) merged[q * channels + ch] = fields[ch]->data()[static_cast<std::size_t>(q)];
  });
}

void Coupler::computeVoidFraction(const dem::ParticleSet& particles, CouplingFields& fields) {
  fields.voidFractionOld.data() = fields.voidFraction.data();
  // the stencils are built piece by piece inside the deposit, each piece just before it is
  // deposited (read back from cache); the particle volume is summed there too (per thread block
  // in particle order, as sumsOverIndices would)
  const bool inPieces = scheme_->beginStencils(particles, topology_, stencils_);
  stencilsReady_ = true;
  const std::size_t cells = solidFraction_.data().size();
  const double* radius = particles.radius.data();
  auto particleVolume = [radius](std::size_t p) { return force::sphereVolume(2.0 * radius[p]); };
  const std::uint8_t* ghost = ghostFlags(particles);  // (ghost particles: deposit and count nothing)
  volumeSums_.assign(static_cast<std::size_t>(omp_get_max_threads()), 0.0);
  // In the order of Simulation::advance (forces, DEM steps, void fraction, fluid sources) the
  // exchange of the pending forces goes with the same stencils: one deposit pass for the volume
  // and the exchange channels (each channel summed exactly as by its own deposit), kept for
  // fillFluidSources.
  exchangeDeposited_ = false;
  const bool fuse = exchangePending_ && carriesExchange(particles);
  if (fuse) followLayout(particles);
  // Nothing reads the stencils after a fused deposit unless the forces are interpolated with them:
  // then each piece is built into a buffer of its thread that holds one piece and stays in cache
  // (the bubbling bed's 24,750 stencils, 3.3 MB, were written out to memory every coupling step).
  const bool transient = inPieces && fuse && settings_.interpolation != InterpolationMode::Stencil;
  if (transient) {
    pieceStencils_.resize(volumeSums_.size());
    for (ParticleStencils& piece : pieceStencils_)
      if (piece.capacity != stencils_.capacity || piece.size() != static_cast<std::size_t>(kDepositPiece))
        piece.resize(static_cast<std::size_t>(kDepositPiece), stencils_.capacity);
  }
  stencilsKept_ = !transient;
  auto buildAndSum = [&](int thread, std::size_t begin, std::size_t end) {
    double sum = volumeSums_[thread];
    for (std::size_t p = begin; p < end; ++p) sum += ghost && ghost[p] ? 0.0 : particleVolume(p);
    volumeSums_[thread] = sum;
    if (transient) {
      ParticleStencils& piece = pieceStencils_[static_cast<std::size_t>(thread)];
      scheme_->buildStencilRange(particles, topology_, piece, begin, end, 0);
      return StencilPiece::of(piece, 0);
    }
    scheme_->buildStencilRange(particles, topology_, stencils_, begin, end, begin);
    return StencilPiece::of(stencils_, begin);
  };
  const double* volume = nullptr;
  std::size_t volumeStride = 1;
  if (fuse) {
    withExchangeLayout([&](auto layout) {
      constexpr ExchangeLayout L = decltype(layout)::value;
      const ExchangeData data = exchangeData(particles);
      volume = depositChannels<1 + channelsOf(L)>(
                   stencils_, cells, deposit_,
                   [&particleVolume, data, ghost](std::size_t p, auto& v) {
                     if (ghost && ghost[p]) return std::fill(std::begin(v), std::end(v), 0.0);
                     v[0] = particleVolume(p);
                     exchangeValues<L>(data, p, v + 1);
                   },
                   buildAndSum)
                   .data();
      volumeStride = 1 + channelsOf(L);
    });
  } else {
    volume = depositChannels<1>(
                 stencils_, cells, deposit_,
                 [&](std::size_t p, double (&v)[1]) { v[0] = ghost && ghost[p] ? 0.0 : particleVolume(p); },
                 buildAndSum)
                 .data();
  }
  sumDepositGhosts(static_cast<int>(volumeStride));
  exchangeDeposited_ = fuse;
  particleVolume_ = 0.0;
  for (double sum : volumeSums_) particleVolume_ += sum;
  // interior cells by rows of flat indices (deposit_.runs), rows in parallel (disjoint writes);
  // the volume sums per row, added in row order: the same bits on any thread count
  double* solid = solidFraction_.data().data();
  double* eps = fields.voidFraction.data().data();
  const double cellVolume = topology_.grid.cellVolume();
  const double minEps = settings_.minVoidFraction;
  if (settings_.smoothingAuto && !(settings_.smoothingLength > 0.0) &&
      (topology_.distributed() ? parallel::anyOverRanks(particles.size() > 0) : particles.size() > 0))
    chooseSmoothingLength(particles);
  const bool smoothing = settings_.smoothingLength > 0.0;
  auto toVoidFraction = [&](std::size_t q) {  // returns the volume clipped by min_void_fraction
    const double e = 1.0 - solid[q];
    eps[q] = std::max(e, minEps);
    return e < minEps ? (minEps - e) * cellVolume : 0.0;
  };
  const auto* runs = interiorRuns_.data();
  const auto runCount = static_cast<std::int64_t>(interiorRuns_.size());
  const std::int64_t cellsPerRun = topology_.grid.cells[0];
  runSums_.resize(interiorRuns_.size());
  forEachIndex(runCount, 4 * cellsPerRun, [&](std::int64_t r) {
    double deposited = 0.0, clipped = 0.0;
    for (std::size_t q = runs[r][0]; q < runs[r][0] + runs[r][1]; ++q) {
      deposited += volume[q * volumeStride];
      solid[q] = volume[q * volumeStride] / cellVolume;  // solid fraction
      if (!smoothing) clipped += toVoidFraction(q);
    }
    runSums_[r] = {deposited, clipped, 0.0};
  });
  if (smoothing) {
    smoothField(topology_, settings_.smoothingLength, solidFraction_);
    forEachIndex(runCount, 4 * cellsPerRun, [&](std::int64_t r) {
      double clipped = 0.0;
      for (std::size_t q = runs[r][0]; q < runs[r][0] + runs[r][1]; ++q) clipped += toVoidFraction(q);
      runSums_[r][1] = clipped;
    });
  }
  depositedVolume_ = clippedVolume_ = 0.0;
  for (const auto& sums : runSums_) {
    depositedVolume_ += sums[0];
    clippedVolume_ += sums[1];
  }
  if (topology_.distributed()) {
    const std::vector<double> all = parallel::sumOverRanks(std::vector<double>{particleVolume_, depositedVolume_, clippedVolume_});
    particleVolume_ = all[0], depositedVolume_ = all[1], clippedVolume_ = all[2];
  }
  fillGhosts(fields.voidFraction);
}

void Coupler::packSamples(const FluidView& fluid, const CouplingFields& fields, bool planesPerThread) {
  // channels: u_f (3), eps (1), then grad p, div tau, vorticity (3 each) where a force needs them
  const ForceSwitches& w = settings_.forces;
  const Field* src[13];
  int k = 0;
  for (int a = 0; a < 3; ++a) src[k++] = fluid.velocity[a];
  src[k++] = &fields.voidFraction;
  gradPChannel_ = divTauChannel_ = vorticityChannel_ = -1;
  if (w.pressureGradient) {
    gradPChannel_ = k;
    for (int a = 0; a < 3; ++a) src[k++] = fluid.pressureGradient[a];
  }
  if (w.viscousStress) {
    divTauChannel_ = k;
    for (int a = 0; a < 3; ++a)
      src[k++] = fluid.viscousStressDivergence[a] ? fluid.viscousStressDivergence[a] : &divTau_[a];
  }
  if (w.saffmanMeiLift || w.magnusLift || w.fluidTorque) {
    vorticityChannel_ = k;
    for (int a = 0; a < 3; ++a) src[k++] = &vorticity_[a];
  }
  sampleChannels_ = k;
  for (int ch = 0; ch < k; ++ch) sampleSource_[ch] = src[ch]->data().data();
  const std::size_t cells = solidFraction_.data().size();
  if (planesPerThread) {
    // each thread packs the planes its own particles read into its buffer (forcePass)
    threadSamples_.resize(static_cast<std::size_t>(omp_get_max_threads()));
    for (auto& buffer : threadSamples_) buffer.resize(cells * k);
    return;
  }
  samples_.resize(cells * k);
  if (topology_.distributed()) {
    // every cell, ghosts included: particles near a cut sample the neighbours' cells
    forEachIndex(static_cast<std::int64_t>(cells), 4 * k, [&](std::int64_t q) {
      for (int ch = 0; ch < k; ++ch) samples_[static_cast<std::size_t>(q) * k + ch] = sampleSource_[ch][q];
    });
    if (settings_.fluxVelocity) scaleToFluxVelocity(fields.voidFraction);
    return;
  }
  // pieces of rows in parallel (disjoint writes); a piece per call, not a row (the 2 x 30 x 90
  // bed's rows hold 2 cells: a call per row cost as much as the copying)
  const auto& n = topology_.grid.cells;
  const std::int64_t rows = static_cast<std::int64_t>(n[2]) * n[1];
  constexpr std::int64_t kRowsPerPiece = 32;
  forEachIndex((rows + kRowsPerPiece - 1) / kRowsPerPiece, kRowsPerPiece * n[0] * k, [&](std::int64_t piece) {
    packSampleRows(samples_.data(), piece * kRowsPerPiece, std::min(rows, (piece + 1) * kRowsPerPiece));
  });
  if (settings_.fluxVelocity) scaleToFluxVelocity(fields.voidFraction);
}

void Coupler::packSampleRows(double* out, std::int64_t rowBegin, std::int64_t rowEnd) const {
  // interior cells only: every stencil and interpolation maps its cells into the interior; the
  // standard channel count fixed at compile time. Row kj = j + n_y k.
  const auto& n = topology_.grid.cells;
  const double* const* in = sampleSource_;
  auto pack = [&]<int Channels>(std::integral_constant<int, Channels>) {
    const int kc = Channels > 0 ? Channels : sampleChannels_;
    int j = static_cast<int>(rowBegin % n[1]), k = static_cast<int>(rowBegin / n[1]);
    for (std::int64_t kj = rowBegin; kj < rowEnd; ++kj) {
      const std::size_t row = topology_.flat(0, j, k);
      for (std::size_t q = row; q < row + static_cast<std::size_t>(n[0]); ++q)
        for (int ch = 0; ch < kc; ++ch) out[q * kc + ch] = in[ch][q];
      if (++j == n[1]) j = 0, ++k;
    }
  };
  if (sampleChannels_ == kStandardChannels) pack(std::integral_constant<int, kStandardChannels>{});
  else pack(std::integral_constant<int, 0>{});
}

std::pair<int, int> Coupler::planesSampledBy(const dem::ParticleSet& particles, std::int64_t begin,
                                             std::int64_t end) const {
  // Trilinear sampling of a point in cell plane c reads planes c - 1 ... c + 1 (its lower cell
  // is c - 1 or c; clamped to the interior in wall directions).
  const int nz = topology_.grid.cells[2];
  const double origin = topology_.grid.origin.z, inverse = topology_.inverseSpacing.z;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::int64_t p = begin; p < end; ++p) {
    const double z = particles.position[static_cast<std::size_t>(p)].z;
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  if (!(lo <= hi)) return {0, nz};  // no particles (or only NaN positions): all planes
  // (clamped as a double: a particle far outside the grid stays within int)
  auto plane = [&](double z) { return static_cast<int>(std::clamp(std::floor((z - origin) * inverse), 0.0, nz - 1.0)); };
  return {std::max(plane(lo) - 1, 0), std::min(plane(hi) + 2, nz)};
}

void Coupler::scaleToFluxVelocity(const Field& eps) {
  // The fluid's cell velocity is the mean of its face velocities u_c = (u_- + u_+)/2, the faces
  // carrying eps_f = (eps_c + eps_nb)/2 in the fluid's momentum and continuity equations. With
  // the same superficial flux Q through both faces (continuity along the axis), u_+- = Q/eps_+-,
  // and the cell's interstitial velocity Q/eps_c is
  //   u_c * R,  R = (1/eps_c) / ((1/eps_- + 1/eps_+)/2) = 2 eps_- eps_+ / (eps_c (eps_- + eps_+)),
  // R = 1 where eps is uniform. Where eps jumps (bottom and top of a bed) the face mean mixes the
  // velocities of the dense and the free side: 19 % low in a bed cell at eps 0.45 next to a
  // particle-free cell, whose particles would feel too little drag (they rest on a distributor
  // instead). The exchange keeps the fluid's own u_c as reference (depositExchange), so the drag
  // given back to the fluid still equals the particles' drag.
  // (decomposed grid: also the first ghost layer across a cut, which particles near it sample)
  const auto& n = topology_.grid.cells;
  int first[3], last[3];
  for (int a = 0; a < 3; ++a) {
    first[a] = topology_.shared[a][0] ? -1 : 0;
    last[a] = topology_.shared[a][1] ? n[a] + 1 : n[a];
  }
  const int k = sampleChannels_;
  const double* e = eps.data().data();
  for (int a = 0; a < 3; ++a) {
    const std::ptrdiff_t st = eps.stride(a);
    for (int kk = first[2]; kk < last[2]; ++kk)
      for (int j = first[1]; j < last[1]; ++j)
        for (int i = first[0]; i < last[0]; ++i) {
          const std::size_t q = eps.index(i, j, kk);
          const double ec = e[q], em = 0.5 * (ec + e[q - st]), ep = 0.5 * (ec + e[q + st]);
          samples_[q * k + a] *= 2.0 * em * ep / (ec * (em + ep));
        }
  }
}

Coupler::Columns Coupler::columnsOf(dem::ParticleSet& particles) const {
  // (all added first: adding a column moves the column objects, not their values)
  const std::size_t beta = particles.addColumn(kBetaColumn, 0.0);
  const std::size_t slip = particles.addColumn(kSlipColumn, Vec3{});
  const std::size_t other = particles.addColumn(kOtherForceColumn, Vec3{});
  // NaN: no history, read as "its current slip", i.e. no virtual-mass force in a particle's first step
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t previous = settings_.forces.virtualMass
                                   ? particles.addColumn(kPreviousSlipColumn, Vec3{nan, nan, nan})
                                   : dem::ParticleSet::kNoColumn;
  return {particles.doubleColumns[beta].values.data(), particles.vec3Columns[slip].values.data(),
          particles.vec3Columns[other].values.data(),
          previous == dem::ParticleSet::kNoColumn ? nullptr : particles.vec3Columns[previous].values.data()};
}

bool Coupler::carriesExchange(const dem::ParticleSet& particles) {
  return particles.findDoubleColumn(kBetaColumn) != dem::ParticleSet::kNoColumn &&
         particles.findVec3Column(kSlipColumn) != dem::ParticleSet::kNoColumn &&
         particles.findVec3Column(kOtherForceColumn) != dem::ParticleSet::kNoColumn;
}

Coupler::ExchangeData Coupler::exchangeData(const dem::ParticleSet& particles) {
  if (!carriesExchange(particles))
    throw std::logic_error("coupling: the particle set does not carry the exchange of computeParticleForces");
  return {particles.doubleColumns[particles.findDoubleColumn(kBetaColumn)].values.data(),
          particles.vec3Columns[particles.findVec3Column(kSlipColumn)].values.data(),
          particles.vec3Columns[particles.findVec3Column(kOtherForceColumn)].values.data()};
}

const std::vector<double>& Coupler::dragCoefficients() const {
  static const std::vector<double> none;
  if (!exchangeSet_ || !carriesExchange(*exchangeSet_)) return none;
  return exchangeSet_->doubleColumns[exchangeSet_->findDoubleColumn(kBetaColumn)].values;
}

const std::vector<Vec3>& Coupler::slipVelocities() const {
  static const std::vector<Vec3> none;
  if (!exchangeSet_ || !carriesExchange(*exchangeSet_)) return none;
  return exchangeSet_->vec3Columns[exchangeSet_->findVec3Column(kSlipColumn)].values;
}

void Coupler::followLayout(const dem::ParticleSet& particles) {
  exchangeSet_ = &particles;
  if (particles.layoutStamp == forceStamp_) return;
  // The DEM reordered (or inserted / removed) particles since computeParticleForces: their columns
  // moved with them (new particles exchange nothing).
  particleForceSumsValid_ = false;  // particles gone or new: sum the moved forces
  if (settings_.forces.virtualMass) previousSlipFromSlip_ = true;
  forceStamp_ = particles.layoutStamp;
}

template <InterpolationMode Mode, bool StandardChannels, class Law>
void Coupler::forcePass(const FluidView& fluid, const Law& law, dem::ParticleSet& particles, const Columns& columns) {
  // Per particle: interpolate every fluid field at once (interleaved cell buffer), slip, Re, drag
  // law (inlined), forces, and the per-particle exchange data for fillFluidSources.
  // StandardChannels: the channel layout of the default forces (u, eps, grad p, div tau; no
  // vorticity) fixed at compile time.
  // Blocks of particles, each in three short passes (sampling; slip and Re; law and forces): the
  // long latency chains of one particle (sqrt, divisions, the law) then overlap with those of
  // the next ones instead of waiting behind a long loop body. Same operations per particle as
  // one pass (bit-identical).
  const ForceSwitches& w = settings_.forces;
  const double k3 = settings_.coarseGraining.fluidForceScale();
  const double dPrimFactor = 1.0 / settings_.coarseGraining.factor;
  // coarse graining per insertion (coarse_graining.hpp): 1/k and k^3 by the particle's material
  const double* const inverseK = settings_.coarseGraining.uniform() ? nullptr : settings_.coarseGraining.inverseByMaterial.data();
  const double* const k3ByMaterial = settings_.coarseGraining.particlesPerParcelByMaterial.data();
  const std::int32_t* const material = particles.type.data();
  const bool modelB = settings_.model == ExchangeModel::B;
  const double rho = fluid.density, mu = fluid.viscosity;
  // (several fluids: the density and viscosity of each particle's cell, fluid.vof)
  const Field* const rhoField = fluid.mixtureDensity;
  const Field* const muField = fluid.mixtureViscosity;
  const bool mixture = rhoField && muField;
  const double epsFloor = std::max(settings_.minVoidFraction, 1e-6);
  [[maybe_unused]] const int channels = StandardChannels ? kStandardChannels : sampleChannels_;
  const int cP = StandardChannels ? 4 : gradPChannel_, cT = StandardChannels ? 7 : divTauChannel_,
            cW = StandardChannels ? -1 : vorticityChannel_;
  const bool planesPerThread = planesPerThread_;
  // The drag-only exchange reads no other exchanged force: its array stays +0 (sized with zeros,
  // moved as zeros), the value this pass would store; not writing it saves a store stream of
  // 24 B per particle and coupling step.
  const bool keepOther = exchangeLayout() != ExchangeLayout::DragOnly;
  // Fluid torque on the particles: written only when switched on; otherwise the torques stay zero
  // (cleared once, computeParticleForces, on the same switch) and the DEM force loop does not read them.
  const bool torqueOut = w.fluidTorque;
  const Vec3 buoyancy = w.buoyancy ? force::buoyancy(rho, 1.0, gravity_) : Vec3{};  // per volume
  const TrilinearSampler sampler(topology_);
  const std::uint8_t* const ghost = ghostFlags(particles);  // (ghosts count in no sum)
  constexpr int kBlock = 32;
  const auto n = static_cast<std::int64_t>(particles.size());
  // the particle's columns (ParticleSet::addColumn), as plain pointers copied into the block loop
  double* const betaOut = columns.beta;
  Vec3* const slipOut = columns.slip;
  Vec3* const otherOut = columns.other;
  const Vec3* const previousSlipIn = columns.previousSlip;
  auto forceBlock = [&, rho, mu, mixture, epsFloor, dPrimFactor, k3, inverseK, k3ByMaterial, material, betaOut, slipOut, otherOut,
                     previousSlipIn](
                        const double* samples, std::size_t begin, int count, std::array<double, 4>& sums) {
    double sum[4] = {sums[0], sums[1], sums[2], sums[3]};  // in registers, not through the reference
    // 1 <= count <= kBlock (the one caller below passes min(kBlock, end - p) with p < end). Said
    // to the compiler: without it GCC 12 takes count <= 0 as possible, in which case the block
    // arrays below (where, eps, re, slipSquared, exchangedSquared) would be passed on unwritten, and
    // warns "may be used uninitialized" at every helper call (squareRoots, gidaspowBlock, ...).
    if (count < 1 || count > kBlock) __builtin_unreachable();
    double s[kBlock][13];
    if constexpr (Mode == InterpolationMode::Trilinear) {
      // locate the whole block first, then sum (the chains of several particles overlap)
      TrilinearSampler::Location where[kBlock];
      for (int q = 0; q < count; ++q) sampler.locate(particles.position[begin + q], where[q]);
      if constexpr (StandardChannels) {
        static_assert(kStandardChannels == kTrilinearBlockChannels);
        sampleTrilinearBlock(where, count, samples, s);
      } else {
        for (int q = 0; q < count; ++q) sampler.sampleAt<0>(where[q], samples, channels, s[q]);
      }
    } else {
      for (int q = 0; q < count; ++q) {
        const std::size_t p = begin + q;
        SampleWeights sw;
        sampleWeights<Mode>(topology_, stencils_, p, particles.position[p], sw);
        sampleInterleaved(sw, samples, channels, s[q]);
      }
    }
    // Re = rho |slip| d_prim / mu, the square roots and divisions two particles at a time (the
    // same operations per particle as rho * norm(slip) * dPrim / mu)
    double eps[kBlock], re[kBlock], slipSquared[kBlock], slipNorm[kBlock], dPrimOf[kBlock];
    for (int q = 0; q < count; ++q) {
      const std::size_t p = begin + q;
      const Vec3 uf{s[q][0], s[q][1], s[q][2]};
      eps[q] = std::clamp(s[q][3], epsFloor, 1.0);
      const Vec3 slip = uf - particles.velocity[p];
      dPrimOf[q] = 2.0 * particles.radius[p] * (inverseK ? inverseK[material[p]] : dPrimFactor);
      slipSquared[q] = dot(slip, slip);
      slipOut[p] = slip;
    }
    squareRoots(slipSquared, slipNorm, count);
    double rhoOf[kBlock], muOf[kBlock];  // (mixture: the particle's cell's; filled only then)
    if (mixture) {
      const CartesianGrid& g = topology_.grid;
      for (int q = 0; q < count; ++q) {
        const Vec3& x = particles.position[begin + q];
        int c[3];
        for (int a = 0; a < 3; ++a)
          c[a] = std::clamp(static_cast<int>(std::floor((x[a] - g.origin[a]) * topology_.inverseSpacing[a])), 0,
                            g.cells[a] - 1);
        rhoOf[q] = (*rhoField)(c[0], c[1], c[2]);
        muOf[q] = (*muField)(c[0], c[1], c[2]);
      }
    }
    for (int q = 0; q < count; ++q)
      re[q] = (mixture ? rhoOf[q] : rho) * slipNorm[q] * dPrimOf[q] / (mixture ? muOf[q] : mu);
    double correction[kBlock];  // f(Re, eps) of the law
    if (w.drag) {
      if constexpr (std::is_same_v<Law, ParticleCorrection>) law.block(begin, re, eps, correction, count);
      else correctionsOf(law, re, eps, correction, count);
    }
    double exchangedSquared[kBlock];
    for (int q = 0; q < count; ++q) {
      const std::size_t p = begin + q;
      const Vec3 slip = slipOut[p];
      const double d = 2.0 * particles.radius[p];
      const double dPrim = dPrimOf[q];
      const double k3p = inverseK ? k3ByMaterial[material[p]] : k3;
      const double volume = force::sphereVolume(d);  // parcel volume = k^3 primary volumes
      const double rhoP = mixture ? rhoOf[q] : rho, muP = mixture ? muOf[q] : mu;
      const double beta = w.drag ? k3p * particleDragCoefficient(muP, dPrim, correction[q]) : 0.0;
      const Vec3 fDrag = force::drag(beta, slip);
      // pressure and viscous forces: given back to the fluid in model B, on the particle only in
      // model A (summed first, then assigned: no reference chosen at run time, which kept both
      // vectors in memory)
      Vec3 undisturbedFlow{};
      if (cP >= 0) undisturbedFlow += force::pressureGradient(volume, {s[q][cP], s[q][cP + 1], s[q][cP + 2]});
      if (cT >= 0) undisturbedFlow += force::viscousStress(volume, {s[q][cT], s[q][cT + 1], s[q][cT + 2]});
      Vec3 exchangedOther = modelB ? undisturbedFlow : Vec3{};
      Vec3 particleOnly = modelB ? Vec3{} : undisturbedFlow;
      if (w.buoyancy) particleOnly += volume * buoyancy;
      if (w.virtualMass) {
        const Vec3 previous = std::isnan(previousSlipIn[p].x) ? slip : previousSlipIn[p];
        exchangedOther += force::virtualMass(w.virtualMassCoefficient, rhoP, volume, slip, previous, fluid.timeStep);
      }
      Vec3 torque{};
      if (cW >= 0) {
        const Vec3 vorticity{s[q][cW], s[q][cW + 1], s[q][cW + 2]};
        const Vec3 relOmega = force::relativeRotation(particles.angularVelocity[p], vorticity);
        if (w.saffmanMeiLift) exchangedOther += k3p * force::saffmanMeiLift(rhoP, muP, dPrim, slip, vorticity);
        if (w.magnusLift) exchangedOther += k3p * force::magnusLift(rhoP, dPrim, relOmega, slip);
        if (w.fluidTorque) torque = k3p * force::rotationalTorque(muP, dPrim, relOmega);
      }
      betaOut[p] = beta;
      if (keepOther) otherOut[p] = exchangedOther;
      particles.externalForce[p] = fDrag + exchangedOther + particleOnly;
      if (torqueOut) particles.externalTorque[p] = torque;
      // (a ghost's forces are its owner's to count: weight 0, else 1, which leaves every bit)
      const double own = ghost && ghost[p] ? 0.0 : 1.0;
      const Vec3 exchanged = own * (fDrag + exchangedOther);
      sum[0] += exchanged.x, sum[1] += exchanged.y, sum[2] += exchanged.z;
      exchangedSquared[q] = dot(exchanged, exchanged);
    }
    double exchangedNorm[kBlock];  // |exchanged force|, added in particle order
    squareRoots(exchangedSquared, exchangedNorm, count);
    for (int q = 0; q < count; ++q) sum[3] += exchangedNorm[q];
    for (int c = 0; c < 4; ++c) sums[c] = sum[c];
  };
  // the particle side of the momentum balance (updateMomentumBalance) summed on the way, per
  // thread block in particle order as sumsOverIndices would
  particleForceSums_ = sumsOverRanges<4>(n, [&](std::int64_t begin, std::int64_t end, std::array<double, 4>& sum) {
    const double* samples = samples_.data();
    if (planesPerThread) {
      // The cell planes this thread's particles read, packed by this thread: no cache line of the
      // buffer comes from the other core (the particles follow the DEM's split, the rows of a
      // shared pack an equal split of the planes; the same values, bit for bit).
      std::vector<double>& own = threadSamples_[static_cast<std::size_t>(omp_get_thread_num())];  // (0 outside a region)
      const auto [k0, k1] = planesSampledBy(particles, begin, end);
      const std::int64_t ny = topology_.grid.cells[1];
      packSampleRows(own.data(), ny * k0, ny * k1);
      samples = own.data();
    }
    for (std::int64_t p = begin; p < end; p += kBlock)
      forceBlock(samples, static_cast<std::size_t>(p), static_cast<int>(std::min<std::int64_t>(kBlock, end - p)), sum);
  }, &particleBlocks_);
  particleForceSumsValid_ = true;
}

void Coupler::computeParticleForces(const FluidView& fluid, const CouplingFields& fields,
                                    dem::ParticleSet& particles) {
  const std::size_t n = particles.size();
  // (substeps after the first: cell and trilinear sampling read positions, not the stencils)
  const bool stencilsNeeded = !averaging_ || averagedSubsteps_ == 0 || settings_.interpolation == InterpolationMode::Stencil;
  if (!stencilsReady_ || (stencilsNeeded && stencils_.size() != n))
    throw std::logic_error("coupling: computeVoidFraction must run before computeParticleForces (particle count changed)");
  lastFluid_ = fluid;
  particles.enableExternalForces();
  const ForceSwitches& w = settings_.forces;
  if (w.fluidTorque) particles.hasExternalTorques = true;  // (forcePass writes them)
  else particles.clearExternalTorques();
  for (int a = 0; a < 3; ++a) {
    if (!fluid.velocity[a]) throw std::invalid_argument("coupling: FluidView::velocity is not set");
    if (w.pressureGradient && !fluid.pressureGradient[a])
      throw std::invalid_argument("coupling: FluidView::pressureGradient is not set (needed by forces.pressure_gradient)");
  }
  if (w.virtualMass && !(fluid.timeStep > 0.0))
    throw std::invalid_argument("coupling: virtual mass force needs FluidView::timeStep > 0");
  if (w.saffmanMeiLift || w.magnusLift || w.fluidTorque) {
    computeVorticity(topology_, fluid.velocity, vorticity_);  // interior cells (all packSamples reads)
    if (topology_.distributed()) parallel::fillGhosts({&vorticity_[0], &vorticity_[1], &vorticity_[2]}, *topology_.decomposition);
  }
  if (w.viscousStress && !fluid.viscousStressDivergence[0]) {
    computeViscousStressDivergence(topology_, fluid.velocity, fluid.viscosity, divTau_);  // interior cells
    if (topology_.distributed()) parallel::fillGhosts({&divTau_[0], &divTau_[1], &divTau_[2]}, *topology_.decomposition);
  }
  // Per-thread packing (forcePass) for trilinear sampling, which reads the planes next to a
  // particle's own (not across a periodic z boundary, not after the flux rescaling).
  // The buffers are whole-grid arrays (flat cell indices): at most kThreadSamplesBytes together.
  constexpr double kThreadSamplesBytes = 256.0 * 1024 * 1024;
  const int rangeThreads = threadsForRanges(static_cast<std::int64_t>(n));
  const double bufferBytes = static_cast<double>(rangeThreads) * static_cast<double>(solidFraction_.data().size()) *
                             13.0 * sizeof(double);  // (13: the most channels)
  planesPerThread_ = settings_.interpolation == InterpolationMode::Trilinear && !settings_.fluxVelocity &&
                     !topology_.periodic[2] && !topology_.distributed() && rangeThreads > 1 &&
                     bufferBytes <= kThreadSamplesBytes;
  packSamples(fluid, fields, planesPerThread_);
  if (w.virtualMass && previousSlipFromSlip_) keepSlipAsPrevious(particles);
  previousSlipFromSlip_ = false;
  const Columns columns = columnsOf(particles);
  const bool standard = sampleChannels_ == kStandardChannels && gradPChannel_ == 4 && divTauChannel_ == 7;
  auto pass = [&](const auto& law) {  // law, interpolation, channels resolved once
    switch (settings_.interpolation) {
      case InterpolationMode::Cell: forcePass<InterpolationMode::Cell, false>(fluid, law, particles, columns); break;
      case InterpolationMode::Trilinear:
        if (standard) forcePass<InterpolationMode::Trilinear, true>(fluid, law, particles, columns);
        else forcePass<InterpolationMode::Trilinear, false>(fluid, law, particles, columns);
        break;
      case InterpolationMode::Stencil:
        forcePass<InterpolationMode::Stencil, false>(fluid, law, particles, columns);
        break;
    }
  };
  // a polydisperse law or the filtered correction: per-particle data besides (Re, eps)
  if (w.drag && (drag_->polydisperse() || settings_.dragCorrection == DragCorrection::Filtered))
    pass(particleCorrection(fluid, particles));
  else
    withDragCorrection(*drag_, pass);
  if (w.drag && drag_->lubricationCutoff() > 0.0) addFluidMediatedFriction(fluid, fields, particles);
  exchangeSet_ = &particles;
  forceStamp_ = particles.layoutStamp;
  if (w.virtualMass) keepSlipAsPrevious(particles);
  forcesReady_ = true;
  exchangePending_ = true;
  exchangeDeposited_ = false;
  if (averaging_) accumulateSubstep(particles);
}

void Coupler::updateSizeStatistics(const dem::ParticleSet& particles, bool classVelocities) {
  const CoarseGraining& cg = settings_.coarseGraining;
  bool known = sizeClasses_.count() > 0;
  for (std::size_t p = 0; known && p < particles.size(); ++p) {
    const double d = 2.0 * particles.radius[p] / cg.factorOf(particles.type[p]);
    known = sizeClasses_.binned() || sizeClasses_.diameters()[static_cast<std::size_t>(sizeClasses_.classOf(d))] == d;
  }
  if (topology_.distributed()) known = !parallel::anyOverRanks(!known);  // (the same classes on every rank)
  if (!known) {
    std::vector<double> diameters(particles.size());
    for (std::size_t p = 0; p < particles.size(); ++p)
      diameters[p] = 2.0 * particles.radius[p] / cg.factorOf(particles.type[p]);
    if (topology_.distributed()) diameters = diametersOfAllRanks(std::move(diameters));
    sizeClasses_ = SizeClasses(std::move(diameters));
  }
  computeCellSizeStatistics(topology_, particles, cg, sizeClasses_, sizeStats_, cellOfParticle_, classOfParticle_,
                            classVelocities, ghostFlags(particles));
  if (topology_.distributed()) completeStatisticsAcrossCuts();
}

void Coupler::completeStatisticsAcrossCuts() {
  // Each rank summed its own particles into its cells and the ghost cells they reach; the sums in
  // ghost cells go to their owners (reverse halo, as the deposits), and the owners' complete cells
  // come back into the ghost cells (a particle near a cut reads its cell's statistics there).
  CellSizeStatistics& st = sizeStats_;
  const auto classes = static_cast<std::size_t>(st.classes);
  const bool classVelocity = !st.classVolumeVelocity.empty();
  const std::size_t channels = 5 + classes * (classVelocity ? 4 : 1);
  const std::size_t cells = st.solidVolume.size();
  if (channelFields_.size() < channels) channelFields_.resize(channels);
  std::vector<Field*> fields;
  for (std::size_t ch = 0; ch < channels; ++ch) {
    if (channelFields_[ch].data().size() != cells) channelFields_[ch] = Field(topology_.grid);
    fields.push_back(&channelFields_[ch]);
  }
  // channel c of cell q: solid volume, volume / diameter, volume velocity (3), class volumes, class
  // volume velocities (3 per class)
  auto forEachChannel = [&](auto&& body) {
    for (std::size_t q = 0; q < cells; ++q) {
      std::size_t c = 0;
      body(c++, q, st.solidVolume[q]);
      body(c++, q, st.volumeOverDiameter[q]);
      for (int a = 0; a < 3; ++a) body(c++, q, st.volumeVelocity[q][a]);
      for (std::size_t i = 0; i < classes; ++i) body(c++, q, st.classVolume[q * classes + i]);
      if (classVelocity)
        for (std::size_t i = 0; i < classes; ++i)
          for (int a = 0; a < 3; ++a) body(c++, q, st.classVolumeVelocity[q * classes + i][a]);
    }
  };
  forEachChannel([&](std::size_t c, std::size_t q, double& v) { fields[c]->data()[q] = v; });
  parallel::sumGhosts(fields, *topology_.decomposition);
  parallel::fillGhosts(fields, *topology_.decomposition);
  forEachChannel([&](std::size_t c, std::size_t q, double& v) { v = fields[c]->data()[q]; });
}

std::vector<double> Coupler::diametersOfAllRanks(std::vector<double> local) {
  // The distinct diameters of every rank: the classes one rank holding every particle would make
  // (SizeClasses keeps up to kMaxSizeClasses distinct diameters, else bins between the smallest and
  // the largest). A rank with more distinct diameters than that sends its smallest, its largest and
  // as many between as make the union binned over the same range.
  std::sort(local.begin(), local.end());
  local.erase(std::unique(local.begin(), local.end()), local.end());
  constexpr auto kMax = static_cast<std::size_t>(SizeClasses::kMaxSizeClasses);
  if (local.size() > kMax + 1) {
    std::vector<double> range(kMax + 1);
    for (std::size_t k = 0; k <= kMax; ++k) range[k] = local[k * (local.size() - 1) / kMax];
    local = std::move(range);
  }
  parallel::Bytes mine;
  parallel::Packer pack(mine);
  for (double d : local) pack.put(d);
  std::vector<double> all;
  for (const parallel::Bytes& bytes : parallel::allgather(mine)) {
    parallel::Unpacker in(bytes);
    while (!in.done()) all.push_back(in.get<double>());
  }
  return all;
}

const CellSizeStatistics& Coupler::sizeStatistics(dem::ParticleSet& particles) {
  updateSizeStatistics(particles);
  const std::size_t column = particles.addColumn(kSizeClassColumn, 0.0);
  double* classOut = particles.doubleColumns[column].values.data();
  for (std::size_t p = 0; p < particles.size(); ++p) classOut[p] = classOfParticle_[p];
  return sizeStats_;
}

ParticleCorrection Coupler::particleCorrection(const FluidView& fluid, const dem::ParticleSet& particles) {
  ParticleCorrection c;
  c.law = drag_.get();
  const CoarseGraining& cg = settings_.coarseGraining;
  const double alpha = cg.factor;
  if (drag_->polydisperse()) {
    updateSizeStatistics(particles, drag_->lubricationCutoff() > 0.0);
    if (sizeClasses_.count() == 1 && !singleSizeWarned_) {
      spdlog::warn("coupling: drag_law {} with particles of one size ({:g} m): it reduces to its monodisperse form",
                   settings_.dragLaw, sizeClasses_.diameters().front());
      singleSizeWarned_ = true;
    }
    // y_i = d_i / <d> and reMix = rho |u_f - <v>| <d> / mu of the particle's cell (the cell holding
    // its centre; size_classes.hpp)
    const std::size_t n = particles.size();
    sizeRatio_.resize(n);
    mixtureReynolds_.resize(n);
    const double* u[3] = {fluid.velocity[0]->data().data(), fluid.velocity[1]->data().data(),
                          fluid.velocity[2]->data().data()};
    for (std::size_t p = 0; p < n; ++p) {
      const std::size_t q = cellOfParticle_[p];
      const double sauter = sizeStats_.sauterDiameter(q);
      const Vec3 mixtureSlip = Vec3{u[0][q], u[1][q], u[2][q]} - sizeStats_.meanParticleVelocity(q);
      sizeRatio_[p] = 2.0 * particles.radius[p] / cg.factorOf(particles.type[p]) / sauter;
      mixtureReynolds_[p] = fluid.density * norm(mixtureSlip) * sauter / fluid.viscosity;
    }
    c.sizeRatio = sizeRatio_.data();
    c.mixtureReynolds = mixtureReynolds_.data();
  }
  if (settings_.dragCorrection == DragCorrection::Filtered) {
    const FilteredDragSettings& fd = settings_.filteredDrag;
    c.filterSize = std::cbrt(topology_.grid.cellVolume());
    c.parcelCorrection = drag::parcelDragCorrection(alpha, fd.parcelA, fd.parcelK);
    if (!cg.uniform()) {  // c_corr(alpha) of each material's factor
      parcelCorrectionByMaterial_.resize(cg.byMaterial.size());
      for (std::size_t m = 0; m < cg.byMaterial.size(); ++m)
        parcelCorrectionByMaterial_[m] = drag::parcelDragCorrection(cg.byMaterial[m], fd.parcelA, fd.parcelK);
      c.parcelCorrectionByMaterial = parcelCorrectionByMaterial_.data();
      c.material = particles.type.data();
    }
    if (!(filterLength_ > 0.0) && (topology_.distributed() || particles.size() > 0)) {
      // d_prim (given, or the Sauter mean primary diameter) and the particles' mean density (of
      // every rank's own particles)
      double volume = 0.0, volumeOverDiameter = 0.0, mass = 0.0;
      const std::uint8_t* ghost = ghostFlags(particles);
      for (std::size_t p = 0; p < particles.size(); ++p) {
        if (ghost && ghost[p]) continue;
        const double d = 2.0 * particles.radius[p];
        volume += force::sphereVolume(d);
        volumeOverDiameter += force::sphereVolume(d) / (d / cg.factorOf(particles.type[p]));
        mass += particles.mass[p];
      }
      if (topology_.distributed()) {
        const std::vector<double> all = parallel::sumOverRanks(std::vector<double>{volume, volumeOverDiameter, mass});
        volume = all[0], volumeOverDiameter = all[1], mass = all[2];
      }
      const double dPrim = fd.primaryDiameter > 0.0 ? fd.primaryDiameter : volume / volumeOverDiameter;
      const double g = norm(gravity_);
      if (!(g > 0.0)) throw std::invalid_argument("coupling: drag_correction: filtered needs gravity (L_char = u_t^2/g Fr^-2/3)");
      const double ut = drag::beetstraTerminalVelocity(dPrim, mass / volume, fluid.density, fluid.viscosity, g);
      if (volume > 0.0) filterLength_ = drag::filteredDragLength(ut, dPrim, g);
      if (volume > 0.0) spdlog::info("coupling: filtered drag (Radl & Sundaresan 2014): d_prim {:.6g} m, u_t {:.6g} m/s, L_char {:.6g} "
                   "m, filter size {:.6g} m, parcel correction {:.6g} at alpha {:g}",
                   dPrim, ut, filterLength_, c.filterSize, c.parcelCorrection, alpha);
    }
    c.filtered = filterLength_ > 0.0;
    c.characteristicLength = filterLength_;
  }
  return c;
}

void Coupler::addFluidMediatedFriction(const FluidView& fluid, const CouplingFields& fields,
                                       dem::ParticleSet& particles) {
  // Per occupied cell, the friction force density on each class (yin_sundaresan.hpp, seed 003 eqs.
  // 3.25-3.27), with the statistics of this force pass (particleCorrection); each particle takes
  // the share V_p / sum_{class i in cell} V_p of its class's force.
  const double lambda = drag_->lubricationCutoff();
  const int nc = sizeStats_.classes;
  const auto& diameters = sizeClasses_.diameters();
  const double mu = fluid.viscosity;
  const double epsFloor = std::max(settings_.minVoidFraction, 1e-6);
  frictionSlot_.assign(sizeStats_.solidVolume.size(), -1);
  frictionForce_.clear();
  std::vector<double> beta(static_cast<std::size_t>(nc)), phi(static_cast<std::size_t>(nc));
  std::vector<Vec3> velocity(static_cast<std::size_t>(nc));
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const std::size_t q = cellOfParticle_[p];
    if (frictionSlot_[q] < 0) {
      frictionSlot_[q] = static_cast<int>(frictionForce_.size() / static_cast<std::size_t>(nc));
      frictionForce_.resize(frictionForce_.size() + static_cast<std::size_t>(nc), Vec3{});
      Vec3* force = frictionForce_.data() + frictionForce_.size() - static_cast<std::size_t>(nc);
      const double eps = std::clamp(fields.voidFraction.data()[q], epsFloor, 1.0);
      const double sauter = sizeStats_.sauterDiameter(q);
      const double reMix = mixtureReynolds_[p];  // the cell's (particleCorrection)
      for (int i = 0; i < nc; ++i) {
        phi[i] = sizeStats_.classVolumeFraction(q, i);
        if (!(phi[i] > 0.0)) continue;
        const double normalised = drag::yinSundaresan(eps, diameters[i] / sauter, reMix) / eps;
        beta[i] = drag::classFrictionCoefficient(phi[i], eps, mu, diameters[i], normalised);
        velocity[i] = sizeStats_.classVelocity(q, i);
      }
      for (int i = 0; i < nc; ++i)
        for (int j = 0; j < nc; ++j) {
          if (j == i || !(phi[i] > 0.0) || !(phi[j] > 0.0)) continue;
          const double alpha = drag::lubricationFactor(std::min(diameters[i], diameters[j]), lambda);
          force[i] += drag::pairFrictionCoefficient(alpha, phi[i], phi[j], beta[i], beta[j]) * (velocity[j] - velocity[i]);
        }
    }
    const int i = classOfParticle_[p];
    const std::size_t k = q * static_cast<std::size_t>(nc) + static_cast<std::size_t>(i);
    const Vec3 density = frictionForce_[static_cast<std::size_t>(frictionSlot_[q]) * static_cast<std::size_t>(nc) +
                                        static_cast<std::size_t>(i)];
    particles.externalForce[p] += (force::sphereVolume(2.0 * particles.radius[p]) / sizeStats_.classVolume[k] *
                                   sizeStats_.cellVolume) * density;
  }
}

void Coupler::chooseSmoothingLength(const dem::ParticleSet& particles) {
  // several factors (per insertion): the law at the largest, whose parcels need the widest smoothing.
  // d32 is the parcels' Sauter mean (seed 003 Tab. 4.15 gives l / d_p,32 of the parcels: l is
  // constant per parcel diameter up to alpha 25, sec. 4.3.1; with it Tab. 4.16's alpha = 33 boxes
  // get their 1.77 mm and 2.23 mm)
  const double alpha = settings_.coarseGraining.largest();
  double volume = 0.0, volumeOverDiameter = 0.0;
  const std::uint8_t* ghost = ghostFlags(particles);
  for (std::size_t p = 0; p < particles.size(); ++p) {
    if (ghost && ghost[p]) continue;
    const double d = 2.0 * particles.radius[p];
    volume += force::sphereVolume(d);
    volumeOverDiameter += force::sphereVolume(d) / d;
  }
  const CartesianGrid& g = topology_.grid;
  auto cells = static_cast<double>(g.interiorCellCount());
  if (topology_.distributed()) {  // (every rank's own particles and cells)
    const std::vector<double> all = parallel::sumOverRanks(std::vector<double>{volume, volumeOverDiameter, cells});
    volume = all[0], volumeOverDiameter = all[1], cells = all[2];
  }
  const double meanFraction = volume / (g.cellVolume() * cells);
  const double sauter = volume / volumeOverDiameter;
  settings_.smoothingLength = autoSmoothingLength(alpha, sauter, meanFraction);
  spdlog::info("coupling: smoothing_length auto = {:.6g} m ({:.4g} d32, parcel d32 = {:.6g} m, alpha = {:g}, <phi_p> = {:.4g}; "
               "seed 003 Tab. 4.15, eq. 4.10)",
               settings_.smoothingLength, settings_.smoothingLength / sauter, sauter, alpha, meanFraction);
}

void Coupler::beginSubstepAverage() {
  averaging_ = true;
  averagedSubsteps_ = 0;
}

void Coupler::accumulateSubstep(dem::ParticleSet& particles) {
  // (a particle inserted during the substeps starts from sums 0: absent from the earlier substeps)
  const std::size_t b = particles.addColumn(kBetaSumColumn, 0.0);
  const std::size_t d = particles.addColumn(kDragSumColumn, Vec3{});
  const std::size_t o = particles.addColumn(kOtherSumColumn, Vec3{});
  double* betaSum = particles.doubleColumns[b].values.data();
  Vec3* dragSum = particles.vec3Columns[d].values.data();
  Vec3* otherSum = particles.vec3Columns[o].values.data();
  const std::size_t n = particles.size();
  if (averagedSubsteps_ == 0) {
    std::fill_n(betaSum, n, 0.0);
    std::fill_n(dragSum, n, Vec3{});
    std::fill_n(otherSum, n, Vec3{});
  }
  const ExchangeData data = exchangeData(particles);
  forEachIndex(static_cast<std::int64_t>(n), 8, [&](std::int64_t p) {
    betaSum[p] += data.beta[p];
    dragSum[p] += force::drag(data.beta[p], data.slip[p]);
    otherSum[p] += data.other[p];
  });
  ++averagedSubsteps_;
}

void Coupler::endSubstepAverage(dem::ParticleSet& particles) {
  averaging_ = false;
  const int substeps = averagedSubsteps_;
  averagedSubsteps_ = 0;
  if (substeps <= 1) return;  // (one substep: its exchange as computed, bit for bit)
  const Columns c = columnsOf(particles);
  const std::size_t b = particles.findDoubleColumn(kBetaSumColumn);
  const std::size_t d = particles.findVec3Column(kDragSumColumn);
  const std::size_t o = particles.findVec3Column(kOtherSumColumn);
  if (b == dem::ParticleSet::kNoColumn || d == dem::ParticleSet::kNoColumn || o == dem::ParticleSet::kNoColumn)
    throw std::logic_error("coupling: endSubstepAverage on a particle set the substeps' forces were not computed on");
  const double* betaSum = particles.doubleColumns[b].values.data();
  const Vec3* dragSum = particles.vec3Columns[d].values.data();
  const Vec3* otherSum = particles.vec3Columns[o].values.data();
  const std::size_t n = particles.size();
  const double inverse = 1.0 / static_cast<double>(substeps);
  forEachIndex(static_cast<std::int64_t>(n), 8, [&](std::int64_t p) {
    // mean beta and mean drag; the slip is what gives that drag with the mean beta (to round-off)
    const double beta = inverse * betaSum[p];
    const Vec3 drag = inverse * dragSum[p];
    c.beta[p] = beta;
    c.slip[p] = beta > 0.0 ? (1.0 / beta) * drag : Vec3{};
    c.other[p] = inverse * otherSum[p];
  });
  exchangeSet_ = &particles;
  forceStamp_ = particles.layoutStamp;
  particleForceSumsValid_ = false;  // the balance sums the means
}

void Coupler::fillFluidSources(const dem::ParticleSet& particles, CouplingFields& fields) {
  if (!forcesReady_) throw std::logic_error("coupling: computeParticleForces must run before fillFluidSources");
  if (stencils_.size() != particles.size())
    throw std::logic_error("coupling: computeVoidFraction must run on the current particle set before fillFluidSources");
  if (!carriesExchange(particles))
    throw std::logic_error("coupling: fillFluidSources on a particle set computeParticleForces did not run on");
  followLayout(particles);
  if (!exchangeDeposited_ && !stencilsKept_) {  // (the deposit below reads them)
    scheme_->buildStencils(particles, topology_, stencils_);
    stencilsKept_ = true;
  }
  fillFluidSources(fields);
}

void Coupler::fillFluidSources(CouplingFields& fields) {
  if (!forcesReady_ || !exchangeSet_ || exchangeSet_->size() != stencils_.size() || !carriesExchange(*exchangeSet_))
    throw std::logic_error("coupling: computeParticleForces must run before fillFluidSources (same particle set)");
  const bool implicit = settings_.exchange == ExchangeScheme::SemiImplicit;
  depositExchange(fields, implicit);
  if (settings_.smoothExchangeFields && settings_.smoothingLength > 0.0) smoothExchange(fields, implicit);
  // the ghosts of the 7 exchange fields in one pass over the ghost lists
  double* exchange[7] = {fields.forceDensity[0].data().data(),     fields.forceDensity[1].data().data(),
                         fields.forceDensity[2].data().data(),     fields.dragCoefficient.data().data(),
                         fields.particleVelocity[0].data().data(), fields.particleVelocity[1].data().data(),
                         fields.particleVelocity[2].data().data()};
  forEachIndex(static_cast<std::int64_t>(ghostTarget_.size()), 7, [&](std::int64_t q) {
    const std::size_t target = ghostTarget_[q], source = ghostSource_[q];  // source: an interior cell
    for (double* d : exchange) d[target] = d[source];
  });
  if (topology_.distributed())  // (across the cuts: the neighbours' cells, one exchange for all 7)
    parallel::fillGhosts({&fields.forceDensity[0], &fields.forceDensity[1], &fields.forceDensity[2],
                          &fields.dragCoefficient, &fields.particleVelocity[0], &fields.particleVelocity[1],
                          &fields.particleVelocity[2]},
                         *topology_.decomposition);
  updateMomentumBalance(fields, implicit, exchangeSet_->size());
  exchangePending_ = exchangeDeposited_ = false;
}

Coupler::ExchangeLayout Coupler::exchangeLayout() const {
  if (settings_.exchange == ExchangeScheme::Explicit) return ExchangeLayout::Explicit;
  // the force pass's exchangedOther: pressure and viscous forces in model B, virtual mass, lifts
  const ForceSwitches& w = settings_.forces;
  const bool modelB = settings_.model == ExchangeModel::B;
  const bool other = (modelB && (w.pressureGradient || w.viscousStress)) || w.virtualMass || w.saffmanMeiLift ||
                     w.magnusLift;
  return other ? ExchangeLayout::Implicit : ExchangeLayout::DragOnly;
}

template <class Body>
void Coupler::withExchangeLayout(Body&& body) const {
  switch (exchangeLayout()) {
    case ExchangeLayout::Explicit: body(std::integral_constant<ExchangeLayout, ExchangeLayout::Explicit>{}); break;
    case ExchangeLayout::Implicit: body(std::integral_constant<ExchangeLayout, ExchangeLayout::Implicit>{}); break;
    case ExchangeLayout::DragOnly: body(std::integral_constant<ExchangeLayout, ExchangeLayout::DragOnly>{}); break;
  }
}

template <Coupler::ExchangeLayout Layout>
void Coupler::exchangeValues(const ExchangeData& data, std::size_t p, double* v) {
  const double* beta_ = data.beta;  // (the members' names, for the formulas below)
  const Vec3* slip_ = data.slip;
  const Vec3* otherExchangedForce_ = data.other;
  if constexpr (Layout == ExchangeLayout::Explicit) {
    // explicit: every exchanged force on the fluid
    const Vec3 f = -(otherExchangedForce_[p] + force::drag(beta_[p], slip_[p]));
    v[0] = f.x, v[1] = f.y, v[2] = f.z;
  } else if constexpr (Layout == ExchangeLayout::Implicit) {
    // implicit: 0-2 explicit force on the fluid, 3 beta, 4-6 beta (u_p - u_f@p)
    const Vec3 f = -otherExchangedForce_[p];
    const double b = beta_[p];
    const Vec3 s = slip_[p];
    v[0] = f.x, v[1] = f.y, v[2] = f.z;
    v[3] = b;
    v[4] = -b * s.x, v[5] = -b * s.y, v[6] = -b * s.z;
  } else {
    // implicit, drag only: 0 beta, 1-3 beta (u_p - u_f@p); the explicit force on the fluid is
    // zero (-0 per particle, whose deposit leaves every cell sum +0: depositExchange writes 0)
    const double b = beta_[p];
    const Vec3 s = slip_[p];
    v[0] = b;
    v[1] = -b * s.x, v[2] = -b * s.y, v[3] = -b * s.z;
  }
}

void Coupler::depositExchange(CouplingFields& fields, bool implicit) {
  const std::size_t cells = solidFraction_.data().size();
  const auto& c = topology_.grid.cells;
  const double inverseCellVolume = 1.0 / topology_.grid.cellVolume();
  const Field* const* u = lastFluid_.velocity;
  // the sums of computeVoidFraction's fused deposit (channel 0 the volume) or a deposit of their own
  const double* sum = nullptr;
  std::size_t stride = 0;
  const ExchangeLayout layout = exchangeLayout();
  if (exchangeDeposited_) {
    stride = 1 + channelsOf(layout);
    sum = deposit_.merged.data() + 1;
  } else {
    if (!stencilsKept_)
      throw std::logic_error(
          "coupling: fillFluidSources without particles after a fused deposit: computeVoidFraction must run again, "
          "or pass the particles");
    withExchangeLayout([&](auto l) {
      constexpr ExchangeLayout L = decltype(l)::value;
      stride = channelsOf(L);
      const ExchangeData data = exchangeData(*exchangeSet_);
      const std::uint8_t* ghost = ghostFlags(*exchangeSet_);
      depositChannels<channelsOf(L)>(stencils_, cells, deposit_, [data, ghost](std::size_t p, auto& v) {
        if (ghost && ghost[p]) return std::fill(std::begin(v), std::end(v), 0.0);
        exchangeValues<L>(data, p, v);
      });
    });
    sumDepositGhosts(static_cast<int>(stride));
    sum = deposit_.merged.data();
  }
  // where the explicit force, beta and beta (u_p - u_f@p) lie in a cell's sums (-1: zero)
  const int forceChannel = layout == ExchangeLayout::DragOnly ? -1 : 0;
  const int dragChannel = layout == ExchangeLayout::DragOnly ? 0 : 3;
  // interior cells are all written below, ghosts by fillGhosts
  if (!implicit) {
    fields.dragCoefficient.fill(0.0);
    for (int a = 0; a < 3; ++a) fields.particleVelocity[a].fill(0.0);
    for (int k = 0; k < c[2]; ++k)
      for (int j = 0; j < c[1]; ++j)
        for (int i = 0; i < c[0]; ++i) {
          const std::size_t q = solidFraction_.index(i, j, k);
          for (int a = 0; a < 3; ++a) fields.forceDensity[a].data()[q] = sum[q * stride + a] * inverseCellVolume;
        }
    return;
  }
  double* force[3] = {fields.forceDensity[0].data().data(), fields.forceDensity[1].data().data(),
                      fields.forceDensity[2].data().data()};
  double* up[3] = {fields.particleVelocity[0].data().data(), fields.particleVelocity[1].data().data(),
                   fields.particleVelocity[2].data().data()};
  const double* uf[3] = {u[0]->data().data(), u[1]->data().data(), u[2]->data().data()};
  double* drag = fields.dragCoefficient.data().data();
  const auto* runs = interiorRuns_.data();
  forEachIndex(static_cast<std::int64_t>(interiorRuns_.size()), 8 * topology_.grid.cells[0], [&](std::int64_t r) {
    const auto& run = runs[r];  // an interior row; rows in parallel (disjoint writes)
    for (std::size_t q = run[0]; q < run[0] + run[1]; ++q) {
      const double* v = &sum[q * stride];
      for (int a = 0; a < 3; ++a) force[a][q] = forceChannel < 0 ? 0.0 : v[forceChannel + a] * inverseCellVolume;
      const double kv = v[dragChannel];  // sum w beta
      drag[q] = kv * inverseCellVolume;
      // K u_p_avg V = sum w beta (u_p + u_c - u_f@p): the mean particle velocity corrected by the
      // interpolation defect, so that K (u_c - u_p_avg) V equals the particles' drag exactly.
      for (int a = 0; a < 3; ++a) up[a][q] = kv > 0.0 ? uf[a][q] + v[dragChannel + 1 + a] / kv : 0.0;
    }
  });
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

void Coupler::updateMomentumBalance(const CouplingFields& fields, bool implicit, std::size_t particleCount) {
  // Newton's third law: particles' exchanged forces + fluid sources (explicit - K (u - u_p)) = 0.
  // the particle side as summed by the force pass (same terms, same order), unless the particle
  // set was reordered since
  const ExchangeData data = particleForceSumsValid_ ? ExchangeData{} : exchangeData(*exchangeSet_);
  const std::uint8_t* ghost = ghostFlags(*exchangeSet_);
  std::array<double, 4> sums =
      particleForceSumsValid_
          ? particleForceSums_
          : sumsOverIndices<4>(
                static_cast<std::int64_t>(particleCount),
                [&](std::int64_t p, std::array<double, 4>& sum) {
                  if (ghost && ghost[p]) return;  // (its owner counts it)
                  const Vec3 f = force::drag(data.beta[p], data.slip[p]) + data.other[p];
                  sum[0] += f.x, sum[1] += f.y, sum[2] += f.z;
                  sum[3] += norm(f);
                },
                &particleBlocks_);
  const Vec3 onParticles{sums[0], sums[1], sums[2]};
  Vec3 onFluid{};
  exchangedForceScale_ = sums[3];
  const double cellVolume = topology_.grid.cellVolume();
  const Field* const* u = lastFluid_.velocity;
  // interior cells in (k, j, i) order, by rows of flat indices (all fields share the layout)
  const double* force[3] = {fields.forceDensity[0].data().data(), fields.forceDensity[1].data().data(),
                            fields.forceDensity[2].data().data()};
  const double* up[3] = {fields.particleVelocity[0].data().data(), fields.particleVelocity[1].data().data(),
                         fields.particleVelocity[2].data().data()};
  const double* uf[3] = {u[0]->data().data(), u[1]->data().data(), u[2]->data().data()};
  const double* drag = fields.dragCoefficient.data().data();
  // interior rows in parallel, the sums per row added in row order (the same bits on any thread count)
  const auto* runs = interiorRuns_.data();
  runSums_.resize(interiorRuns_.size());
  forEachIndex(static_cast<std::int64_t>(interiorRuns_.size()), 8 * topology_.grid.cells[0], [&](std::int64_t r) {
    std::array<double, 3> sum{};
    for (std::size_t q = runs[r][0]; q < runs[r][0] + runs[r][1]; ++q)
      for (int a = 0; a < 3; ++a) {
        double s = force[a][q];
        if (implicit) s -= drag[q] * (uf[a][q] - up[a][q]);
        sum[a] += s * cellVolume;
      }
    runSums_[r] = sum;
  });
  for (const auto& sum : runSums_)
    for (int a = 0; a < 3; ++a) onFluid[a] += sum[a];
  Vec3 particles = onParticles;
  if (topology_.distributed()) {  // (every rank's particles and cells: one allreduce)
    const std::vector<double> all = parallel::sumOverRanks(std::vector<double>
        {particles.x, particles.y, particles.z, exchangedForceScale_, onFluid.x, onFluid.y, onFluid.z});
    particles = {all[0], all[1], all[2]};
    exchangedForceScale_ = all[3];
    onFluid = {all[4], all[5], all[6]};
  }
  balanceError_ = particles + onFluid;
}

CouplingIntervalCheck Coupler::checkCouplingInterval(double demTimeStep, int demStepsPerFluidStep,
                                                     const dem::ParticleSet& particles, const FluidView& fluid,
                                                     double slip) const {
  // the fastest-relaxing particle: smallest rho_p d_prim^2
  double best = -1.0, d = 0.0, rhoP = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double dp = 2.0 * particles.radius[p] / settings_.coarseGraining.factorOf(particles.type[p]);
    const double rp = particles.mass[p] / force::sphereVolume(2.0 * particles.radius[p]);
    if (best < 0.0 || rp * dp * dp < best) {
      best = rp * dp * dp;
      d = dp;
      rhoP = rp;
    }
  }
  if (topology_.distributed()) {
    // the fastest-relaxing particle of all ranks (the lowest rank's among equals)
    const std::vector<double> bests = parallel::allgather(best >= 0.0 ? best : std::numeric_limits<double>::infinity());
    const std::vector<double> ds = parallel::allgather(d), rhos = parallel::allgather(rhoP);
    const auto r = static_cast<std::size_t>(std::min_element(bests.begin(), bests.end()) - bests.begin());
    if (!std::isfinite(bests[r])) return {};
    best = bests[r], d = ds[r], rhoP = rhos[r];
  }
  if (best < 0.0) return {};
  return gf::coupling::checkCouplingInterval(demTimeStep, demStepsPerFluidStep, rhoP, d, fluid.density,
                                             fluid.viscosity, slip, settings_.minRelaxationToIntervalRatio);
}

void Coupler::keepSlipAsPrevious(dem::ParticleSet& particles) const {
  // the slip of this step is the previous slip of the next one; only the virtual mass force reads
  // it (its column exists only then), otherwise the checkpoint takes the slip itself
  const std::size_t previous = particles.findVec3Column(kPreviousSlipColumn);
  const std::size_t slip = particles.findVec3Column(kSlipColumn);
  if (previous != dem::ParticleSet::kNoColumn && slip != dem::ParticleSet::kNoColumn)
    particles.vec3Columns[previous].values = particles.vec3Columns[slip].values;
}

void Coupler::save(BinaryWriter& out, const dem::ParticleSet& particles) const {
  // the ids, and the previous slip in their order (the slip itself where it is the previous one:
  // without virtual mass, or before the next force pass copies it); nothing before the first force pass
  const std::size_t slip = particles.findVec3Column(kSlipColumn);
  const std::size_t previous = particles.findVec3Column(kPreviousSlipColumn);
  const bool fromPrevious =
      settings_.forces.virtualMass && !previousSlipFromSlip_ && previous != dem::ParticleSet::kNoColumn;
  if (topology_.distributed()) {
    // every rank's own particles, gathered on rank 0 and sorted by id (the same file for any
    // rank count; only rank 0's writer is written out)
    parallel::Bytes mine;
    parallel::Packer pack(mine);
    const std::uint8_t* ghost = ghostFlags(particles);
    if (slip != dem::ParticleSet::kNoColumn)
      for (std::size_t p = 0; p < particles.size(); ++p)
        if (!(ghost && ghost[p])) {
          pack.put(particles.id[p]);
          pack.put(particles.vec3Columns[fromPrevious ? previous : slip].values[p]);
        }
    std::vector<std::pair<std::int64_t, Vec3>> all;
    for (const parallel::Bytes& bytes : parallel::gatherToRoot(mine)) {
      parallel::Unpacker in(bytes);
      while (!in.done()) {
        const auto id = in.get<std::int64_t>();
        all.emplace_back(id, in.get<Vec3>());
      }
    }
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::int64_t> ids(all.size());
    std::vector<Vec3> slips(all.size());
    for (std::size_t k = 0; k < all.size(); ++k) ids[k] = all[k].first, slips[k] = all[k].second;
    out.putVector(ids);
    out.putVector(slips);
    return;
  }
  if (slip == dem::ParticleSet::kNoColumn) {
    out.putVector(std::vector<std::int64_t>{});
    out.putVector(std::vector<Vec3>{});
    return;
  }
  out.putVector(particles.id);
  out.putVector(particles.vec3Columns[fromPrevious ? previous : slip].values);
}

void Coupler::load(BinaryReader& in, dem::ParticleSet& particles) {
  const std::vector<std::int64_t> ids = in.getVector<std::int64_t>();
  const std::vector<Vec3> slips = in.getVector<Vec3>();
  if (ids.size() != slips.size())
    throw CheckpointError("checkpoint is corrupt: coupling state arrays have different lengths");
  previousSlipFromSlip_ = false;
  forceStamp_ = 0;
  if (ids.empty()) return;  // (written before the first force pass)
  // into the slip column too: the same checkpoint again from a restart without a force pass
  const Columns columns = columnsOf(particles);
  const std::vector<std::size_t> from = previousIndexById(ids, particles.id);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const bool known = from[p] != kNewParticle;
    columns.slip[p] = known ? slips[from[p]] : Vec3{};
    if (columns.previousSlip) columns.previousSlip[p] = known ? slips[from[p]] : Vec3{nan, nan, nan};
  }
}

}  // namespace gf::coupling
