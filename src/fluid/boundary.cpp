#include "fluid/boundary.hpp"

#include <fmt/format.h>

#include "fluid/loops.hpp"
#include "parallel/halo.hpp"

namespace gf::fluid {

namespace {

constexpr const char* kSideNames[6] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};

/// Calls body(coord, base) for every grid line along `axis`, ghost rows of the other two axes
/// included: coord[b] is the line's index along the two other axes b (coord[axis] = 0), base the
/// flat index of point 0 on the line. Lines run with the lower of the other axes innermost (x for
/// the y and z lines: neighbouring memory); they are independent (each writes only its own ghost
/// points), threaded for large faces. The x and y lines are restricted to the z planes of
/// `planes` (all planes by default).
template <class Body>
void forEachLine(const Field& f, int axis, const GhostPlanes& planes, Body&& body) {
  const int g = f.grid().ghosts;
  const int lo = axis == 0 ? 1 : 0, hi = axis == 2 ? 1 : 2;
  const auto& pts = f.points();
  const int nLo = pts[lo] + 2 * g, nHi = pts[hi] + 2 * g;
  const std::ptrdiff_t sLo = f.stride(lo), sHi = f.stride(hi);
  const std::size_t first = f.index(0, 0, 0) - static_cast<std::size_t>(g * sLo + g * sHi);
  auto row = [&](std::int64_t q) {
    int coord[3] = {0, 0, 0};
    coord[hi] = static_cast<int>(q) - g;
    const std::size_t b = first + static_cast<std::size_t>(q * sHi);
    for (int p = 0; p < nLo; ++p) {
      coord[lo] = p - g;
      body(static_cast<const int*>(coord), b + static_cast<std::size_t>(p * sLo));
    }
  };
  // Rows q (ghost-shifted index along hi): z planes [kBegin, kEnd) plus the ghost planes of the
  // flagged z sides for the x and y lines; all rows for the z lines.
  const int qBegin = hi == 2 ? planes.kBegin + (planes.lowZ ? 0 : g) : 0;
  const int qEnd = hi == 2 ? (planes.kEnd < 0 ? pts[2] : planes.kEnd) + g + (planes.highZ ? g : 0) : nHi;
  if (!planes.threaded || static_cast<std::int64_t>(nLo) * nHi < kSerialBelow || serialLoops()) {
    for (int q = qBegin; q < qEnd; ++q) row(q);
  } else {
#pragma omp parallel for schedule(static)
    for (int q = qBegin; q < qEnd; ++q) row(q);
  }
}

}  // namespace

const char* sideName(int s) { return kSideNames[s]; }

Boundaries Boundaries::read(Params& fluid, const std::array<bool, 3>& periodic, bool twoD) {
  Boundaries bc;
  Params sec = fluid.section({"boundaries", "-", "boundary condition per box face (x_min, x_max, y_min, ...)"});
  for (int s = 0; s < 6; ++s) {
    const int axis = s / 2;
    Params p = sec.section({kSideNames[s], "-", "boundary condition on this face"});
    BoundarySide& b = bc.side[s];
    const std::string type =
        p.choice({"type", "-", "wall | slip | inlet | pressure_outlet | outflow (zero gradient) | periodic"},
                 {"wall", "slip", "inlet", "pressure_outlet", "outflow", "periodic"},
                 periodic[axis] ? "periodic" : "wall");
    b.velocity = p.vec3({"velocity", "m/s", "wall velocity (tangential part used) or inlet velocity (peak if parabolic)"},
                        Vec3{});
    b.parabolic = p.choice({"profile", "-", "inlet profile: uniform or parabolic (peak = velocity)"},
                           {"uniform", "parabolic"}, "uniform") == "parabolic";
    b.pressure = p.real({"pressure", "Pa", "static pressure at a pressure_outlet"}, 0.0);
    b.scalarFixed = p.choice({"scalar", "-", "passive scalar condition: zero_gradient or fixed"},
                             {"zero_gradient", "fixed"}, "zero_gradient") == "fixed";
    b.scalarValue = p.real({"scalar_value", "-", "passive scalar value where scalar: fixed"}, 0.0);
    b.rampTime = p.real({"ramp_time", "s",
                         "inlet/wall velocity multiplied by min(1, t / ramp_time) (linear start-up or "
                         "fluidisation ramp); 0 = constant",
                         Range::nonNegative()},
                        0.0);
    b.superficial = p.boolean({"superficial", "-",
                               "inlet: velocity is the superficial velocity (the face mass flux eps_f u_f equals "
                               "it whatever eps is in the first cell; the face velocity is velocity / eps_f); "
                               "false: the face (interstitial) velocity is prescribed"},
                              true);
    b.phase = p.text({"phase", "-",
                      "with fluid.vof: the phase entering through this inlet, or through this outlet where the flow "
                      "turns inwards (an inlet per phase); default: fluid.vof.inflow_phase"},
                     "");
    if (type == "wall") b.type = BoundaryType::Wall;
    else if (type == "slip") b.type = BoundaryType::Slip;
    else if (type == "inlet") b.type = BoundaryType::Inlet;
    else if (type == "pressure_outlet") b.type = BoundaryType::PressureOutlet;
    else if (type == "outflow") b.type = BoundaryType::Outflow;
    else b.type = BoundaryType::Periodic;
    if (!p.documenting() && !(twoD && axis == 2) && (b.type == BoundaryType::Periodic) != periodic[axis])
      p.fail("type", type,
             periodic[axis] ? "periodic (the domain is periodic along this axis)"
                            : "a non-periodic condition (domain.periodic is 0 along this axis)");
    if (twoD && axis == 2) b.type = BoundaryType::Periodic;
  }
  return bc;
}

void Boundaries::decompose(std::shared_ptr<const parallel::Decomposition> d, const Vec3& origin,
                           const std::array<int, 3>& cells) {
  if (!decomposition)
    for (int s = 0; s < 6; ++s) domainType[s] = side[s].type;
  decomposition = std::move(d);
  domainOrigin = origin;
  domainCells = cells;
  for (int s = 0; s < 6; ++s) {
    side[s].type = domainType[s];
    if (decomposition->side(s / 2, s % 2 == 0 ? -1 : 1) == parallel::Side::Shared) side[s].type = BoundaryType::Shared;
  }
}

namespace {
/// The exchange of a ghost fill on a decomposed grid, before the conditions of the physical and
/// periodic sides (their lines read the exchanged ghost rows). Only for a fill of all planes: the
/// plane teams (GhostPlanes of one member) are not used on a decomposed grid.
void exchangeGhosts(Field& f, const Boundaries& bc, bool allPlanes) {
  if (bc.distributed() && allPlanes) parallel::fillGhosts(f, *bc.decomposition);
}
bool allPlanes(const GhostPlanes& p) { return p.kBegin == 0 && p.kEnd < 0 && p.lowZ && p.highZ && p.exchange; }
}  // namespace

double inletNormalVelocity(const Boundaries& bc, int axis, int side, const CartesianGrid& g, const Vec3& x) {
  const BoundarySide& s = bc.at(axis, side);
  double u = s.velocity[axis] * rampFactor(s, bc.time);
  if (!s.parabolic) return u;
  // (across the whole domain: on a decomposed grid, its origin and cells)
  const bool whole = bc.decomposition == nullptr;
  for (int b = 0; b < 3; ++b) {
    if (b == axis || bc.domainPeriodic(b)) continue;
    const double xi = whole ? (x[b] - g.origin[b]) / (g.cells[b] * g.spacing[b])
                            : (x[b] - bc.domainOrigin[b]) / (bc.domainCells[b] * g.spacing[b]);
    u *= 4.0 * xi * (1.0 - xi);
  }
  return u;
}

int firstTimeDependentVelocityAxis(const Boundaries& bc) {
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 2; ++s) {
      const BoundarySide& side = bc.at(a, s);
      if (side.type == BoundaryType::Inlet) return a;
      if (side.type == BoundaryType::Wall && !(side.velocity[0] == 0.0 && side.velocity[1] == 0.0 && side.velocity[2] == 0.0))
        return a;
    }
  return 3;
}

void fillVelocityGhosts(Field& u, int c, const Boundaries& bc, GhostMode mode, int firstAxis) {
  fillVelocityGhostsPlanes(u, c, bc, mode, GhostPlanes{}, firstAxis);
}

void fillVelocityGhostsPlanes(Field& u, int c, const Boundaries& bc, GhostMode mode, const GhostPlanes& planes,
                              int firstAxis) {
  // One loop per side and condition (the condition is decided once, not per grid line).
  const CartesianGrid& grid = u.grid();
  const int g = grid.ghosts;
  double* d = u.data().data();
  const bool full = mode == GhostMode::Full;
  exchangeGhosts(u, bc, allPlanes(planes));
  for (int a = firstAxis; a < 3; ++a) {
    const int n = grid.cells[a];
    const std::ptrdiff_t st = u.stride(a);
    if (a == 2 && !planes.lowZ && !planes.highZ) break;
    if (bc.periodic(a)) {
      if (c == a) {
        forEachLine(u, a, planes, [&](const int*, std::size_t base) {
          d[base + n * st] = d[base];
          for (int m = 1; m <= g; ++m) {
            d[base - m * st] = d[base + (n - m) * st];
            d[base + (n + m) * st] = d[base + m * st];
          }
        });
      } else {
        forEachLine(u, a, planes, [&](const int*, std::size_t base) {
          for (int m = 1; m <= g; ++m) {
            d[base - m * st] = d[base + (n - m) * st];
            d[base + (n - 1 + m) * st] = d[base + (m - 1) * st];
          }
        });
      }
      continue;
    }
    for (int s = 0; s < 2; ++s) {
      if (a == 2 && !(s == 0 ? planes.lowZ : planes.highZ)) continue;
      if (bc.shared(a, s)) continue;
      const BoundarySide& side = bc.at(a, s);
      const std::ptrdiff_t in = s == 0 ? st : -st;  // one point inwards
      if (c == a) {
        // Normal component: boundary face at 0 or n; at(k) = l[k * in] counts inwards from it.
        const std::ptrdiff_t face = s == 0 ? 0 : n * st;
        switch (side.type) {
          case BoundaryType::Wall:
          case BoundaryType::Slip:
            forEachLine(u, a, planes, [&](const int*, std::size_t base) {
              double* l = d + base + face;
              l[0] = 0.0;
              for (int m = 1; m <= g; ++m) l[-m * in] = -l[m * in];
            });
            break;
          case BoundaryType::Inlet: {
            const Field* eps = side.superficial ? bc.voidFraction : nullptr;
            const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            forEachLine(u, a, planes, [&](const int* coord, std::size_t base) {
              double value = 0.0;
              if (full) {
                Vec3 x;
                x[a] = grid.origin[a] + (s == 0 ? 0 : n) * grid.spacing[a];
                x[b1] = grid.origin[b1] + (coord[b1] + 0.5) * grid.spacing[b1];
                x[b2] = grid.origin[b2] + (coord[b2] + 0.5) * grid.spacing[b2];
                value = inletNormalVelocity(bc, a, s, grid, x);
                if (eps) {
                  // Superficial inlet: eps_f u_f = U at the face (continuity uses the same eps_f).
                  int cell[3];
                  cell[a] = s == 0 ? 0 : n - 1;
                  cell[b1] = coord[b1];
                  cell[b2] = coord[b2];
                  const std::size_t cc = eps->index(cell[0], cell[1], cell[2]);
                  const std::ptrdiff_t outward = (s == 0 ? -1 : 1) * eps->stride(a);
                  const double epsF = 0.5 * (eps->data()[cc] + eps->data()[cc + outward]);
                  if (epsF > 0.0) value /= epsF;
                }
              }
              double* l = d + base + face;
              l[0] = value;
              for (int m = 1; m <= g; ++m) l[-m * in] = value;
            });
            break;
          }
          default:  // outlets: the boundary face is set by the solver; ghosts copy it
            forEachLine(u, a, planes, [&](const int*, std::size_t base) {
              double* l = d + base + face;
              if (!full) l[0] = 0.0;
              for (int m = 1; m <= g; ++m) l[-m * in] = l[0];
            });
            break;
        }
      } else {
        // Tangential component: cell rows 0..n-1; at(k) = l[k * in], k = 0 next to the boundary.
        const std::ptrdiff_t row0 = s == 0 ? 0 : (n - 1) * st;
        switch (side.type) {
          case BoundaryType::Wall:
          case BoundaryType::Inlet: {
            const double uw = full ? side.velocity[c] * rampFactor(side, bc.time) : 0.0;
            // Quadratic through wall value, rows 0 and 1: exact for parabolic profiles.
            if (n >= 2)
              forEachLine(u, a, planes, [&](const int*, std::size_t base) {
                double* l = d + base + row0;
                l[-in] = (8.0 * uw - 6.0 * l[0] + l[in]) / 3.0;
                l[-2 * in] = 2.0 * uw - l[in];
              });
            else
              forEachLine(u, a, planes, [&](const int*, std::size_t base) {
                double* l = d + base + row0;
                l[-in] = 2.0 * uw - l[0];
                l[-2 * in] = l[-in];
              });
            break;
          }
          case BoundaryType::Slip:
            forEachLine(u, a, planes, [&](const int*, std::size_t base) {
              double* l = d + base + row0;
              for (int m = 1; m <= g; ++m) l[-m * in] = l[(n >= m ? m - 1 : 0) * in];
            });
            break;
          default:
            forEachLine(u, a, planes, [&](const int*, std::size_t base) {
              double* l = d + base + row0;
              for (int m = 1; m <= g; ++m) l[-m * in] = l[0];
            });
            break;
        }
      }
    }
  }
}

namespace {
/// fillVelocityStencilGhosts on the planes kBegin <= k < kEnd (x and y ghosts) and the z sides
/// flagged by lowZ / highZ; threaded = may start an OpenMP team for large faces.
void stencilGhosts(Field& u, int c, const Boundaries& bc, int kBegin, int kEnd, bool lowZ, bool highZ, bool threaded) {
  const CartesianGrid& grid = u.grid();
  const auto& pts = u.points();
  double* d = u.data().data();
  exchangeGhosts(u, bc, threaded && kBegin == 0 && kEnd == pts[2] && lowZ && highZ);
  for (int a = 0; a < 3; ++a) {
    const int n = grid.cells[a];
    const bool periodic = bc.periodic(a);
    if (!periodic && c == a) continue;  // boundary faces: kept by the sweeps
    if (a == 2 && !lowZ && !highZ) continue;
    // The two other axes, lower one innermost (contiguous rows for the y and z faces).
    const int lo = a == 0 ? 1 : 0, hi = a == 2 ? 1 : 2;
    const std::ptrdiff_t st = u.stride(a), sLo = u.stride(lo), sHi = u.stride(hi);
    const std::size_t origin = u.index(0, 0, 0);
    const int nLo = pts[lo], nHi = pts[hi];
    // Value of the first ghost from the boundary row (at0) and the next one (at1): tangential
    // components (c != a) as in fillVelocityGhosts; periodic axes copy from the other end.
    // Rows along the highest other axis: z planes kBegin..kEnd-1 for the x and y sides.
    const int qBegin = a == 2 ? 0 : kBegin, qEnd = a == 2 ? nHi : kEnd;
    auto forRows = [&](auto&& body) {
      auto row = [&](std::int64_t q) {
        const std::size_t base = origin + static_cast<std::size_t>(q) * sHi;
        for (int p = 0; p < nLo; ++p) body(base + static_cast<std::size_t>(p) * sLo);
      };
      if (!threaded || serialLoops() || static_cast<std::int64_t>(nLo) * nHi < kSerialElementsBelow / 8) {
        for (int q = qBegin; q < qEnd; ++q) row(q);
      } else {
#pragma omp parallel for schedule(static)
        for (int q = 0; q < nHi; ++q) row(q);
      }
    };
    if (periodic) {
      if (c == a) {
        forRows([&](std::size_t b) {
          d[b + n * st] = d[b];
          d[b - st] = d[b + (n - 1) * st];
        });
      } else {
        forRows([&](std::size_t b) {
          d[b - st] = d[b + (n - 1) * st];
          d[b + n * st] = d[b];
        });
      }
      continue;
    }
    for (int s = 0; s < 2; ++s) {
      if (a == 2 && !(s == 0 ? lowZ : highZ)) continue;
      if (bc.shared(a, s)) continue;
      const BoundarySide& side = bc.at(a, s);
      // at(k) = d[b + first + k * inward]: k = 0 is the row next to the boundary.
      const std::ptrdiff_t first = s == 0 ? 0 : (n - 1) * st, inward = s == 0 ? st : -st;
      switch (side.type) {
        case BoundaryType::Wall:
        case BoundaryType::Inlet: {
          const double uw = side.velocity[c] * rampFactor(side, bc.time);
          if (n >= 2)
            forRows([&](std::size_t b) {
              const std::size_t r0 = b + first;
              d[r0 - inward] = (8.0 * uw - 6.0 * d[r0] + d[r0 + inward]) / 3.0;
            });
          else
            forRows([&](std::size_t b) { d[b + first - inward] = 2.0 * uw - d[b + first]; });
          break;
        }
        default:  // slip and outlets: zero gradient
          forRows([&](std::size_t b) { d[b + first - inward] = d[b + first]; });
          break;
      }
    }
  }
}

}  // namespace

void fillVelocityStencilGhosts(Field& u, int c, const Boundaries& bc) {
  stencilGhosts(u, c, bc, 0, u.points()[2], true, true, true);
}

void fillVelocityStencilGhostsSlab(Field& u, int c, const Boundaries& bc, int kBegin, int kEnd, bool lowZ,
                                   bool highZ) {
  stencilGhosts(u, c, bc, kBegin, kEnd, lowZ, highZ, false);
}

void fillCellGhosts(Field& f, const Boundaries& bc, CellGhostKind kind) {
  fillCellGhostsPlanes(f, bc, kind, GhostPlanes{});
}

void fillCellGhostsPlanes(Field& f, const Boundaries& bc, CellGhostKind kind, const GhostPlanes& planes) {
  const CartesianGrid& grid = f.grid();
  const int g = grid.ghosts;
  double* d = f.data().data();
  exchangeGhosts(f, bc, allPlanes(planes));
  for (int a = 0; a < 3; ++a) {
    const int n = grid.cells[a];
    const std::ptrdiff_t st = f.stride(a);
    if (a == 2 && !planes.lowZ && !planes.highZ) break;
    if (bc.periodic(a)) {
      forEachLine(f, a, planes, [&](const int*, std::size_t base) {
        for (int m = 1; m <= g; ++m) {
          d[base - m * st] = d[base + (((n - m) % n + n) % n) * st];
          d[base + (n - 1 + m) * st] = d[base + ((m - 1) % n) * st];
        }
      });
      continue;
    }
    if (kind == CellGhostKind::PeriodicOnly) continue;
    for (int s = 0; s < 2; ++s) {
      if (a == 2 && !(s == 0 ? planes.lowZ : planes.highZ)) continue;
      if (bc.shared(a, s)) continue;
      const BoundarySide& side = bc.at(a, s);
      bool dirichlet = false;
      double value = 0.0;
      if (kind == CellGhostKind::Pressure && side.type == BoundaryType::PressureOutlet) {
        dirichlet = true;
        value = side.pressure;
      } else if (kind == CellGhostKind::PressureIncrement && side.type == BoundaryType::PressureOutlet) {
        dirichlet = true;
      } else if (kind == CellGhostKind::Scalar && side.scalarFixed) {
        dirichlet = true;
        value = side.scalarValue;
      }
      const std::ptrdiff_t row0 = s == 0 ? 0 : (n - 1) * st, in = s == 0 ? st : -st;
      if (dirichlet)
        forEachLine(f, a, planes, [&](const int*, std::size_t base) {
          double* l = d + base + row0;
          for (int m = 1; m <= g; ++m) l[-m * in] = 2.0 * value - l[std::min(m - 1, n - 1) * in];
        });
      else
        forEachLine(f, a, planes, [&](const int*, std::size_t base) {
          double* l = d + base + row0;
          for (int m = 1; m <= g; ++m) l[-m * in] = l[std::min(m - 1, n - 1) * in];
        });
    }
  }
}

}  // namespace gf::fluid
