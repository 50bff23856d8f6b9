#include "app/validation_extract.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gf::app::validation {

namespace {
void requireSamples(const Series& s) {
  if (s.x.empty() || s.x.size() != s.y.size()) throw std::invalid_argument("empty or inconsistent series");
}
// x where the segment (x0, y0)-(x1, y1) reaches y = level.
double crossingX(double x0, double y0, double x1, double y1, double level) {
  return y1 == y0 ? x0 : x0 + (level - y0) / (y1 - y0) * (x1 - x0);
}
}  // namespace

Series sortedByX(std::vector<std::pair<double, double>> points) {
  std::stable_sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Series out;
  for (const auto& [x, y] : points) {
    out.x.push_back(x);
    out.y.push_back(y);
  }
  return out;
}

Series window(const Series& s, double from, double to) {
  Series out;
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (s.x[i] >= from && s.x[i] <= to) {
      out.x.push_back(s.x[i]);
      out.y.push_back(s.y[i]);
    }
  return out;
}

std::optional<double> interpolate(const Series& s, double x0) {
  requireSamples(s);
  const double span = std::max(std::abs(s.x.front()), std::abs(s.x.back()));
  const double slack = 1e-12 * span;  // x read back from 12-digit CSV text
  if (x0 < s.x.front() - slack || x0 > s.x.back() + slack) return std::nullopt;
  if (s.x.size() == 1) return s.y.front();
  const auto upper = std::upper_bound(s.x.begin(), s.x.end(), x0);
  std::size_t i1 = static_cast<std::size_t>(upper - s.x.begin());
  i1 = std::clamp<std::size_t>(i1, 1, s.x.size() - 1);
  const std::size_t i0 = i1 - 1;
  if (s.x[i1] == s.x[i0]) return s.y[i1];
  const double w = (x0 - s.x[i0]) / (s.x[i1] - s.x[i0]);
  return (1.0 - w) * s.y[i0] + w * s.y[i1];
}

double finalValue(const Series& s) {
  requireSamples(s);
  return s.y.back();
}
double initialValue(const Series& s) {
  requireSamples(s);
  return s.y.front();
}
double minimum(const Series& s) {
  requireSamples(s);
  return *std::min_element(s.y.begin(), s.y.end());
}
double maximum(const Series& s) {
  requireSamples(s);
  return *std::max_element(s.y.begin(), s.y.end());
}

double mean(const Series& s) {
  requireSamples(s);
  const double length = s.x.back() - s.x.front();
  if (s.x.size() == 1 || length <= 0.0) {
    double sum = 0.0;
    for (double v : s.y) sum += v;
    return sum / static_cast<double>(s.y.size());
  }
  double integral = 0.0;
  for (std::size_t i = 1; i < s.x.size(); ++i) integral += 0.5 * (s.y[i] + s.y[i - 1]) * (s.x[i] - s.x[i - 1]);
  return integral / length;
}

std::optional<double> firstCrossing(const Series& s, double threshold) {
  requireSamples(s);
  if (s.y.front() == threshold) return s.x.front();
  for (std::size_t i = 1; i < s.x.size(); ++i) {
    const double a = s.y[i - 1] - threshold, b = s.y[i] - threshold;
    if (b == 0.0 || (a < 0.0) != (b < 0.0)) return crossingX(s.x[i - 1], s.y[i - 1], s.x[i], s.y[i], threshold);
  }
  return std::nullopt;
}

std::optional<double> durationAbove(const Series& s, double threshold) {
  requireSamples(s);
  std::size_t i = 0;
  while (i < s.y.size() && !(s.y[i] > threshold)) ++i;
  if (i == s.y.size()) return std::nullopt;
  const double start = i == 0 ? s.x[0] : crossingX(s.x[i - 1], s.y[i - 1], s.x[i], s.y[i], threshold);
  while (i < s.y.size() && s.y[i] > threshold) ++i;
  if (i == s.y.size()) return std::nullopt;
  const double end = crossingX(s.x[i - 1], s.y[i - 1], s.x[i], s.y[i], threshold);
  return end - start;
}

double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2 || x.size() != y.size()) throw std::invalid_argument("a log-log slope needs at least two points");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(std::abs(x[i])), ly = std::log(std::abs(y[i]));
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double richardsonOrder(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 3 || x.size() != y.size()) throw std::invalid_argument("an observed order needs at least three runs");
  const std::size_t n = x.size();
  const double r1 = x[n - 2] / x[n - 3], r2 = x[n - 1] / x[n - 2];
  if (!(r1 > 0.0) || r1 == 1.0 || std::abs(r2 / r1 - 1.0) > 1e-6)
    throw std::invalid_argument("an observed order needs a constant refinement ratio between the last three runs");
  const double ratio = r1 > 1.0 ? r1 : 1.0 / r1;
  return std::log(std::abs(y[n - 3] - y[n - 2]) / std::abs(y[n - 2] - y[n - 1])) / std::log(ratio);
}

double minIncrement(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2 || x.size() != y.size()) throw std::invalid_argument("an increment needs at least two points");
  std::vector<std::size_t> order(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  double smallest = INFINITY;
  for (std::size_t k = 1; k < order.size(); ++k) smallest = std::min(smallest, y[order[k]] - y[order[k - 1]]);
  return smallest;
}

double gapClosed(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 3 || x.size() != y.size()) throw std::invalid_argument("the gap closed needs at least three points");
  std::vector<std::size_t> order(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  const double last = y[order.back()];
  const double gap = std::abs(y[order[0]] - last);
  if (!(gap > 0.0)) throw std::invalid_argument("the first run equals the last: no gap to close");
  return 1.0 - std::abs(y[order[1]] - last) / gap;
}

Comparison compareValue(double computed, double reference, const Tolerance& tolerance) {
  Comparison c{reference, computed, computed - reference, false};
  if (tolerance.lowerBound) {
    c.pass = std::isfinite(computed) && computed >= reference;
    return c;
  }
  if (tolerance.relative) c.error = reference == 0.0 ? (computed == 0.0 ? 0.0 : INFINITY) : c.error / std::abs(reference);
  c.pass = std::isfinite(c.error) && std::abs(c.error) <= tolerance.value;
  return c;
}

std::vector<std::optional<Comparison>> compareProfile(const Series& computed, const Series& reference, const Tolerance& tolerance) {
  double scale = 0.0;
  for (double v : reference.y) scale = std::max(scale, std::abs(v));
  std::vector<std::optional<Comparison>> out;
  for (std::size_t i = 0; i < reference.x.size(); ++i) {
    const auto value = interpolate(computed, reference.x[i]);
    if (!value) {
      out.emplace_back();
      continue;
    }
    Comparison c{reference.y[i], *value, *value - reference.y[i], false};
    if (tolerance.relative) c.error = scale > 0.0 ? c.error / scale : (c.error == 0.0 ? 0.0 : INFINITY);
    if (!std::isfinite(c.error)) c.error = INFINITY;
    c.pass = std::isfinite(c.error) && std::abs(c.error) <= tolerance.value;
    out.push_back(c);
  }
  return out;
}

std::optional<Comparison> compareCurve(const Series& computed, const Series& reference, const Tolerance& tolerance) {
  std::optional<Comparison> worst;
  for (const auto& c : compareProfile(computed, reference, tolerance))
    if (c && (!worst || !(std::abs(c->error) <= std::abs(worst->error)))) worst = c;
  return worst;
}

Series lastProfile(const std::vector<double>& time, const std::vector<double>& position, const std::vector<double>& value) {
  if (time.empty() || time.size() != position.size() || time.size() != value.size())
    throw std::invalid_argument("empty or inconsistent profile table");
  const double last = time.back();  // rows of one sample carry the same time text, hence the same number
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] == last) points.emplace_back(position[i], value[i]);
  return sortedByX(std::move(points));
}

}  // namespace gf::app::validation
