#pragma once
// Resolve a drag law once, before a particle loop: the laws of the common CFD-DEM cases become a
// compile-time functor (inlined in the loop); any other law is called through its function
// pointer (one indirect call per particle, still no virtual call, no per-particle dispatch).
#include "coupling/drag/di_felice.hpp"
#include "coupling/drag/drag_law.hpp"
#include "coupling/drag/gidaspow.hpp"
#include "coupling/drag/schiller_naumann.hpp"

namespace gf::coupling {

template <CorrectionFunction F>
struct StaticCorrection {
  double operator()(double re, double eps) const { return F(re, eps); }
};

struct PointerCorrection {
  CorrectionFunction f;
  double operator()(double re, double eps) const { return f(re, eps); }
};

struct VirtualCorrection {  // a law that is not a pure function (none today)
  const DragLaw* law;
  double operator()(double re, double eps) const { return law->correction(re, eps); }
};

/// f[i] = law(re[i], eps[i]) for i in [0, n): one call per value, or the law's block form where it
/// has one (the same values bit for bit).
template <class Law>
inline void correctionsOf(const Law& law, const double* re, const double* eps, double* f, int n) {
  for (int i = 0; i < n; ++i) f[i] = law(re[i], eps[i]);
}
inline void correctionsOf(const StaticCorrection<&drag::gidaspow>&, const double* re, const double* eps, double* f,
                          int n) {
  drag::gidaspowBlock(re, eps, f, n);
}

/// Calls body(functor) with the law resolved to the cheapest functor type.
template <class Body>
void withDragCorrection(const DragLaw& law, Body&& body) {
  const CorrectionFunction f = law.function();
  if (f == &drag::gidaspow) body(StaticCorrection<&drag::gidaspow>{});
  else if (f == &drag::diFelice) body(StaticCorrection<&drag::diFelice>{});
  else if (f == &drag::schillerNaumann) body(StaticCorrection<&drag::schillerNaumann>{});
  else if (f) body(PointerCorrection{f});
  else body(VirtualCorrection{&law});
}

}  // namespace gf::coupling
