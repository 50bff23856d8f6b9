#include "dem/contact/restitution_damping.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

namespace gf::dem {

double restitutionForDamping(double alpha, double p, double q) {
  // Dimensionless collision, RK4 with a step small against the dimensionless duration (~3).
  auto accel = [&](double x, double v) {
    if (x <= 0.0) return 0.0;
    const double f = std::pow(x, p) + alpha * std::pow(x, q) * v;
    return f > 0.0 ? -f : 0.0;
  };
  const double h = 1e-3;
  double x = 0.0, v = 1.0;
  for (int step = 0; step < 10000000; ++step) {
    const double k1x = v, k1v = accel(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, v + h * k3v);
    const double xNew = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vNew = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xNew <= 0.0 && step > 0) return -vNew;
    // Force vanished while still compressed and moving apart: free flight from here on.
    if (vNew < 0.0 && accel(xNew, vNew) == 0.0) return -vNew;
    x = xNew;
    v = vNew;
  }
  return 0.0;  // over-damped: never separates
}

double dampingForRestitution(double e, double p, double q) {
  if (e >= 1.0) return 0.0;
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double>, double> cache;
  std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_tuple(e, p, q);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  double lo = 0.0, hi = 1.0;
  while (restitutionForDamping(hi, p, q) > e && hi < 1e3) hi *= 2.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (restitutionForDamping(mid, p, q) > e ? lo : hi) = mid;
  }
  const double alpha = 0.5 * (lo + hi);
  cache[key] = alpha;
  return alpha;
}

}  // namespace gf::dem
