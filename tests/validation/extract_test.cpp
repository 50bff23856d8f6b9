// Extraction operations of `grainflow validate` on synthetic series with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "app/validation_extract.hpp"

using namespace gf::app::validation;

namespace {
// y = sin(x) sampled on [0, 2 pi] with n intervals.
Series sine(int n) {
  Series s;
  for (int i = 0; i <= n; ++i) {
    const double x = 2.0 * M_PI * i / n;
    s.x.push_back(x);
    s.y.push_back(std::sin(x));
  }
  return s;
}
}  // namespace

TEST(Extract, SimpleReductions) {
  const Series s{{0.0, 1.0, 2.0, 3.0}, {4.0, -1.0, 7.0, 2.0}};
  EXPECT_EQ(finalValue(s), 2.0);
  EXPECT_EQ(initialValue(s), 4.0);
  EXPECT_EQ(minimum(s), -1.0);
  EXPECT_EQ(maximum(s), 7.0);
  // trapezoid: (1.5 + 3 + 4.5) / 3
  EXPECT_DOUBLE_EQ(mean(s), 3.0);
  const Series w = window(s, 0.5, 2.0);
  ASSERT_EQ(w.x.size(), 2u);
  EXPECT_EQ(w.y[0], -1.0);
  EXPECT_EQ(w.y[1], 7.0);
}

TEST(Extract, MeanIsTimeWeightedNotSampleWeighted) {
  // Dense samples early, sparse late: the time average of y = x on [0, 10] is 5.
  Series s;
  for (int i = 0; i <= 100; ++i) s.x.push_back(0.01 * i), s.y.push_back(0.01 * i);
  s.x.push_back(10.0), s.y.push_back(10.0);
  EXPECT_NEAR(mean(s), 5.0, 1e-12);
}

TEST(Extract, InterpolationInsideAndOutside) {
  const Series s{{0.0, 1.0, 3.0}, {0.0, 2.0, 6.0}};
  EXPECT_DOUBLE_EQ(*interpolate(s, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(*interpolate(s, 2.0), 4.0);
  EXPECT_DOUBLE_EQ(*interpolate(s, 3.0), 6.0);
  EXPECT_DOUBLE_EQ(*interpolate(s, 1.0), 2.0);
  EXPECT_FALSE(interpolate(s, 3.1).has_value());
  EXPECT_FALSE(interpolate(s, -0.1).has_value());
}

TEST(Extract, CrossingsConvergeToTheExactRoot) {
  // sin crosses 0.5 first at pi/6; linear interpolation error is O(h^2).
  const double coarse = std::abs(*firstCrossing(sine(50), 0.5) - M_PI / 6);
  const double fine = std::abs(*firstCrossing(sine(500), 0.5) - M_PI / 6);
  EXPECT_LT(fine, 2e-5);
  EXPECT_LT(fine, coarse / 50.0);
  EXPECT_FALSE(firstCrossing(sine(50), 2.0).has_value());
}

TEST(Extract, DurationAboveThreshold) {
  // sin > 0.5 on (pi/6, 5 pi/6): duration 2 pi / 3.
  EXPECT_NEAR(*durationAbove(sine(1000), 0.5), 2.0 * M_PI / 3.0, 1e-5);
  // Never back below the threshold: no complete interval.
  const Series rising{{0, 1, 2}, {0, 1, 2}};
  EXPECT_FALSE(durationAbove(rising, 0.5).has_value());
  EXPECT_FALSE(durationAbove(rising, 5.0).has_value());
}

TEST(Extract, LogLogSlopeRecoversPowerLaws) {
  std::vector<double> x = {0.1, 0.3, 1.0, 3.0}, y;
  for (double v : x) y.push_back(7.0 * std::pow(v, -0.2));
  EXPECT_NEAR(logLogSlope(x, y), -0.2, 1e-12);
  for (double& v : y) v = -v;  // sign does not matter (errors may be negative)
  EXPECT_NEAR(logLogSlope(x, y), -0.2, 1e-12);
  EXPECT_THROW(logLogSlope({1.0}, {1.0}), std::invalid_argument);
}

TEST(Extract, RichardsonOrderCancelsTheCommonError) {
  // f(h) = f0 + C h^2 + D (D: an error every run shares, e.g. the time error of a space study).
  auto f = [](double h) { return 3.0 + 0.7 * h * h + 0.01; };
  EXPECT_NEAR(richardsonOrder({16, 32, 64}, {f(1.0 / 16), f(1.0 / 32), f(1.0 / 64)}), 2.0, 1e-9);  // cells (ratio 2)
  EXPECT_NEAR(richardsonOrder({0.3, 0.1, 1.0 / 30}, {f(0.3), f(0.1), f(1.0 / 30)}), 2.0, 1e-9);     // steps (ratio 1/3)
  // The last three runs count: a pre-asymptotic first run does not.
  EXPECT_NEAR(richardsonOrder({8, 16, 32, 64}, {9.0, f(1.0 / 16), f(1.0 / 32), f(1.0 / 64)}), 2.0, 1e-9);
  EXPECT_THROW(richardsonOrder({16, 32}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(richardsonOrder({16, 32, 48}, {1.0, 2.0, 2.5}), std::invalid_argument);  // ratio not constant
}

TEST(Extract, MinIncrementOrdersByTheSweptValue) {
  EXPECT_DOUBLE_EQ(minIncrement({0.1, 0.4, 0.2}, {10.0, 14.0, 11.5}), 1.5);  // 10 -> 11.5 -> 14
  EXPECT_DOUBLE_EQ(minIncrement({0.1, 0.2}, {10.0, 9.0}), -1.0);
  EXPECT_THROW(minIncrement({0.1}, {1.0}), std::invalid_argument);
}

TEST(Extract, GapClosedOrdersByTheSweptValue) {
  // coarse 0.63, coarse corrected 0.71, fine 0.69: the correction closes 1 - 0.02 / 0.06 of the gap
  EXPECT_NEAR(gapClosed({4, 4, 16}, {0.63, 0.71, 0.69}), 1.0 - 0.02 / 0.06, 1e-12);
  EXPECT_NEAR(gapClosed({16, 4, 4}, {0.69, 0.63, 0.71}), 1.0 - 0.02 / 0.06, 1e-12);  // equal x keep their order
  EXPECT_LT(gapClosed({4, 4, 16}, {0.63, 0.80, 0.69}), 0.0);                         // overshoots: farther
  EXPECT_NEAR(gapClosed({4, 4, 16}, {0.63, 0.63, 0.69}), 0.0, 1e-12);                // no effect
  EXPECT_THROW(gapClosed({4, 16}, {0.63, 0.69}), std::invalid_argument);
  EXPECT_THROW(gapClosed({4, 4, 16}, {0.69, 0.7, 0.69}), std::invalid_argument);     // no gap
}

TEST(Extract, CompareValueLowerBound) {
  Tolerance bound;
  bound.lowerBound = true;
  EXPECT_TRUE(compareValue(1.95, 1.9, bound).pass);
  EXPECT_TRUE(compareValue(1.9, 1.9, bound).pass);
  const auto c = compareValue(1.85, 1.9, bound);
  EXPECT_FALSE(c.pass);
  EXPECT_NEAR(c.error, -0.05, 1e-12);
  EXPECT_FALSE(compareValue(NAN, 1.9, bound).pass);
}

TEST(Extract, CompareValueAbsoluteAndRelative) {
  const auto a = compareValue(1.02, 1.0, {0.03, false});
  EXPECT_NEAR(a.error, 0.02, 1e-15);
  EXPECT_TRUE(a.pass);
  EXPECT_FALSE(compareValue(1.04, 1.0, {0.03, false}).pass);
  const auto r = compareValue(-2.1, -2.0, {0.04, true});
  EXPECT_NEAR(r.error, -0.05, 1e-12);  // (computed - reference) / |reference|
  EXPECT_FALSE(r.pass);
  EXPECT_FALSE(compareValue(NAN, 1.0, {1e9, false}).pass);
  EXPECT_FALSE(compareValue(1.0, 0.0, {0.5, true}).pass);
}

TEST(Extract, CompareCurveReportsTheWorstPointInsideTheRange) {
  const Series computed{{0.0, 1.0, 2.0}, {0.0, 1.0, 2.0}};
  const Series reference{{0.5, 1.5, 5.0}, {0.5, 1.7, 99.0}};  // x = 5 is outside: ignored
  const auto c = compareCurve(computed, reference, {0.1, false});
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->reference, 1.7);
  EXPECT_DOUBLE_EQ(c->computed, 1.5);
  EXPECT_NEAR(c->error, -0.2, 1e-12);
  EXPECT_FALSE(c->pass);
  const auto rel = compareCurve(computed, reference, {0.2, true});  // relative to max |reference| = 99
  ASSERT_TRUE(rel.has_value());
  EXPECT_TRUE(rel->pass);
  EXPECT_FALSE(compareCurve(computed, Series{{7.0}, {1.0}}, {1.0, false}).has_value());
}

TEST(Extract, LastProfileTakesTheRowsOfTheLastSampleSortedByPosition) {
  // Long format as fluid_line_profile writes it: three cells per sample, samples at t = 0, 1, 2.
  const std::vector<double> t = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  const std::vector<double> y = {0.5, 1.5, 2.5, 0.5, 1.5, 2.5, 2.5, 0.5, 1.5};  // (any order within a sample)
  const std::vector<double> u = {9, 9, 9, 8, 8, 8, 30, 10, 20};
  const Series p = lastProfile(t, y, u);
  ASSERT_EQ(p.x.size(), 3u);
  EXPECT_EQ(p.x, (std::vector<double>{0.5, 1.5, 2.5}));
  EXPECT_EQ(p.y, (std::vector<double>{10, 20, 30}));
  // One sample only; a time series (one row per time) gives its last row.
  EXPECT_EQ(lastProfile({4, 4}, {1, 0}, {7, 6}).y, (std::vector<double>{6, 7}));
  EXPECT_EQ(lastProfile({0, 1, 2}, {5, 5, 5}, {1, 2, 3}).y, (std::vector<double>{3}));
  EXPECT_THROW(lastProfile({}, {}, {}), std::invalid_argument);
  EXPECT_THROW(lastProfile({0, 1}, {0}, {0, 1}), std::invalid_argument);
}

TEST(Extract, CompareProfileGivesOneComparisonPerReferencePoint) {
  // A parabola sampled at cell centres y = 0.125, 0.375, ...; the reference at the walls is outside.
  Series computed;
  for (int j = 0; j < 4; ++j) {
    const double y = (j + 0.5) / 4;
    computed.x.push_back(y);
    computed.y.push_back(y * (1 - y));
  }
  const Series reference{{0.0, 0.125, 0.25, 0.5, 1.0}, {0.0, 0.109375, 0.1875, 0.26, 0.0}};
  const auto c = compareProfile(computed, reference, {0.005, false});
  ASSERT_EQ(c.size(), 5u);
  EXPECT_FALSE(c[0].has_value());  // y = 0 beyond the first cell centre
  EXPECT_FALSE(c[4].has_value());
  ASSERT_TRUE(c[1] && c[2] && c[3]);
  EXPECT_NEAR(c[1]->error, 0.0, 1e-15);  // on a sample
  EXPECT_TRUE(c[1]->pass);
  // y = 0.25 between samples: linear interpolation, (0.109375 + 0.234375) / 2 = 0.171875 against 0.1875.
  EXPECT_NEAR(c[2]->computed, 0.171875, 1e-15);
  EXPECT_NEAR(c[2]->error, -0.015625, 1e-15);
  EXPECT_FALSE(c[2]->pass);
  EXPECT_NEAR(c[3]->error, 0.234375 - 0.26, 1e-15);  // y = 0.5 between 0.375 and 0.625 (equal values)
  // Relative tolerance: errors relative to max |reference| = 0.26, as for curves (no division by a zero).
  const auto r = compareProfile(computed, reference, {0.1, true});
  EXPECT_NEAR(r[2]->error, -0.015625 / 0.26, 1e-15);
  EXPECT_TRUE(r[2]->pass);
  EXPECT_NEAR(r[3]->error, (0.234375 - 0.26) / 0.26, 1e-15);
  EXPECT_TRUE(r[3]->pass);  // -9.9 % of the peak
  EXPECT_FALSE(compareProfile(computed, reference, {0.09, true})[3]->pass);
}
