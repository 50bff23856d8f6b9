// The fast paths of the coupling step against their definitions, bit for bit: the tabulated
// trilinear sampler (forces), the 2 x 2 x 2 block path of the divided scheme and its piecewise
// building (void fraction), and the per-thread-block sums (momentum balance, particle volume).
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "coupling/deposit.hpp"
#include "coupling/drag/dispatch.hpp"
#include "coupling/drag/gidaspow.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/loops.hpp"
#include "coupling/void_fraction/divided.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {

const std::array<bool, 3> kPeriodicities[] = {{false, false, false}, {true, false, true}, {true, true, true}};

/// The 29 unit points of the divided scheme as its documentation defines them (divided.cpp, CFDEM
/// 'divided'): the centre, and on spheres of radius 0.623926 and 0.623926 + 0.293976 the 8 points
/// (+-r/2, +-r/2, +-r/sqrt(2)) and the 6 points on the axes.
std::vector<Vec3> dividedUnitPoints() {
  std::vector<Vec3> pts{{0.0, 0.0, 0.0}};
  for (double r : {0.623926, 0.623926 + 0.293976}) {
    for (double sx : {1.0, -1.0})
      for (double sy : {1.0, -1.0})
        for (double sz : {1.0, -1.0}) pts.push_back({sx * 0.5 * r, sy * 0.5 * r, sz * std::sqrt(0.5) * r});
    for (int axis = 0; axis < 3; ++axis)
      for (double s : {-1.0, 1.0}) {
        Vec3 v{};
        v[axis] = s * r;
        pts.push_back(v);
      }
  }
  return pts;
}

std::unique_ptr<VoidFractionScheme> makeScheme(const std::string& name) {
  Params p = Params::loadString("void_fraction: " + name + "\n", "test.yaml");
  return Registry<VoidFractionScheme>::instance().create(p, {"void_fraction", "-", "scheme"}, name);
}

}  // namespace

TEST(FastPaths, TabulatedTrilinearSamplerIsBitIdenticalToSampleTrilinear) {
  // positions inside, next to the walls and up to 1.5 cells outside (clamped / wrapped)
  const CartesianGrid g = makeGrid({3, 4, 5}, {0.01, 0.008, 0.012}, {-0.004, 0.002, 0.001});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  constexpr int kChannels = 10;
  for (const auto& periodic : kPeriodicities) {
    const GridTopology t(g, periodic);
    const Field layout(g);
    std::vector<double> buffer(layout.data().size() * kChannels);
    for (double& v : buffer) v = u(rng);
    const TrilinearSampler sampler(t);
    for (int n = 0; n < 2000; ++n) {
      Vec3 x;
      for (int a = 0; a < 3; ++a) x[a] = g.origin[a] + (0.5 + 0.5 * u(rng)) * g.cells[a] * g.spacing[a] + u(rng) * g.spacing[a];
      double expected[kChannels], fixed[kChannels], runtime[kChannels];
      sampleTrilinear<kChannels>(t, x, buffer.data(), kChannels, expected);
      sampler.sample<kChannels>(x, buffer.data(), kChannels, fixed);
      sampler.sample<0>(x, buffer.data(), kChannels, runtime);
      for (int ch = 0; ch < kChannels; ++ch) {
        ASSERT_EQ(fixed[ch], expected[ch]) << "channel " << ch;
        ASSERT_EQ(runtime[ch], expected[ch]) << "channel " << ch;
      }
    }
  }
}

TEST(FastPaths, DividedBlockStencilsAreTheCellsOfThe29SatellitePoints) {
  // particles smaller than a cell (the block path), centres inside and up to 3 cells outside the
  // box: every satellite point's part (1/29) goes to the cell containing the point (wrapped at
  // periodic boundaries, folded back at walls), merged by cell
  const CartesianGrid g = makeGrid({2, 6, 7}, {0.0075, 0.005, 0.005}, {0.0, 0.001, -0.002});
  const dem::ParticleSet particles =
      randomParticles(4000, 0.0008, 0.0013, {-0.0225, -0.014, -0.017}, {0.0375, 0.046, 0.048}, 5);
  const std::vector<Vec3> unit = dividedUnitPoints();
  ASSERT_EQ(unit.size(), 29u);
  const auto scheme = makeScheme("divided");
  for (bool avx512 : {true, false})  // the AVX-512 form (where the CPU has it) and the generic one
  for (const auto& periodic : kPeriodicities) {
    allowDividedAvx512(avx512);
    const GridTopology t(g, periodic);
    ParticleStencils s;
    scheme->buildStencils(particles, t, s);
    allowDividedAvx512(true);
    ASSERT_EQ(s.capacity, 8);  // the block path
    for (std::size_t p = 0; p < particles.size(); ++p) {
      std::map<std::size_t, int> points;
      for (const Vec3& v : unit) {
        const auto c = t.cellOf(particles.position[p] + particles.radius[p] * v);
        ++points[t.flat(c[0], c[1], c[2])];
      }
      ASSERT_EQ(s.count[p], static_cast<int>(points.size())) << "particle " << p;
      double sum = 0.0;
      for (int e = 0; e < s.count[p]; ++e) {
        const std::size_t cell = s.cell[p * s.capacity + e];
        ASSERT_EQ(points.count(cell), 1u) << "particle " << p;
        EXPECT_EQ(s.weight[p * s.capacity + e], points[cell] * (1.0 / 29.0));
        sum += s.weight[p * s.capacity + e];
      }
      EXPECT_NEAR(sum, 1.0, 1e-15);
    }
  }
}

namespace {
// Stencils of the AVX-512 and the generic divided paths (each periodicity): same counts, cells and
// weights, bit for bit (and the given stencil capacity, where one is given).
void expectDividedPathsAgree(const dem::ParticleSet& particles, const CartesianGrid& g, int expectedCapacity = 0) {
  const auto scheme = makeScheme("divided");
  for (const auto& periodic : kPeriodicities) {
    const GridTopology t(g, periodic);
    ParticleStencils vector, generic;
    scheme->buildStencils(particles, t, vector);
    allowDividedAvx512(false);
    scheme->buildStencils(particles, t, generic);
    allowDividedAvx512(true);
    ASSERT_EQ(vector.capacity, generic.capacity);
    if (expectedCapacity > 0) {
      ASSERT_EQ(vector.capacity, expectedCapacity);
    }
    ASSERT_EQ(vector.count, generic.count);
    for (std::size_t p = 0; p < generic.count.size(); ++p)
      for (int e = 0; e < generic.count[p]; ++e) {
        const std::size_t q = p * generic.capacity + e;
        ASSERT_EQ(vector.cell[q], generic.cell[q]) << "particle " << p;
        ASSERT_EQ(vector.weight[q], generic.weight[q]) << "particle " << p;
      }
  }
}
}  // namespace

TEST(FastPaths, DividedBlockPathGivesTheSameStencilsWithAndWithoutAvx512) {
  // particles smaller than a cell, also outside the box (folds, wraps), radii changing along the
  // set (the scaled points are rebuilt) and runs of equal radii (reused)
  const CartesianGrid g = makeGrid({2, 6, 7}, {0.0075, 0.005, 0.005}, {0.0, 0.001, -0.002});
  dem::ParticleSet particles =
      randomParticles(3000, 0.0008, 0.0013, {-0.0225, -0.014, -0.017}, {0.0375, 0.046, 0.048}, 13);
  for (std::size_t p = 0; p < particles.size(); p += 3) particles.radius[p] = 0.00125;
  expectDividedPathsAgree(particles, g);
}

TEST(FastPaths, DividedGroupsOfEightEqualRadiiGiveTheSameStencilsAsTheGenericPath) {
  // the AVX-512 block path takes 8 particles of one radius side by side (splits per lane) and the
  // block cells from per-axis tables: the bed's case (one radius, centres inside the box or a
  // little outside: folds and wraps), plus runs broken by another radius and centres far outside
  // (beyond the tables: the per-particle form) at places that cut groups of 8 anywhere
  const CartesianGrid g = makeGrid({2, 6, 7}, {0.0075, 0.005, 0.005}, {0.0, 0.001, -0.002});
  dem::ParticleSet particles =
      randomParticles(4000, 0.00125, 0.00125, {-0.004, -0.004, -0.006}, {0.019, 0.035, 0.037}, 17);
  for (std::size_t p = 0; p < particles.size(); ++p) particles.radius[p] = 0.00125;
  for (std::size_t p = 37; p < particles.size(); p += 101) particles.radius[p] = 0.001;
  for (std::size_t p = 500; p < particles.size(); p += 613) particles.position[p].z = 0.06;
  expectDividedPathsAgree(particles, g, 8);
}

namespace {
/// depositChannels<C> of random signed values over the divided stencils of `particles`, with or
/// without the four-channels-per-operation form.
template <int C>
std::vector<double> depositRandom(const ParticleStencils& s, std::size_t cells, bool wide) {
  std::vector<double> values(s.size() * C);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& v : values) v = u(rng) * std::pow(10.0, 6.0 * u(rng));  // mixed magnitudes and signs
  allowWideDeposit(wide);
  DepositBuffers b;
  std::vector<double> sums = depositChannels<C>(s, cells, b, [&](std::size_t p, double (&v)[C]) {
    for (int ch = 0; ch < C; ++ch) v[ch] = values[p * C + ch];
  });
  allowWideDeposit(true);
  return sums;
}
}  // namespace

TEST(FastPaths, WideDepositIsBitIdenticalToThePairwiseDeposit) {
  // channels 4 at a time (AVX2, where the CPU has it) against 2 at a time, for the channel counts
  // of the fused volume + exchange deposits (5 drag-only, 8 implicit) and others; particles
  // crowded in few cells (long chains per cell), 1 thread and the threads at hand
  const CartesianGrid g = makeGrid({2, 4, 5}, {0.0075, 0.005, 0.005});
  const dem::ParticleSet particles = randomParticles(6000, 0.00125, 0.00125, {0, 0, 0}, {0.015, 0.02, 0.025}, 31);
  const auto scheme = makeScheme("divided");
  const GridTopology t(g, {true, false, false});
  ParticleStencils s;
  scheme->buildStencils(particles, t, s);
  const std::size_t cells = Field(g).data().size();  // flat indices with ghosts
  for (int threads : {1, omp_get_max_threads()}) {
    omp_set_num_threads(threads);
    EXPECT_EQ(depositRandom<5>(s, cells, true), depositRandom<5>(s, cells, false));
    EXPECT_EQ(depositRandom<8>(s, cells, true), depositRandom<8>(s, cells, false));
    EXPECT_EQ(depositRandom<4>(s, cells, true), depositRandom<4>(s, cells, false));
    EXPECT_EQ(depositRandom<7>(s, cells, true), depositRandom<7>(s, cells, false));
  }
}

TEST(FastPaths, TrilinearBlockSamplingIsBitIdenticalToTheSampler) {
  // sampleTrilinearBlock (vector registers, AVX-512 / AVX2 clones) against TrilinearSampler::sampleAt
  const CartesianGrid g = makeGrid({3, 4, 5}, {0.01, 0.008, 0.012}, {-0.004, 0.002, 0.001});
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  constexpr int kChannels = kTrilinearBlockChannels;
  for (const auto& periodic : kPeriodicities) {
    const GridTopology t(g, periodic);
    const Field layout(g);
    std::vector<double> buffer(layout.data().size() * kChannels);
    for (double& v : buffer) v = u(rng) * std::exp(10.0 * u(rng));
    const TrilinearSampler sampler(t);
    constexpr int kBlock = 32;
    for (int block = 0; block < 60; ++block) {
      TrilinearSampler::Location where[kBlock];
      for (auto& l : where) {
        Vec3 x;
        for (int a = 0; a < 3; ++a)
          x[a] = g.origin[a] + (0.5 + 0.5 * u(rng)) * g.cells[a] * g.spacing[a] + u(rng) * g.spacing[a];
        sampler.locate(x, l);
      }
      const int count = 1 + block % kBlock;  // partial blocks too
      double out[kBlock][13];
      sampleTrilinearBlock(where, count, buffer.data(), out);
      for (int q = 0; q < count; ++q) {
        double expected[kChannels];
        sampler.sampleAt<kChannels>(where[q], buffer.data(), kChannels, expected);
        for (int ch = 0; ch < kChannels; ++ch) ASSERT_EQ(out[q][ch], expected[ch]) << "channel " << ch;
      }
    }
  }
}

TEST(FastPaths, DragOnlyExchangeEqualsTheFullImplicitExchangeBitForBit) {
  // Model A without virtual mass and lifts exchanges the drag only: the deposit skips the three
  // zero channels of the explicit force. The same case with a zero virtual-mass force (C_vm = 0)
  // takes the full 7-channel implicit layout; both must give the same fields and forces, in the
  // time-loop order (exchange fused into the void-fraction deposit) and in the short order.
  const CartesianGrid g = makeGrid({6, 7, 8}, {0.01, 0.01, 0.01});
  const dem::ParticleSet base = randomParticles(6000, 0.001, 0.002, {0, 0, 0}, {0.06, 0.07, 0.08}, 21);
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{std::sin(60 * x.y), 0.3 * x.x, 1.0 + std::cos(50 * x.x)}; });
  fluid.setPressureGradient(g, [](const Vec3& x) { return Vec3{0.0, 10 * x.z, -9810.0 + 100 * x.y}; });
  for (bool fused : {true, false}) {
    std::vector<Field> results[2];
    std::vector<Vec3> forces[2];
    for (int variant = 0; variant < 2; ++variant) {
      const std::string yaml = std::string("  drag_law: gidaspow\n") +
                               (variant ? "  forces:\n    virtual_mass: true\n    virtual_mass_coefficient: 0\n" : "");
      auto c = makeCoupler(yaml, g, {true, false, false});
      dem::ParticleSet particles = base;
      CouplingFields fields(g);
      c->computeVoidFraction(particles, fields);
      c->computeParticleForces(fluid.view(1.2, 1.8e-5, 2e-5), fields, particles);
      if (fused) {
        for (std::size_t p = 0; p < particles.size(); ++p) particles.position[p].z += 0.0007;  // "DEM"
        c->computeVoidFraction(particles, fields);
        c->fillFluidSources(particles, fields);
      } else {
        c->fillFluidSources(fields);
      }
      EXPECT_LT(norm(c->momentumBalanceError()), 1e-13 * c->exchangedForceScale());
      results[variant] = {fields.forceDensity[0], fields.forceDensity[1], fields.forceDensity[2],
                          fields.dragCoefficient, fields.particleVelocity[0], fields.particleVelocity[1],
                          fields.particleVelocity[2], fields.voidFraction};
      forces[variant] = particles.externalForce;
    }
    EXPECT_EQ(forces[0], forces[1]) << "fused " << fused;
    for (std::size_t f = 0; f < results[0].size(); ++f)
      EXPECT_EQ(results[0][f].data(), results[1][f].data()) << "field " << f << ", fused " << fused;
  }
}

TEST(FastPaths, StencilsBuiltInPiecesEqualTheWholeBuildForEveryScheme) {
  const CartesianGrid g = makeGrid({4, 5, 6}, {0.01, 0.01, 0.01});
  const dem::ParticleSet small = randomParticles(700, 0.001, 0.002, {-0.001, 0, 0}, {0.041, 0.05, 0.06}, 9);
  const dem::ParticleSet big = randomParticles(200, 0.004, 0.006, {0, 0, 0}, {0.04, 0.05, 0.06}, 10);
  for (const char* name : {"pcm", "divided", "kernel", "big_particle"}) {
    const auto scheme = makeScheme(name);
    for (const dem::ParticleSet* particles : {&small, &big}) {
      const GridTopology t(g, {true, false, false});
      ParticleStencils whole, pieces;
      scheme->buildStencils(*particles, t, whole);
      scheme->beginStencils(*particles, t, pieces);
      // uneven pieces, last first
      const std::size_t n = particles->size(), cut = n / 3;
      scheme->buildStencilRange(*particles, t, pieces, cut, n, cut);
      scheme->buildStencilRange(*particles, t, pieces, 0, cut, 0);
      ASSERT_EQ(pieces.capacity, whole.capacity) << name;
      ASSERT_EQ(pieces.count, whole.count) << name;
      for (std::size_t p = 0; p < n; ++p)
        for (int e = 0; e < whole.count[p]; ++e) {
          const std::size_t q = p * whole.capacity + e;
          ASSERT_EQ(pieces.cell[q], whole.cell[q]) << name;
          ASSERT_EQ(pieces.weight[q], whole.weight[q]) << name;
        }
      // schemes that build in pieces: each piece into a buffer of one piece (entries from 0)
      ParticleStencils sized;
      if (!scheme->beginStencils(*particles, t, sized)) continue;
      ParticleStencils buffer;
      buffer.resize(100, sized.capacity);
      for (std::size_t begin = 0; begin < n; begin += 100) {
        const std::size_t end = std::min(n, begin + 100);
        scheme->buildStencilRange(*particles, t, buffer, begin, end, 0);
        for (std::size_t p = begin; p < end; ++p) {
          ASSERT_EQ(buffer.count[p - begin], whole.count[p]) << name;
          for (int e = 0; e < whole.count[p]; ++e) {
            ASSERT_EQ(buffer.cell[(p - begin) * whole.capacity + e], whole.cell[p * whole.capacity + e]) << name;
            ASSERT_EQ(buffer.weight[(p - begin) * whole.capacity + e], whole.weight[p * whole.capacity + e]) << name;
          }
        }
      }
    }
  }
}

TEST(FastPaths, SumsOverRangesEqualSumsOverIndicesBitForBit) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> values(20011);
  for (double& v : values) v = u(rng) * std::exp(20.0 * u(rng));  // wide range: order matters
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    const auto n = static_cast<std::int64_t>(values.size());
    const auto byIndex = sumsOverIndices<2>(n, [&](std::int64_t i, std::array<double, 2>& s) {
      s[0] += values[i];
      s[1] += std::abs(values[i]);
    });
    const auto byRange = sumsOverRanges<2>(n, [&](std::int64_t begin, std::int64_t end, std::array<double, 2>& s) {
      for (std::int64_t i = begin; i < end; i += 7)  // in pieces, as the force pass does
        for (std::int64_t k = i; k < std::min(end, i + 7); ++k) {
          s[0] += values[k];
          s[1] += std::abs(values[k]);
        }
    });
    EXPECT_EQ(byRange[0], byIndex[0]) << threads;
    EXPECT_EQ(byRange[1], byIndex[1]) << threads;
  }
  omp_set_num_threads(saved);
}

TEST(FastPaths, ThreadBlockTakesAFittingSplitElseEqualBlocks) {
  const std::vector<std::size_t> split{0, 7, 10};
  EXPECT_EQ(gf::threadBlock(10, 0, 2, &split), (std::pair<std::int64_t, std::int64_t>{0, 7}));
  EXPECT_EQ(gf::threadBlock(10, 1, 2, &split), (std::pair<std::int64_t, std::int64_t>{7, 10}));
  // not a split of these particles for this team: equal blocks (schedule(static))
  EXPECT_EQ(gf::threadBlock(11, 0, 2, &split), (std::pair<std::int64_t, std::int64_t>{0, 6}));
  EXPECT_EQ(gf::threadBlock(10, 1, 3, &split), (std::pair<std::int64_t, std::int64_t>{4, 7}));
  EXPECT_EQ(gf::threadBlock(10, 2, 3, nullptr), (std::pair<std::int64_t, std::int64_t>{7, 10}));
}

TEST(FastPaths, SumsAndDepositsFollowTheGivenParticleSplit) {
  // A split like the DEM's (uneven blocks): every particle summed and deposited once, on the
  // thread whose block holds it; the results equal the equal-block ones up to round-off.
  const CartesianGrid g = makeGrid({2, 4, 5}, {0.0075, 0.005, 0.005});
  const dem::ParticleSet particles = randomParticles(6000, 0.00125, 0.00125, {0, 0, 0}, {0.015, 0.02, 0.025}, 37);
  const auto scheme = makeScheme("divided");
  const GridTopology t(g, {true, false, false});
  ParticleStencils s;
  scheme->buildStencils(particles, t, s);
  const std::size_t cells = Field(g).data().size();
  const auto n = static_cast<std::int64_t>(s.size());
  const int saved = omp_get_max_threads();
  omp_set_num_threads(2);
  const std::vector<std::size_t> split{0, 4500, 6000};
  std::vector<int> seenBy(s.size(), -1);
  const auto sums = sumsOverRanges<1>(
      n,
      [&](std::int64_t begin, std::int64_t end, std::array<double, 1>& sum) {
        for (std::int64_t p = begin; p < end; ++p) {
          seenBy[p] = omp_get_thread_num();
          sum[0] += particles.radius[p];
        }
      },
      &split);
  if (omp_get_max_threads() == 2) {
    EXPECT_EQ(seenBy[4499], 0);
    EXPECT_EQ(seenBy[4500], 1);
  }
  double expected = 0.0;
  for (double r : particles.radius) expected += r;
  EXPECT_NEAR(sums[0], expected, 1e-12 * expected);
  auto deposit = [&](const std::vector<std::size_t>* blocks, std::vector<int>* seen) {
    DepositBuffers b;
    b.blocks = blocks;
    return depositChannels<1>(
        s, cells, b, [&](std::size_t p, double (&v)[1]) { v[0] = particles.radius[p]; },
        [&](int thread, std::size_t begin, std::size_t end) {
          if (seen)
            for (std::size_t p = begin; p < end; ++p) (*seen)[p] = thread;
          return StencilPiece::of(s, begin);
        });
  };
  std::vector<int> depositedBy(s.size(), -1);
  const std::vector<double> bySplit = deposit(&split, &depositedBy);
  const std::vector<double> byEqual = deposit(nullptr, nullptr);
  omp_set_num_threads(saved);
  for (int who : depositedBy) ASSERT_GE(who, 0);
  if (saved >= 2) {
    EXPECT_EQ(depositedBy[4499], depositedBy[0]);
  }
  double total = 0.0;
  for (std::size_t q = 0; q < cells; ++q) {
    EXPECT_NEAR(bySplit[q], byEqual[q], 1e-15) << q;
    total += bySplit[q];
  }
  EXPECT_NEAR(total, expected, 1e-12 * expected);  // the weights of a particle add up to 1
}

TEST(FastPaths, ReusedDepositBuffersGiveTheBitsOfFreshOnes) {
  // The per-thread buffers stay zero between deposits (each thread zeroes the cells it touched,
  // the merge reads a buffer only there): one DepositBuffers used for deposits of 5, 1 and 8
  // channels over particle sets in other parts of the grid, and over splits where a thread has
  // all or none of the particles, gives each time the bits of a deposit with new buffers.
  const CartesianGrid g = makeGrid({2, 6, 8}, {0.0075, 0.005, 0.005});
  const auto scheme = makeScheme("divided");
  const GridTopology t(g, {true, false, false});
  const std::size_t cells = Field(g).data().size();
  const int saved = omp_get_max_threads();
  omp_set_num_threads(std::max(2, saved));
  DepositBuffers reused;
  for (const auto& d : reused.perThread) ASSERT_TRUE(d.empty());
  auto check = [&]<int C>(const dem::ParticleSet& particles, const std::vector<std::size_t>* split, int round) {
    ParticleStencils s;
    scheme->buildStencils(particles, t, s);
    auto value = [&](std::size_t p, double (&v)[C]) {
      for (int ch = 0; ch < C; ++ch) v[ch] = (ch % 2 == 0 ? 1.0 : -1.0) * particles.radius[p] * (1.0 + ch + p % 7);
    };
    reused.blocks = split;
    const std::vector<double> again = depositChannels<C>(s, cells, reused, value);
    DepositBuffers fresh;
    fresh.blocks = split;
    const std::vector<double> first = depositChannels<C>(s, cells, fresh, value);
    ASSERT_EQ(again.size(), first.size());
    for (std::size_t q = 0; q < first.size(); ++q) ASSERT_EQ(again[q], first[q]) << round << " " << q;
    for (const auto& buffer : reused.perThread)
      for (double v : buffer) ASSERT_EQ(v, 0.0) << round;  // zero again after the deposit
  };
  const dem::ParticleSet low = randomParticles(5000, 0.00125, 0.00125, {0, 0, 0}, {0.015, 0.03, 0.015}, 41);
  const dem::ParticleSet high = randomParticles(6000, 0.00125, 0.00125, {0, 0, 0.02}, {0.015, 0.03, 0.04}, 43);
  const std::vector<std::size_t> allOnFirst{0, 6000, 6000}, allOnSecond{0, 0, 6000};
  check.template operator()<5>(low, nullptr, 0);
  check.template operator()<1>(high, nullptr, 1);
  check.template operator()<8>(high, &allOnFirst, 2);
  check.template operator()<5>(high, &allOnSecond, 3);
  check.template operator()<1>(low, nullptr, 4);
  omp_set_num_threads(saved);
}

TEST(FastPaths, ViscousStressDivergenceIsTheSevenPointLaplacianBitForBit) {
  // computeViscousStressDivergence (rows, components side by side in one vector) against the
  // definition cell by cell: mu sum_a (u_hi - 2 u_c + u_lo) / h_a^2, the neighbour across a wall
  // the cell itself, across a periodic boundary the wrapped cell
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::array<int, 3>& cells : {std::array<int, 3>{2, 5, 6}, {1, 4, 3}, {4, 3, 5}}) {
    const CartesianGrid g = makeGrid(cells, {0.0075, 0.005, 0.004});
    for (const auto& periodic : kPeriodicities) {
      const GridTopology t(g, periodic);
      Field velocity[3] = {Field(g), Field(g), Field(g)}, divTau[3] = {Field(g), Field(g), Field(g)};
      for (auto& f : velocity)
        for (double& v : f.data()) v = u(rng) * std::exp(5.0 * u(rng));
      const Field* in[3] = {&velocity[0], &velocity[1], &velocity[2]};
      const double mu = 1.8e-5;
      computeViscousStressDivergence(t, in, mu, divTau);
      for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
          for (int i = 0; i < cells[0]; ++i) {
            const int idx[3] = {i, j, k};
            for (int c = 0; c < 3; ++c) {
              double lap = 0.0;
              for (int a = 0; a < 3; ++a) {
                int lo[3] = {i, j, k}, hi[3] = {i, j, k};
                lo[a] = periodic[a] ? t.mapIndex(idx[a] - 1, a) : std::max(idx[a] - 1, 0);
                hi[a] = periodic[a] ? t.mapIndex(idx[a] + 1, a) : std::min(idx[a] + 1, cells[a] - 1);
                const double h = g.spacing[a];
                lap += (velocity[c](hi[0], hi[1], hi[2]) - 2.0 * velocity[c](i, j, k) + velocity[c](lo[0], lo[1], lo[2])) /
                       (h * h);
              }
              ASSERT_EQ(divTau[c](i, j, k), mu * lap) << i << " " << j << " " << k << " component " << c;
            }
          }
    }
  }
}

TEST(FastPaths, GidaspowBlockEqualsTheLawValueByValue) {
  // the force pass evaluates the law block-wise (Ergun in vector registers, Wen-Yu where eps >= 0.8)
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {1, 7, 8, 9, 31, 32}) {
    std::vector<double> re(n), eps(n), block(n);
    for (int i = 0; i < n; ++i) {
      re[i] = std::exp(12.0 * u(rng) - 6.0);                                          // 0.0025 .. 400
      eps[i] = i % 4 == 0 ? 0.8 : i % 4 == 1 ? std::nextafter(0.8, 0.0) : 0.3 + 0.7 * u(rng);  // both branches, the switch
    }
    correctionsOf(StaticCorrection<&drag::gidaspow>{}, re.data(), eps.data(), block.data(), n);
    for (int i = 0; i < n; ++i) ASSERT_EQ(block[i], drag::gidaspow(re[i], eps[i])) << "re " << re[i] << " eps " << eps[i];
  }
}

TEST(FastPaths, MaxRadiusIsTheLargestRadius) {
  // eight running maxima side by side: the serial maximum whatever the position of the largest
  for (int n : {0, 1, 7, 8, 9, 100, 1001}) {
    dem::ParticleSet particles = n ? randomParticles(n, 0.001, 0.002, {0, 0, 0}, {0.1, 0.1, 0.1}, 31 + n) : dem::ParticleSet{};
    for (int largest = 0; largest < std::min(n, 17); ++largest) {
      std::vector<double> radius = particles.radius;
      radius[largest] = 0.003;
      dem::ParticleSet set = particles;
      set.radius = radius;
      double serial = 0.0;
      for (double r : radius) serial = std::max(serial, r);
      ASSERT_EQ(maxRadius(set), serial) << n << " " << largest;
    }
    if (n == 0) {
      EXPECT_EQ(maxRadius(particles), 0.0);
    }
  }
}

TEST(FastPaths, FluidViewGhostsAreNeverRead) {
  // The time loop lends the coupling cell velocity and pressure gradient without ghost fills
  // (Simulation::fluidView, fluid::CellGhosts::Left): every scheme, interpolation and force must
  // read interior cells only, at walls and across periodic sides. Ghosts full of NaN give the
  // bits of ghosts holding finite values.
  const CartesianGrid g = makeGrid({3, 4, 5}, {0.01, 0.01, 0.01});
  const dem::ParticleSet base = randomParticles(400, 0.001, 0.002, {-0.001, 0, 0}, {0.031, 0.04, 0.05}, 31);
  FluidFields clean(g);
  clean.setVelocity(g, [](const Vec3& x) { return Vec3{std::sin(60 * x.y), 0.3 * x.x + x.z, 1.0 + std::cos(50 * x.x)}; });
  clean.setPressureGradient(g, [](const Vec3& x) { return Vec3{5.0 * x.y, 10 * x.z, -9810.0 + 100 * x.y}; });
  FluidFields poisoned = clean;
  for (int a = 0; a < 3; ++a)
    for (Field* f : {&poisoned.u[a], &poisoned.gradP[a]})
      for (int k = -g.ghosts; k < g.cells[2] + g.ghosts; ++k)
        for (int j = -g.ghosts; j < g.cells[1] + g.ghosts; ++j)
          for (int i = -g.ghosts; i < g.cells[0] + g.ghosts; ++i) {
            const bool interior = i >= 0 && i < g.cells[0] && j >= 0 && j < g.cells[1] && k >= 0 && k < g.cells[2];
            if (!interior) (*f)(i, j, k) = std::nan("");
          }
  const std::string forces =
      "  forces:\n    virtual_mass: true\n    saffman_mei_lift: true\n    magnus_lift: true\n    fluid_torque: true\n";
  for (const char* scheme : {"pcm", "divided", "kernel", "big_particle"})
    for (const char* interpolation : {"cell", "trilinear", "stencil"})
      for (const auto& periodic : kPeriodicities) {
        std::vector<Vec3> force[2], torque[2];
        std::vector<double> density[2];
        int v = 0;
        for (const FluidFields* fluid : {&clean, &poisoned}) {
          auto c = makeCoupler(std::string("  drag_law: gidaspow\n  void_fraction: ") + scheme +
                                   "\n  interpolation: " + interpolation + "\n" + forces,
                               g, periodic);
          dem::ParticleSet particles = base;
          CouplingFields fields(g);
          c->computeVoidFraction(particles, fields);
          c->computeParticleForces(fluid->view(1.2, 1.8e-5, 2e-5), fields, particles);
          c->fillFluidSources(fields);
          force[v] = particles.externalForce;
          torque[v] = particles.externalTorque;
          density[v] = fields.forceDensity[2].data();
          ++v;
        }
        const std::string where = std::string(scheme) + ", " + interpolation + ", periodic " +
                                  std::to_string(periodic[0]) + std::to_string(periodic[1]) +
                                  std::to_string(periodic[2]);
        for (const Vec3& f : force[1]) ASSERT_TRUE(std::isfinite(f.x + f.y + f.z)) << where;
        EXPECT_EQ(force[0], force[1]) << where;
        EXPECT_EQ(torque[0], torque[1]) << where;
        EXPECT_EQ(density[0], density[1]) << where;
      }
}

TEST(FastPaths, DepositFromOnePieceBuffersEqualsTheDepositOverKeptStencils) {
  // The Coupler's fused deposit builds each piece of divided stencils into its thread's buffer
  // (nothing keeps them): the same sums, bit for bit, as over the whole stencil set, on 1 thread
  // and on the threads at hand, in the pairwise and the wide form.
  const CartesianGrid g = makeGrid({3, 5, 6}, {0.01, 0.01, 0.01});
  const dem::ParticleSet particles = randomParticles(9000, 0.001, 0.0015, {0, 0, 0}, {0.03, 0.05, 0.06}, 41);
  const auto scheme = makeScheme("divided");
  const GridTopology t(g, {false, false, true});
  ParticleStencils whole;
  scheme->buildStencils(particles, t, whole);
  const std::size_t cells = Field(g).data().size();
  auto value = [&](std::size_t p, double (&v)[5]) {
    for (int ch = 0; ch < 5; ++ch) v[ch] = particles.position[p][ch % 3] * (ch + 1) - 0.01 * ch;
  };
  const int saved = omp_get_max_threads();
  for (int threads : {1, saved}) {
    omp_set_num_threads(threads);
    for (bool wide : {false, true}) {
      allowWideDeposit(wide);
      DepositBuffers kept, transient;
      const std::vector<double> expected = depositChannels<5>(whole, cells, kept, value);
      ParticleStencils sized;
      ASSERT_TRUE(scheme->beginStencils(particles, t, sized));
      std::vector<ParticleStencils> buffers(static_cast<std::size_t>(threads));
      for (ParticleStencils& b : buffers) b.resize(static_cast<std::size_t>(kDepositPiece), sized.capacity);
      const std::vector<double> sums =
          depositChannels<5>(sized, cells, transient, value, [&](int thread, std::size_t begin, std::size_t end) {
            ParticleStencils& b = buffers[static_cast<std::size_t>(thread)];
            scheme->buildStencilRange(particles, t, b, begin, end, 0);
            return StencilPiece::of(b, 0);
          });
      for (const auto& run : kept.runs.empty() ? std::vector<std::array<std::size_t, 2>>{{0, cells}} : kept.runs)
        for (std::size_t q = run[0] * 5; q < (run[0] + run[1]) * 5; ++q)
          ASSERT_EQ(sums[q], expected[q]) << "threads " << threads << ", wide " << wide << ", entry " << q;
    }
  }
  allowWideDeposit(true);
  omp_set_num_threads(saved);
}
