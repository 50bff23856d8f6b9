#pragma once
// The closing half kick of velocity Verlet, v += (dt/2) F/m and w += (dt/2) T/I, as its own pass
// after the force evaluation (contact_kernel.hpp), with the per-particle 1/m and 1/I it reads.
// A pass of its own: every force is final before any particle is kicked, so the forces of
// particles held by other processes can be added in between.
#include <omp.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/cpu_features.hpp"
#include "core/parallel.hpp"
#include "core/vec3.hpp"
#include "dem/particles.hpp"

namespace gf::dem {

/// 1/m and 1/I per particle (I = 2/5 m r^2), kept by the System, so that the integration and the
/// kicks multiply instead of dividing.
struct InverseInertia {
  const double* mass;    // 1/m, 1/kg
  const double* moment;  // 1/I, 1/(kg m^2)
  /// Every particle has the radius, mass and type of particle 0 (a monodisperse bed of one
  /// material): the sweep then reads these per-particle values at index 0 (identicalIndexMask).
  bool identical = false;
};

/// Index mask for the per-particle constants (radius, mass, type, 1/m, 1/I) of the contact sweep:
/// all ones, or zero when every particle has particle 0's values. The loads x[i & mask] then stay
/// on one cache line instead of a line per partner and per row (the values are the same, so are
/// the results: bit-identical either way). The bubbling bed (24,750 identical spheres): contacts
/// -10 % on one thread (docs/dem.md, Performance).
inline std::uint32_t identicalIndexMask(bool identical) { return identical ? 0u : ~0u; }

/// The half kick of the particles [begin, end). SharedLines: the block follows another thread's
/// block, whose sweep read the velocities of this block's first particles (its rows list them):
/// the lines are requested for writing some particles ahead, as in the drift (System::step).
template <bool SharedLines>
inline void halfKickRange(Vec3* __restrict v, Vec3* __restrict w, const Vec3* __restrict f,
                          const Vec3* __restrict tq, const double* __restrict im, const double* __restrict ii,
                          std::size_t at, double h, std::int64_t begin, std::int64_t end) {
  constexpr std::int64_t kAhead = 24;
  for (std::int64_t q = begin; q < end; ++q) {
    if constexpr (SharedLines) {
      if (q + kAhead < end) {
        prefetchForWrite(v + q + kAhead);
        prefetchForWrite(w + q + kAhead);
      }
    }
    const auto qa = static_cast<std::size_t>(q) & at;
    v[q] += (h * im[qa]) * f[q];
    w[q] += (h * ii[qa]) * tq[q];
  }
}

/// The closing half kick v += halfKick F/m, w += halfKick T/I of every particle. Each particle's
/// kick reads only its own force and torque, so the result does not depend on the order or on
/// the split. With a team, each thread kicks the block of rows it swept in the force evaluation
/// (`blocks`, PartnerBuffers::blockStart: its particles' forces are in its cache).
inline void closingHalfKick(ParticleSet& p, double halfKick, const InverseInertia& inverse,
                            const std::vector<std::size_t>& blocks) {
  const auto n = static_cast<std::int64_t>(p.size());
  Vec3* v = p.velocity.data();
  Vec3* w = p.angularVelocity.data();
  const Vec3* f = p.force.data();
  const Vec3* tq = p.torque.data();
  const std::size_t at = identicalIndexMask(inverse.identical);
  const int threads = omp_get_max_threads();
  if (threads <= 1 || blocks.size() != static_cast<std::size_t>(threads) + 1 ||
      blocks.back() != static_cast<std::size_t>(n)) {
    parallelFor(n, [&](std::int64_t q) {
      const auto qa = static_cast<std::size_t>(q) & at;
      v[q] += (halfKick * inverse.mass[qa]) * f[q];
      w[q] += (halfKick * inverse.moment[qa]) * tq[q];
    });
    return;
  }
  const bool requestLines = cpuHasPrefetchW();
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const bool own = omp_get_num_threads() == threads;  // (fewer delivered: member 0 kicks all)
    const auto begin = static_cast<std::int64_t>(own ? blocks[t] : 0);
    const auto end = own ? static_cast<std::int64_t>(blocks[t + 1]) : (t == 0 ? n : 0);
    if (requestLines && own && t > 0)
      halfKickRange<true>(v, w, f, tq, inverse.mass, inverse.moment, at, halfKick, begin, end);
    else
      halfKickRange<false>(v, w, f, tq, inverse.mass, inverse.moment, at, halfKick, begin, end);
  }
}

}  // namespace gf::dem
