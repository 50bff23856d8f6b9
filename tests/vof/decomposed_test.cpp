// The phase-fraction transport on the boxes of a decomposed grid (vof::decomposedFill through
// parallel::fillGhosts) against the whole grid on every rank. Under mpirun with 2 and 4 ranks
// (tests/CMakeLists.txt); alone it runs the one-box layout.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/domain.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/environment.hpp"
#include "parallel/halo.hpp"
#include "parallel/reductions.hpp"
#include "vof/vof.hpp"

namespace {

using gf::CartesianGrid;
using gf::Field;
using gf::Staggering;
namespace vof = gf::vof;
namespace parallel = gf::parallel;

constexpr int kNx = 32, kNy = 16;

/// px x py x 1 layouts of `ranks` (z is one cell).
std::vector<parallel::Layout> layoutsFor(int ranks) {
  std::vector<parallel::Layout> out;
  for (int px = 1; px <= ranks; ++px)
    if (ranks % px == 0) out.push_back({px, ranks / px, 1});
  return out;
}

}  // namespace

TEST(DecomposedVof, EveryLayoutGivesTheBitsOfTheWholeGrid) {
  const parallel::Environment& env = parallel::Environment::instance();
  // periodic in x, walls in y (the vortex and the translation have no normal velocity there)
  gf::Domain domain;
  domain.min = {0, 0, 0};
  domain.max = {1, 1, 1.0 / kNx};
  domain.periodic = {true, false, true};
  CartesianGrid whole;
  whole.cells = {kNx, kNy, 1};
  whole.spacing = {1.0 / kNx, 1.0 / kNy, 1.0 / kNx};
  auto psi = [](double x, double y) { return std::pow(std::sin(std::numbers::pi * x) * std::sin(std::numbers::pi * y), 2) / std::numbers::pi; };
  Field u(whole, Staggering::FaceX), v(whole, Staggering::FaceY), w(whole, Staggering::FaceZ);
  for (int k = -2; k < 3; ++k)
    for (int j = -2; j < kNy + 3; ++j)
      for (int i = -2; i < kNx + 3; ++i) {
        const double x = i * whole.spacing.x, y = j * whole.spacing.y;
        if (j < kNy + 2) u(i, j, k) = 0.3 + (psi(x, y + whole.spacing.y) - psi(x, y)) / whole.spacing.y;
        if (i < kNx + 2) v(i, j, k) = -(psi(x + whole.spacing.x, y) - psi(x, y)) / whole.spacing.x;
      }
  Field eps(whole, Staggering::Cell, 1.0);
  std::vector<Field> alpha(3, Field(whole));
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) {
      const auto c = whole.cellCentre(i, j, 0);
      eps(i, j, 0) = 1.0 - 0.3 * std::exp(-(std::pow(c.x - 0.5, 2) + std::pow(c.y - 0.4, 2)) / 0.03);
      alpha[1](i, j, 0) = std::hypot(c.x - 0.45, c.y - 0.5) < 0.25 ? 1.0 : 0.0;
      alpha[2](i, j, 0) = (alpha[1](i, j, 0) == 0.0 && c.x > 0.55 && c.x < 0.85) ? 1.0 : 0.0;
      alpha[0](i, j, 0) = 1.0 - alpha[1](i, j, 0) - alpha[2](i, j, 0);
    }
  const parallel::Decomposition one(domain, {1, 1, 1}, 1, 0, whole.cells);
  const vof::Sides wholeSides = vof::boxSides(one);
  vof::fillCellGhosts(eps, wholeSides);
  const std::array<const Field*, 3> wholeFlux{&u, &v, &w};
  const double dt = 0.5 / vof::maxCourant(eps, wholeFlux, 1.0);
  constexpr int kSteps = 25;

  // the whole grid on every rank (no reduction scope: its own sums)
  std::vector<Field> reference = alpha;
  vof::PhaseTransport wholeWork(whole, 3);
  for (int s = 0; s < kSteps; ++s)
    vof::advance(wholeWork, reference, eps, wholeFlux, dt, wholeSides, {}, vof::singleBoxFill(wholeSides));
  double wholeVolume[3];
  for (int p = 0; p < 3; ++p) wholeVolume[p] = vof::phaseVolume(reference[static_cast<std::size_t>(p)], eps);

  for (const parallel::Layout& layout : layoutsFor(env.size())) {
    const parallel::Decomposition d(domain, layout, env.size(), env.rank(), whole.cells);
    CartesianGrid box = whole;
    box.cells = d.cellCount();
    const auto off = d.cellOffset();
    box.origin = {off[0] * whole.spacing.x, off[1] * whole.spacing.y, 0.0};
    auto extract = [&](const Field& f) {
      Field local(box, f.staggering());
      parallel::extractBox(f, d, local);
      return local;
    };
    std::vector<Field> a;
    for (const Field& f : alpha) a.push_back(extract(f));
    const Field bu = extract(u), bv = extract(v), bw = extract(w), be = extract(eps);
    vof::PhaseTransport work(box, 3);
    const vof::GhostFill fill = vof::decomposedFill(d);
    const parallel::RankReductionScope scope(d);
    for (int s = 0; s < kSteps; ++s) vof::advance(work, a, be, {&bu, &bv, &bw}, dt, vof::boxSides(d), {}, fill);
    double diff = 0.0;
    for (int p = 0; p < 3; ++p) {
      for (int j = 0; j < box.cells[1]; ++j)
        for (int i = 0; i < box.cells[0]; ++i)
          diff = std::max(diff, std::abs(a[static_cast<std::size_t>(p)](i, j, 0) -
                                         reference[static_cast<std::size_t>(p)](i + off[0], j + off[1], 0)));
      // the volume summed across the ranks (an allreduce in the scope)
      EXPECT_NEAR(vof::phaseVolume(a[static_cast<std::size_t>(p)], be) / wholeVolume[p], 1.0, 1e-13)
          << "layout " << d.describe();
    }
    EXPECT_EQ(diff, 0.0) << "rank " << env.rank() << " of layout " << d.describe();
    EXPECT_LE(vof::maxSumError(a), 1e-12);
  }
}
