#pragma once
// Pure extraction operations of `grainflow validate`: reduce a monitor series y(x) (x usually
// time) to one number, compare numbers and curves against reference data. No I/O here, so
// every operation is unit-tested on synthetic series (tests/validation/extract_test.cpp).
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gf::app::validation {

/// A sampled curve y(x) with non-decreasing x.
struct Series {
  std::vector<double> x;
  std::vector<double> y;
};

/// (x, y) points in any order as a Series sorted by x (stable: equal x keep their order).
Series sortedByX(std::vector<std::pair<double, double>> points);

/// The samples with x in [from, to] (inclusive).
Series window(const Series& s, double from, double to);

/// Linear interpolation at x0; x0 outside [x.front(), x.back()] is an error (std::nullopt).
std::optional<double> interpolate(const Series& s, double x0);

double finalValue(const Series& s);
double initialValue(const Series& s);
double minimum(const Series& s);
double maximum(const Series& s);
/// Time-weighted (trapezoidal) mean over the series' x range; the plain value for one sample.
double mean(const Series& s);
/// First x where y crosses `threshold` (either direction), linearly interpolated; nullopt if never.
std::optional<double> firstCrossing(const Series& s, double threshold);
/// Length in x of the first interval where y > threshold, both ends interpolated; nullopt if
/// y never rises above the threshold or has not fallen back below it by the end.
std::optional<double> durationAbove(const Series& s, double threshold);

/// Least-squares slope of log|y| over log|x| (observed order of convergence); needs >= 2 points.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y);

/// Observed order of convergence from the last three of a sequence of runs refined by a constant
/// ratio r (x: the resolution parameter, cells or time step, in the order run; y: the result):
/// p = ln(|y1 - y2| / |y2 - y3|) / ln(r), r = x2/x1 or x1/x2 (whichever is > 1). The exact
/// solution is not needed: the leading error term C h^p cancels in the differences (Roache 1998,
/// Verification and Validation in Computational Science and Engineering, eq. 5.4.1). Needs >= 3
/// points and a constant ratio (std::invalid_argument otherwise).
double richardsonOrder(const std::vector<double>& x, const std::vector<double>& y);

/// Smallest increase y[k+1] - y[k] between consecutive points ordered by x (> 0: y increases
/// strictly with x); needs >= 2 points.
double minIncrement(const std::vector<double>& x, const std::vector<double>& y);

/// Points ordered by x (equal x keep their order): the share of the first point's distance from the
/// last that the second closes, 1 - |y2 - y_last| / |y1 - y_last| (1: the second equals the last;
/// > 0: the second is closer to the last than the first, e.g. a correction on a coarse grid against
/// the fine grid); needs >= 3 points and y1 != y_last.
double gapClosed(const std::vector<double>& x, const std::vector<double>& y);

struct Tolerance {
  double value = 0.0;
  bool relative = false;    // relative to |reference|; for curves to max |reference|
  bool lowerBound = false;  // the reference is a lower bound: pass if computed >= reference (value unused)
};

/// One compared number: the error is signed (computed - reference), relative when the tolerance is;
/// with a lower-bound tolerance it passes when computed >= reference.
struct Comparison {
  double reference = 0.0;
  double computed = 0.0;
  double error = 0.0;
  bool pass = false;
};
Comparison compareValue(double computed, double reference, const Tolerance& tolerance);

/// A computed curve against reference points (xr, yr): the computed curve is interpolated at
/// each xr inside its range; the reported comparison is the point of largest |error| (a relative
/// error is divided by max |yr|). nullopt if no reference point lies inside the computed range.
std::optional<Comparison> compareCurve(const Series& computed, const Series& reference, const Tolerance& tolerance);

/// The last sample of a long-format table, where the rows of one sample share its time (a
/// profile along a line: one row per cell): the (position, value) pairs of the rows whose time
/// equals the last row's, sorted by position.
Series lastProfile(const std::vector<double>& time, const std::vector<double>& position, const std::vector<double>& value);

/// A computed profile against reference points (xr, yr), one comparison per point: the profile
/// interpolated linearly at xr, the error relative to max |yr| when the tolerance is relative (as
/// for curves, so that points where the profile crosses zero are not singular); nullopt for a
/// point outside the computed range (a wall value beyond the last cell centre).
std::vector<std::optional<Comparison>> compareProfile(const Series& computed, const Series& reference, const Tolerance& tolerance);

}  // namespace gf::app::validation
