// Phase-fraction transport (src/vof): boundedness, conservation, sum of the fractions, order of
// accuracy, interface compression, walls, a split into two boxes, and the mixture properties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "core/domain.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/halo.hpp"
#include "vof/vof.hpp"

namespace {

using gf::CartesianGrid;
using gf::Field;
using gf::Staggering;
namespace vof = gf::vof;
constexpr double kPi = std::numbers::pi;

CartesianGrid makeGrid(int nx, int ny, double lx = 1.0, double ly = 1.0) {
  CartesianGrid g;
  g.cells = {nx, ny, 1};
  g.spacing = {lx / nx, ly / ny, lx / nx};
  g.ghosts = 2;
  return g;
}

/// Superficial face velocities from a stream function psi(x, y) at the cell corners (2D), plus a
/// uniform translation (u0, v0): the discrete divergence vanishes to round-off. Every point of the
/// face fields is set, ghosts included (psi is evaluated at any index).
struct Fluxes {
  Field u, v, w;
  std::array<const Field*, 3> ptr() const { return {&u, &v, &w}; }
};
Fluxes streamFluxes(const CartesianGrid& g, const std::function<double(double, double)>& psi, double u0, double v0) {
  Fluxes f{Field(g, Staggering::FaceX), Field(g, Staggering::FaceY), Field(g, Staggering::FaceZ)};
  const int G = g.ghosts;
  const double hx = g.spacing.x, hy = g.spacing.y;
  for (int k = -G; k < 1 + G; ++k)
    for (int j = -G; j < g.cells[1] + 1 + G; ++j)
      for (int i = -G; i < g.cells[0] + 1 + G; ++i) {
        const double x = g.origin.x + i * hx, y = g.origin.y + j * hy;
        if (j < g.cells[1] + G) f.u(i, j, k) = u0 + (psi(x, y + hy) - psi(x, y)) / hy;
        if (i < g.cells[0] + G) f.v(i, j, k) = v0 - (psi(x + hx, y) - psi(x, y)) / hx;
      }
  return f;
}

std::vector<Field> phases(const CartesianGrid& g, int n) { return std::vector<Field>(static_cast<std::size_t>(n), Field(g)); }

double timeStepFor(const Field& eps, const Fluxes& f, double courant) {
  return courant / vof::maxCourant(eps, f.ptr(), 1.0);
}

/// Two phases in 1D: alpha_0 = profile(x), uniform velocity 1 in a periodic unit interval, moved by
/// one period at Courant 0.5; returns the L1 error over the cells where `weight` is true.
double translateOnePeriod(int n, const std::function<double(double)>& profile, const vof::TransportSettings& s,
                          const std::function<bool(double)>& weight, std::vector<double>* finalAlpha = nullptr) {
  const CartesianGrid g = makeGrid(n, 1, 1.0, 1.0 / n);
  Fluxes f = streamFluxes(g, [](double, double) { return 0.0; }, 1.0, 0.0);
  Field eps(g, Staggering::Cell, 1.0);
  auto alpha = phases(g, 2);
  for (int i = 0; i < n; ++i) {
    alpha[0](i, 0, 0) = profile(g.cellCentre(i, 0, 0).x);
    alpha[1](i, 0, 0) = 1.0 - alpha[0](i, 0, 0);
  }
  const auto sides = vof::Sides::allPeriodic();
  vof::PhaseTransport work(g, 2);
  const double dt = 0.5 * g.spacing.x;
  for (int step = 0; step < 2 * n; ++step) vof::advance(work, alpha, eps, f.ptr(), dt, sides, s, vof::singleBoxFill(sides));
  double err = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = g.cellCentre(i, 0, 0).x;
    if (weight(x)) err += std::abs(alpha[0](i, 0, 0) - profile(x)) * g.spacing.x;
    if (finalAlpha) finalAlpha->push_back(alpha[0](i, 0, 0));
  }
  return err;
}

double step(double x) { return (x >= 0.25 && x < 0.75) ? 1.0 : 0.0; }

}  // namespace

TEST(VofTransport, ThreePhasesStayBoundedConservedAndSumToOneInARotatingTranslatingFlow) {
  const CartesianGrid g = makeGrid(64, 64);
  // a vortex (stream function sin^2(pi x) sin^2(pi y) / pi) carried by a uniform translation
  Fluxes f = streamFluxes(g, [](double x, double y) { return std::pow(std::sin(kPi * x) * std::sin(kPi * y), 2) / kPi; }, 0.5, 0.25);
  Field eps(g, Staggering::Cell, 1.0);  // a steady bed (eps 0.6 at its centre) that the flow crosses
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const auto c = g.cellCentre(i, j, 0);
      eps(i, j, 0) = 1.0 - 0.4 * std::exp(-(std::pow(c.x - 0.5, 2) + std::pow(c.y - 0.3, 2)) / 0.02);
    }
  const auto sides = vof::Sides::allPeriodic();
  vof::fillCellGhosts(eps, sides);
  auto alpha = phases(g, 3);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const auto c = g.cellCentre(i, j, 0);
      const bool disc = std::hypot(c.x - 0.4, c.y - 0.5) < 0.2;
      const bool block = !disc && c.x > 0.5 && c.x < 0.8 && c.y > 0.3 && c.y < 0.7;  // touches the disc: triple points
      alpha[1](i, j, 0) = disc ? 1.0 : 0.0;
      alpha[2](i, j, 0) = block ? 1.0 : 0.0;
      alpha[0](i, j, 0) = 1.0 - alpha[1](i, j, 0) - alpha[2](i, j, 0);
    }
  double v0[3];
  for (int i = 0; i < 3; ++i) v0[i] = vof::phaseVolume(alpha[static_cast<std::size_t>(i)], eps);
  const double dt = timeStepFor(eps, f, 0.5);
  vof::PhaseTransport work(g, 3);
  double worstBound = 0.0, worstVolume = 0.0, worstSum = 0.0;
  for (int s = 0; s < 200; ++s) {
    vof::advance(work, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
    for (int i = 0; i < 3; ++i) {
      const auto r = vof::fractionRange(alpha[static_cast<std::size_t>(i)]);
      worstBound = std::max({worstBound, -r[0], r[1] - 1.0});
      worstVolume = std::max(worstVolume, std::abs(vof::phaseVolume(alpha[static_cast<std::size_t>(i)], eps) / v0[i] - 1.0));
    }
    worstSum = std::max(worstSum, vof::maxSumError(alpha));
  }
  std::printf("[ figures  ] 3 phases, 64 x 64, 200 steps at Courant 0.5: worst bound excess %.2e, volume error %.2e, "
              "|sum - 1| %.2e\n", worstBound, worstVolume, worstSum);
  EXPECT_LE(worstBound, 1e-12);
  EXPECT_LE(worstVolume, 1e-12);
  EXPECT_LE(worstSum, 1e-12);
}

TEST(VofTransport, WallsKeepEveryPhaseInsideTheBox) {
  const CartesianGrid g = makeGrid(48, 48);
  // the vortex alone: its normal velocity vanishes on the walls x, y = 0, 1
  Fluxes f = streamFluxes(g, [](double x, double y) { return std::pow(std::sin(kPi * x) * std::sin(kPi * y), 2) / kPi; }, 0.0, 0.0);
  vof::Sides sides;  // walls in x and y, periodic in z (2D)
  sides.side[4] = sides.side[5] = vof::SideType::Periodic;
  Field eps(g, Staggering::Cell, 1.0);
  auto alpha = phases(g, 3);
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 48; ++i) {
      const auto c = g.cellCentre(i, j, 0);
      alpha[1](i, j, 0) = c.y < 0.3 ? 1.0 : 0.0;                       // a layer on the floor
      alpha[2](i, j, 0) = (c.y >= 0.3 && c.y < 0.55) ? 1.0 : 0.0;      // a layer above it
      alpha[0](i, j, 0) = 1.0 - alpha[1](i, j, 0) - alpha[2](i, j, 0);  // the rest above
    }
  double v0[3];
  for (int i = 0; i < 3; ++i) v0[i] = vof::phaseVolume(alpha[static_cast<std::size_t>(i)], eps);
  const double dt = timeStepFor(eps, f, 0.5);
  vof::PhaseTransport work(g, 3);
  for (int s = 0; s < 150; ++s) vof::advance(work, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
  for (int i = 0; i < 3; ++i) {
    const auto r = vof::fractionRange(alpha[static_cast<std::size_t>(i)]);
    EXPECT_GE(r[0], -1e-12);
    EXPECT_LE(r[1], 1.0 + 1e-12);
    EXPECT_NEAR(vof::phaseVolume(alpha[static_cast<std::size_t>(i)], eps) / v0[i], 1.0, 1e-12);
  }
  EXPECT_LE(vof::maxSumError(alpha), 1e-12);
}

TEST(VofTransport, SmoothProfileConvergesAtSecondOrderAwayFromExtrema) {
  auto profile = [](double x) { return 0.5 + 0.4 * std::sin(2.0 * kPi * x); };
  auto awayFromExtrema = [](double x) { return std::abs(std::cos(2.0 * kPi * x)) > 0.5; };
  vof::TransportSettings s;
  s.compression = 0.0;
  std::vector<double> err;
  for (int n : {32, 64, 128, 256}) err.push_back(translateOnePeriod(n, profile, s, awayFromExtrema));
  for (std::size_t m = 1; m < err.size(); ++m)
    std::printf("[ figures  ] smooth profile, L1 error away from extrema: n = %d: %.3e, observed order %.2f\n",
                32 << m, err[m], std::log2(err[m - 1] / err[m]));
  EXPECT_GE(std::log2(err[2] / err[3]), 1.8);
  EXPECT_GE(std::log2(err[1] / err[2]), 1.8);
}

TEST(VofTransport, DiscontinuityL1OrderWithAndWithoutCompression) {
  auto all = [](double) { return true; };
  vof::TransportSettings plain, compressed;
  plain.compression = 0.0;
  std::vector<double> e0, e1;
  for (int n : {50, 100, 200, 400}) {
    e0.push_back(translateOnePeriod(n, step, plain, all));
    e1.push_back(translateOnePeriod(n, step, compressed, all));
  }
  for (std::size_t m = 1; m < e0.size(); ++m)
    std::printf("[ figures  ] step, L1 error: n = %d: FCT %.3e (order %.2f), FCT + compression %.3e (order %.2f)\n",
                50 << m, e0[m], std::log2(e0[m - 1] / e0[m]), e1[m], std::log2(e1[m - 1] / e1[m]));
  EXPECT_GE(std::log2(e0[2] / e0[3]), 0.6);  // a smeared discontinuity: h^(2/3) for second-order schemes
  EXPECT_GE(std::log2(e1[2] / e1[3]), 0.9);  // a front of fixed width in cells: first order
}

TEST(VofTransport, CompressionKeepsTheInterfaceWithinThreeCellsOverOneDomainLength) {
  auto all = [](double) { return true; };
  auto smeared = [](const std::vector<double>& a) {
    int cells = 0;
    for (double v : a) cells += (v > 0.01 && v < 0.99) ? 1 : 0;
    return cells / 2.0;  // two interfaces
  };
  vof::TransportSettings plain, compressed;
  plain.compression = 0.0;
  std::vector<double> a0, a1;
  translateOnePeriod(100, step, plain, all, &a0);
  translateOnePeriod(100, step, compressed, all, &a1);
  std::printf("[ figures  ] cells per interface with 0.01 < alpha < 0.99 after one domain length (100 cells): "
              "compression off %.1f, on %.1f\n", smeared(a0), smeared(a1));
  EXPECT_LE(smeared(a1), 3.0);
  EXPECT_GT(smeared(a0), smeared(a1));
}

TEST(VofTransport, TwoBoxesGiveTheBitsOfTheWholeGrid) {
  const CartesianGrid whole = makeGrid(32, 16);
  const auto sides = vof::Sides::allPeriodic();
  Fluxes f = streamFluxes(whole, [](double x, double y) { return std::pow(std::sin(kPi * x) * std::sin(kPi * y), 2) / kPi; }, 0.3, 0.1);
  Field eps(whole, Staggering::Cell, 1.0);
  auto alpha = phases(whole, 3);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 32; ++i) {
      const auto c = whole.cellCentre(i, j, 0);
      alpha[1](i, j, 0) = std::hypot(c.x - 0.45, c.y - 0.5) < 0.25 ? 1.0 : 0.0;
      alpha[2](i, j, 0) = (alpha[1](i, j, 0) == 0.0 && c.x > 0.55 && c.x < 0.85) ? 1.0 : 0.0;
      alpha[0](i, j, 0) = 1.0 - alpha[1](i, j, 0) - alpha[2](i, j, 0);
    }
  vof::fillCellGhosts(eps, sides);

  gf::Domain domain;
  domain.min = {0, 0, 0};
  domain.max = {1, 1, 1.0 / 32};
  domain.periodic = {true, true, true};
  std::vector<gf::parallel::Decomposition> d;
  std::vector<CartesianGrid> boxGrid;
  vof::Sides boxSides = sides;
  boxSides.side[0] = boxSides.side[1] = vof::SideType::Shared;
  for (int r = 0; r < 2; ++r) {
    d.emplace_back(domain, gf::parallel::Layout{2, 1, 1}, 2, r, std::array<int, 3>{32, 16, 1});
    CartesianGrid b = whole;
    b.cells = d.back().cellCount();
    b.origin.x = d.back().cellOffset()[0] * whole.spacing.x;
    boxGrid.push_back(b);
  }
  // the boxes' copies of the inputs, and a ghost exchange through the whole grid's field
  auto extract = [&](const Field& w, int r) {
    Field local(boxGrid[static_cast<std::size_t>(r)], w.staggering());
    gf::parallel::extractBox(w, d[static_cast<std::size_t>(r)], local);
    return local;
  };
  auto exchange = [&](std::vector<std::vector<Field*>> perBox) {  // perBox[r][m]: field m of box r
    for (std::size_t m = 0; m < perBox[0].size(); ++m) {
      Field w(whole);
      for (int r = 0; r < 2; ++r) {
        const Field& local = *perBox[static_cast<std::size_t>(r)][m];
        const int off = d[static_cast<std::size_t>(r)].cellOffset()[0];
        for (int j = 0; j < 16; ++j)
          for (int i = 0; i < local.grid().cells[0]; ++i) w(i + off, j, 0) = local(i, j, 0);
      }
      vof::fillCellGhosts(w, sides);
      for (int r = 0; r < 2; ++r) gf::parallel::extractBox(w, d[static_cast<std::size_t>(r)], *perBox[static_cast<std::size_t>(r)][m]);
    }
  };
  std::vector<std::vector<Field>> boxAlpha(2);
  std::vector<Fluxes> boxFlux;
  std::vector<Field> boxEps;
  std::vector<vof::PhaseTransport> work;
  for (int r = 0; r < 2; ++r) {
    for (auto& a : alpha) boxAlpha[static_cast<std::size_t>(r)].push_back(extract(a, r));
    boxFlux.push_back(Fluxes{extract(f.u, r), extract(f.v, r), extract(f.w, r)});
    boxEps.push_back(extract(eps, r));
    work.emplace_back(boxGrid[static_cast<std::size_t>(r)], 3);
  }
  const double dt = timeStepFor(eps, f, 0.5);
  vof::PhaseTransport wholeWork(whole, 3);
  auto alphaPtrs = [&](int r) {
    std::vector<Field*> p;
    for (auto& a : boxAlpha[static_cast<std::size_t>(r)]) p.push_back(&a);
    return p;
  };
  for (int s = 0; s < 30; ++s) {
    vof::advance(wholeWork, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
    exchange({alphaPtrs(0), alphaPtrs(1)});
    for (int r = 0; r < 2; ++r)
      work[static_cast<std::size_t>(r)].computeFluxes(boxAlpha[static_cast<std::size_t>(r)], boxEps[static_cast<std::size_t>(r)],
                                                      boxFlux[static_cast<std::size_t>(r)].ptr(), dt, boxSides, {});
    exchange({work[0].limiterFields(), work[1].limiterFields()});
    for (int r = 0; r < 2; ++r) work[static_cast<std::size_t>(r)].applyLimitedFluxes(boxAlpha[static_cast<std::size_t>(r)]);
  }
  double worst = 0.0;
  for (int r = 0; r < 2; ++r) {
    const int off = d[static_cast<std::size_t>(r)].cellOffset()[0];
    for (int p = 0; p < 3; ++p)
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < boxGrid[static_cast<std::size_t>(r)].cells[0]; ++i)
          worst = std::max(worst, std::abs(boxAlpha[static_cast<std::size_t>(r)][static_cast<std::size_t>(p)](i, j, 0) -
                                           alpha[static_cast<std::size_t>(p)](i + off, j, 0)));
  }
  EXPECT_EQ(worst, 0.0);
}

TEST(VofMixture, VolumeWeightedDensityAndViscosity) {
  // seed 002 eqs. 3-4: air, slag, iron
  const double rho[3] = {1.0, 2800.0, 7000.0}, mu[3] = {1.8e-5, 0.5, 6e-3};
  const double a[3] = {0.2, 0.3, 0.5};
  EXPECT_DOUBLE_EQ(vof::mixtureValue(a, rho, 3), 0.2 * 1.0 + 0.3 * 2800.0 + 0.5 * 7000.0);
  EXPECT_DOUBLE_EQ(vof::mixtureValue(a, mu, 3), 0.2 * 1.8e-5 + 0.3 * 0.5 + 0.5 * 6e-3);
  const CartesianGrid g = makeGrid(4, 4);
  auto alpha = phases(g, 3);
  for (int p = 0; p < 3; ++p) alpha[static_cast<std::size_t>(p)].fill(a[p]);
  Field out(g);
  vof::mixtureField(alpha, {rho[0], rho[1], rho[2]}, out);
  EXPECT_DOUBLE_EQ(out(2, 3, 0), vof::mixtureValue(a, rho, 3));
  EXPECT_DOUBLE_EQ(out(-2, -2, 0), vof::mixtureValue(a, rho, 3));  // ghosts as well
}

TEST(VofTransport, ZalesakSlottedDiskKeepsItsShapeOverOneRevolution) {
  // Zalesak (1979): a disk of radius 0.15 at (0.5, 0.75) with a slot 0.05 wide and 0.25 deep,
  // rotated once about the centre of the unit square (u = -omega (y - 0.5), v = omega (x - 0.5):
  // periodic, divergence-free face by face); 80 x 80 cells, slot 4 cells wide.
  const int n = 80;
  const CartesianGrid g = makeGrid(n, n);
  const double omega = 2.0 * kPi;
  Fluxes f = streamFluxes(g, [&](double x, double y) { return -0.5 * omega * (std::pow(x - 0.5, 2) + std::pow(y - 0.5, 2)); }, 0.0, 0.0);
  Field eps(g, Staggering::Cell, 1.0);
  const auto sides = vof::Sides::allPeriodic();
  auto alpha = phases(g, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto c = g.cellCentre(i, j, 0);
      const bool disk = std::hypot(c.x - 0.5, c.y - 0.75) < 0.15 && !(std::abs(c.x - 0.5) < 0.025 && c.y < 0.85);
      alpha[1](i, j, 0) = disk ? 1.0 : 0.0;
      alpha[0](i, j, 0) = 1.0 - alpha[1](i, j, 0);
    }
  const std::vector<double> initial = alpha[1].data();
  const double h2 = g.spacing.x * g.spacing.y;
  double area0 = 0.0, sharpArea0 = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      area0 += alpha[1](i, j, 0) * h2;
      sharpArea0 += alpha[1](i, j, 0) >= 0.5 ? h2 : 0.0;
    }
  const int steps = static_cast<int>(std::ceil(1.0 / timeStepFor(eps, f, 0.8)));
  const double dt = 1.0 / steps;
  vof::PhaseTransport work(g, 2);
  const auto plainStart = alpha;
  for (int s = 0; s < steps; ++s) vof::advance(work, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
  // the same without compression, for comparison
  auto plain = plainStart;
  vof::TransportSettings noCompression;
  noCompression.compression = 0.0;
  for (int s = 0; s < steps; ++s) vof::advance(work, plain, eps, f.ptr(), dt, sides, noCompression, vof::singleBoxFill(sides));
  double area = 0.0, sharpArea = 0.0, shapeError = 0.0, plainError = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = alpha[1](i, j, 0);
      area += a * h2;
      sharpArea += a >= 0.5 ? h2 : 0.0;
      shapeError += std::abs(a - initial[alpha[1].index(i, j, 0)]) * h2;
      plainError += std::abs(plain[1](i, j, 0) - initial[alpha[1].index(i, j, 0)]) * h2;
    }
  const auto r = vof::fractionRange(alpha[1]);
  std::printf("[ figures  ] slotted disk, %d x %d, %d steps: volume error %.2e, area of alpha >= 0.5 %+.2f %%, "
              "L1 shape error / area %.3f (without compression %.3f), range [%.2e, 1 %+.2e]\n", n, n, steps,
              area / area0 - 1.0, 100.0 * (sharpArea / sharpArea0 - 1.0), shapeError / area0, plainError / area0, r[0],
              r[1] - 1.0);
  EXPECT_NEAR(area / area0, 1.0, 1e-12);
  EXPECT_NEAR(sharpArea / sharpArea0, 1.0, 0.03);
  // about 1.3 cells of smearing all along the perimeter (0.41 measured; the disk keeps its slot)
  EXPECT_LE(shapeError / area0, 0.45);
  EXPECT_LT(shapeError, 0.7 * plainError);
  EXPECT_GE(r[0], -1e-12);
  EXPECT_LE(r[1], 1.0 + 1e-12);
}

TEST(VofTransport, ChangingVoidFractionKeepsAUniformMixtureUniformAndConservesEachPhase) {
  // A bed that fills and empties: a divergent superficial flux phi(x) changes eps by seed 002
  // eq. 5, eps_new = eps - dt dphi/dx. A uniform mixture must stay uniform (no fractions made by
  // the bed), and a layered one keeps each phase's eps alpha_i V.
  const int n = 64;
  const CartesianGrid g = makeGrid(n, 1, 1.0, 1.0 / n);
  Fluxes f = streamFluxes(g, [](double, double) { return 0.0; }, 0.0, 0.0);
  for (int i = -2; i < n + 3; ++i) f.u(i, 0, 0) = 0.3 + 0.1 * std::sin(2.0 * kPi * i / n);
  const auto sides = vof::Sides::allPeriodic();
  Field eps(g, Staggering::Cell, 0.8);
  auto uniform = phases(g, 3), layered = phases(g, 3);
  for (int i = 0; i < n; ++i) {
    const double x = g.cellCentre(i, 0, 0).x;
    uniform[0](i, 0, 0) = 0.2, uniform[1](i, 0, 0) = 0.3, uniform[2](i, 0, 0) = 0.5;
    layered[1](i, 0, 0) = x < 0.3 ? 1.0 : 0.0;
    layered[2](i, 0, 0) = x >= 0.3 && x < 0.6 ? 1.0 : 0.0;
    layered[0](i, 0, 0) = 1.0 - layered[1](i, 0, 0) - layered[2](i, 0, 0);
  }
  double v0[3];
  for (int p = 0; p < 3; ++p) v0[p] = vof::phaseVolume(layered[static_cast<std::size_t>(p)], eps);
  const double dt = 0.5 * g.spacing.x;  // outflow Courant <= 1/3 while eps >= 0.6
  vof::PhaseTransport work(g, 3), workUniform(g, 3);
  double uniformError = 0.0, epsMin = 1.0, epsMax = 0.0;
  for (int s = 0; s < 40; ++s) {
    vof::fillCellGhosts(eps, sides);
    vof::advance(workUniform, uniform, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
    vof::advance(work, layered, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
    Field next(g);
    for (int i = 0; i < n; ++i) {
      next(i, 0, 0) = eps(i, 0, 0) - dt * (f.u(i + 1, 0, 0) - f.u(i, 0, 0)) / g.spacing.x;  // seed 002 eq. 5
      EXPECT_NEAR(work.transportedVoidFraction()(i, 0, 0), next(i, 0, 0), 1e-15);
      epsMin = std::min(epsMin, next(i, 0, 0));
      epsMax = std::max(epsMax, next(i, 0, 0));
      for (int p = 0; p < 3; ++p)
        uniformError = std::max(uniformError, std::abs(uniform[static_cast<std::size_t>(p)](i, 0, 0) - (p == 0 ? 0.2 : p == 1 ? 0.3 : 0.5)));
    }
    eps = next;
  }
  std::printf("[ figures  ] eps between %.3f and %.3f over 40 steps: uniform mixture kept to %.2e\n", epsMin, epsMax, uniformError);
  EXPECT_LT(epsMin, 0.7);  // the bed did change, within physical values
  EXPECT_LE(epsMax, 1.0);
  EXPECT_LE(uniformError, 1e-14);
  for (int p = 0; p < 3; ++p) {
    const auto r = vof::fractionRange(layered[static_cast<std::size_t>(p)]);
    EXPECT_GE(r[0], -1e-12);
    EXPECT_LE(r[1], 1.0 + 1e-12);
    EXPECT_NEAR(vof::phaseVolume(layered[static_cast<std::size_t>(p)], eps) / v0[p], 1.0, 1e-12);
  }
  EXPECT_LE(vof::maxSumError(layered), 1e-12);
}

TEST(VofTransport, SubcyclingSplitsALongStepAndStaysBoundedAndConservative) {
  // A divergent flux through a bed (eps changes) at an outflow Courant number of about 2 per step:
  // the step is split into substeps of Courant <= 0.5, with the same bits as those substeps taken
  // one by one from the transported eps, and every phase stays bounded and conserved.
  const int n = 64;
  const CartesianGrid g = makeGrid(n, 1, 1.0, 1.0 / n);
  Fluxes f = streamFluxes(g, [](double, double) { return 0.0; }, 0.0, 0.0);
  for (int i = -2; i < n + 3; ++i) f.u(i, 0, 0) = 0.3 + 0.1 * std::sin(2.0 * kPi * i / n);
  const auto sides = vof::Sides::allPeriodic();
  Field eps(g, Staggering::Cell, 0.8);
  vof::fillCellGhosts(eps, sides);
  auto alpha = phases(g, 3);
  for (int i = 0; i < n; ++i) {
    const double x = g.cellCentre(i, 0, 0).x;
    alpha[1](i, 0, 0) = x < 0.3 ? 1.0 : 0.0;
    alpha[2](i, 0, 0) = x >= 0.3 && x < 0.6 ? 1.0 : 0.0;
    alpha[0](i, 0, 0) = 1.0 - alpha[1](i, 0, 0) - alpha[2](i, 0, 0);
  }
  auto manual = alpha;
  const double dt = 4.0 * g.spacing.x;  // Courant 0.4 * 4 / 0.8 = 2 at the fastest face
  vof::PhaseTransport work(g, 3);
  const int m = vof::advanceSubcycled(work, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
  std::printf("[ figures  ] step at outflow Courant %.2f taken in %d substeps\n", vof::maxCourant(eps, f.ptr(), dt), m);
  EXPECT_GE(m, 4);
  Field e(eps), epsEnd(g);
  for (int k = 0; k < m; ++k) {
    vof::advance(work, manual, e, f.ptr(), dt / m, sides, {}, vof::singleBoxFill(sides));
    e.data() = work.transportedVoidFraction().data();
    vof::fillCellGhosts(e, sides);
  }
  for (int i = 0; i < n; ++i) epsEnd(i, 0, 0) = eps(i, 0, 0) - dt * (f.u(i + 1, 0, 0) - f.u(i, 0, 0)) / g.spacing.x;
  for (int p = 0; p < 3; ++p) {
    const auto& a = alpha[static_cast<std::size_t>(p)];
    for (int i = 0; i < n; ++i) EXPECT_EQ(a(i, 0, 0), manual[static_cast<std::size_t>(p)](i, 0, 0));
    const auto r = vof::fractionRange(a);
    EXPECT_GE(r[0], -1e-12);
    EXPECT_LE(r[1], 1.0 + 1e-12);
    Field start(g);
    for (int i = 0; i < n; ++i)
      start(i, 0, 0) = (p == 1 ? (g.cellCentre(i, 0, 0).x < 0.3) : p == 2 ? (g.cellCentre(i, 0, 0).x >= 0.3 && g.cellCentre(i, 0, 0).x < 0.6)
                                                                     : (g.cellCentre(i, 0, 0).x >= 0.6)) ? 1.0 : 0.0;
    EXPECT_NEAR(vof::phaseVolume(a, epsEnd) / vof::phaseVolume(start, eps), 1.0, 1e-12);
  }
  EXPECT_LE(vof::maxSumError(alpha), 1e-12);
}

TEST(VofTransport, OpenSidesLetPhasesInAndOutWithAnExactVolumeBalance) {
  // A channel along x with an inlet of pure phase 2 at x = 0 and an outlet at x = 1; phase 1 is a
  // slab that flows out. Each phase's volume changes by exactly what crossed the open sides.
  const int n = 50;
  const CartesianGrid g = makeGrid(n, 1, 1.0, 1.0 / n);
  Fluxes f = streamFluxes(g, [](double, double) { return 0.0; }, 1.0, 0.0);
  vof::Sides sides = vof::Sides::allPeriodic();
  sides.side[0] = sides.side[1] = vof::SideType::Open;
  sides.inflow[0] = {0.0, 0.0, 1.0};
  Field eps(g, Staggering::Cell, 1.0);
  vof::fillCellGhosts(eps, sides);
  auto alpha = phases(g, 3);
  for (int i = 0; i < n; ++i) {
    const double x = g.cellCentre(i, 0, 0).x;
    alpha[1](i, 0, 0) = x >= 0.4 && x < 0.6 ? 1.0 : 0.0;
    alpha[0](i, 0, 0) = 1.0 - alpha[1](i, 0, 0);
  }
  double v0[3], crossed[3] = {0.0, 0.0, 0.0};
  for (int p = 0; p < 3; ++p) v0[p] = vof::phaseVolume(alpha[static_cast<std::size_t>(p)], eps);
  const double dt = 0.5 * g.spacing.x;
  vof::PhaseTransport work(g, 3);
  for (int s = 0; s < 60; ++s) {
    vof::advance(work, alpha, eps, f.ptr(), dt, sides, {}, vof::singleBoxFill(sides));
    for (int p = 0; p < 3; ++p) crossed[p] += dt * (work.boundaryOutflow(p, 0, 0, sides) + work.boundaryOutflow(p, 0, 1, sides));
  }
  const double volume = g.cellVolume() * n;
  std::printf("[ figures  ] channel after 0.6 s: volumes / channel %.4f %.4f %.4f (inlet phase 2 filled 0.6)\n",
              vof::phaseVolume(alpha[0], eps) / volume, vof::phaseVolume(alpha[1], eps) / volume,
              vof::phaseVolume(alpha[2], eps) / volume);
  for (int p = 0; p < 3; ++p) {
    const auto& a = alpha[static_cast<std::size_t>(p)];
    EXPECT_NEAR(vof::phaseVolume(a, eps), v0[p] - crossed[p], 1e-14 * volume) << "phase " << p;
    const auto r = vof::fractionRange(a);
    EXPECT_GE(r[0], -1e-12);
    EXPECT_LE(r[1], 1.0 + 1e-12);
  }
  EXPECT_NEAR(vof::phaseVolume(alpha[2], eps) / volume, 0.6, 0.02);  // what came in at 1 m/s for 0.6 s
  EXPECT_LT(vof::phaseVolume(alpha[1], eps) / volume, 0.02);        // the slab has left
  EXPECT_LE(vof::maxSumError(alpha), 1e-12);
}
