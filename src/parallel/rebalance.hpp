#pragma once
// Load balancing of the particles: a recursive coordinate bisection (RCB, Zoltan's
// implementation: Boman et al., "The Zoltan and Isorropia parallel toolkits for combinatorial
// scientific computing", Sci. Prog. 20 (2012); Berger & Bokhari, IEEE Trans. Comput. 36 (1987))
// of weighted points spread over the ranks into one box per rank. The cut tree splits space, so
// its boxes, clipped to the domain, tile the domain; they become the explicit boxes of a
// Decomposition. The caller decides when (DEM: parallel.rebalance_interval and
// parallel.rebalance_threshold) and moves its particles.
#include <cstdint>
#include <vector>

#include "core/domain.hpp"
#include "core/vec3.hpp"
#include "parallel/decomposition.hpp"

namespace gf::parallel {

/// max / mean of the per-rank loads (1 when all are equal or all zero).
double imbalance(const std::vector<double>& loads);

/// Boxes, one per part, from a recursive coordinate bisection of the points of every rank (each
/// rank passes its own: ids, positions and weights of the same length), clipped to the domain.
/// Collective over all ranks; every rank returns rank 0's boxes (one answer everywhere). The
/// points are handed to Zoltan in the order of their ids, so the same points give the same boxes.
/// Runs on one rank too (any number of parts). Throws std::runtime_error when Zoltan fails.
std::vector<Box> bisect(const Domain& domain, const std::vector<std::int64_t>& ids, const std::vector<Vec3>& points,
                        const std::vector<double>& weights, int parts);

}  // namespace gf::parallel
