// Solid fraction kernels (src/resolved/overlap.hpp): exact areas and volumes, the body's volume
// recovered from the cells' fractions, and no jump when the body moves by a tenth of a cell.
#include "resolved/overlap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace gf::resolved {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Overlap, QuadrantAreaLimits) {
  EXPECT_NEAR(quadrantArea(2.0, 2.0, 1.0), kPi / 4.0, 1e-14);        // whole quarter disk
  EXPECT_NEAR(quadrantArea(0.3, 0.4, 1.0), 0.12, 1e-15);             // rectangle inside
  // Strip 0 <= y <= 1 of the quarter disk (r = 1, b unbounded): integral of sqrt(1 - y^2) on [0, 1/2].
  const double strip = 0.5 * (0.5 * std::sqrt(0.75) + std::asin(0.5));
  EXPECT_NEAR(quadrantArea(0.5, 3.0, 1.0), strip, 1e-14);
}

TEST(Overlap, DiskRectangleAreaMatchesMonteCarloAndWholeDisk) {
  EXPECT_NEAR(diskRectangleArea(0.1, -0.2, 0.7, -5, 5, -5, 5), kPi * 0.49, 1e-13);
  EXPECT_NEAR(diskRectangleArea(0.0, 0.0, 1.0, 0.0, 5.0, -5.0, 5.0), kPi / 2.0, 1e-13);  // half disk
  // A cut rectangle against a fine midpoint sum.
  const double cy = 0.13, cz = -0.07, r = 0.5, y0 = 0.2, y1 = 0.9, z0 = -0.3, z1 = 0.25;
  const int n = 2000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double y = y0 + (i + 0.5) * (y1 - y0) / n, z = z0 + (j + 0.5) * (z1 - z0) / n;
      sum += (y - cy) * (y - cy) + (z - cz) * (z - cz) <= r * r;
    }
  const double mc = sum * (y1 - y0) * (z1 - z0) / (double(n) * n);
  EXPECT_NEAR(diskRectangleArea(cy, cz, r, y0, y1, z0, z1), mc, 2e-5);
}

TEST(Overlap, SphereBoxVolumeHalfAndOctant) {
  const Vec3 c{0.3, -0.2, 0.1};
  const double R = 0.4, V = 4.0 / 3.0 * kPi * R * R * R;
  EXPECT_NEAR(sphereBoxVolume(c, R, c - Vec3{1, 1, 1}, c + Vec3{1, 1, 1}), V, 1e-14);
  EXPECT_NEAR(sphereBoxVolume(c, R, c - Vec3{1, 1, 1}, c + Vec3{0, 1, 1}), V / 2.0, 1e-10 * V);
  EXPECT_NEAR(sphereBoxVolume(c, R, c, c + Vec3{1, 1, 1}), V / 8.0, 1e-10 * V);
  // Spherical cap of height hc: pi hc^2 (3R - hc) / 3.
  const double hc = 0.13;
  EXPECT_NEAR(sphereBoxVolume(c, R, c + Vec3{R - hc, -1, -1}, c + Vec3{1, 1, 1}), kPi * hc * hc * (3 * R - hc) / 3.0,
              1e-10 * V);
}

/// Sum of the fractions of the cells (spacing h) around the sphere, times the cell volume.
double coveredVolume(const Vec3& c, double R, double h) {
  const int n = static_cast<int>(std::ceil(R / h)) + 2;
  double v = 0.0;
  for (int k = -n; k < n; ++k)
    for (int j = -n; j < n; ++j)
      for (int i = -n; i < n; ++i) {
        const Vec3 lo{i * h, j * h, k * h}, hi{(i + 1) * h, (j + 1) * h, (k + 1) * h};
        v += sphereBoxFraction(c, R, lo, hi) * h * h * h;
      }
  return v;
}

TEST(Overlap, CellFractionsAddUpToSphereVolumeAtAnyPosition) {
  // 8 cells per diameter, random positions: relative error of the total below 1e-9.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = 1.0, R = 4.0, V = 4.0 / 3.0 * kPi * R * R * R;
  for (int trial = 0; trial < 5; ++trial) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    EXPECT_NEAR(coveredVolume(c, R, h), V, 1e-9 * V) << trial;
  }
  // 4 cells per diameter (the coarsest accepted): below 1e-8.
  EXPECT_NEAR(coveredVolume({0.37, 0.11, 0.9}, 2.0, 1.0), 4.0 / 3.0 * kPi * 8.0, 1e-8 * 4.0 / 3.0 * kPi * 8.0);
}

/// Largest change of any cell's fraction when the sphere (8 cells per diameter) moves by `step`
/// cells along a diagonal, over two cells of travel.
double largestFractionChange(double step) {
  const double h = 1.0, R = 4.0;
  const Vec3 dir = normalized(Vec3{1.0, 0.6, 0.3});
  std::vector<double> prev;
  double maxStep = 0.0;
  const int steps = static_cast<int>(std::lround(2.0 / step));
  for (int s = 0; s <= steps; ++s) {
    const Vec3 c = Vec3{0.05, 0.05, 0.05} + dir * (step * h * s);
    std::vector<double> now;
    for (int k = -6; k < 7; ++k)
      for (int j = -6; j < 7; ++j)
        for (int i = -6; i < 7; ++i)
          now.push_back(sphereBoxFraction(c, R, {i * h, j * h, k * h}, {(i + 1) * h, (j + 1) * h, (k + 1) * h}));
    if (!prev.empty())
      for (std::size_t q = 0; q < now.size(); ++q) maxStep = std::max(maxStep, std::abs(now[q] - prev[q]));
    prev = now;
  }
  return maxStep;
}

TEST(Overlap, CellFractionVariesSmoothlyWhenTheSphereMovesByATenthOfACell) {
  // The rate of change of a cell's fraction per cell moved is the cell's share of the sphere's
  // cross-section over h^2, at most sqrt(3) along a diagonal: a move of h/10 changes no fraction by
  // more than 0.18, and a move of h/100 by a tenth of that (Lipschitz: no jump anywhere). The
  // stair-step representation (centre in or out, seed 000 Fig. 3.2) jumps by 1.
  const double tenth = largestFractionChange(0.1), hundredth = largestFractionChange(0.01);
  EXPECT_LT(tenth, 0.18);
  EXPECT_GT(tenth, 0.02);  // (the cut cells do change)
  EXPECT_LT(hundredth, 0.12 * tenth);
}

TEST(Overlap, CylinderFractionsAddUpToDiskAreaAndVarySmoothly) {
  const double h = 0.5, R = 2.0, A = kPi * R * R;
  std::vector<double> prev;
  double maxStep = 0.0;
  for (int s = 0; s <= 10; ++s) {
    const Vec3 c{0.03 + 0.1 * h * s, 0.21 - 0.05 * h * s, 0.0};
    double area = 0.0;
    std::vector<double> now;
    for (int j = -8; j < 9; ++j)
      for (int i = -8; i < 10; ++i) {
        const double f = cylinderBoxFraction(c, R, {i * h, j * h, -1.0}, {(i + 1) * h, (j + 1) * h, 3.0});
        area += f * h * h;
        now.push_back(f);
      }
    EXPECT_NEAR(area, A, 1e-12 * A) << s;
    if (!prev.empty())
      for (std::size_t q = 0; q < now.size(); ++q) maxStep = std::max(maxStep, std::abs(now[q] - prev[q]));
    prev = now;
  }
  EXPECT_LT(maxStep, 0.2);
  EXPECT_GT(maxStep, 0.02);
}

}  // namespace
}  // namespace gf::resolved
