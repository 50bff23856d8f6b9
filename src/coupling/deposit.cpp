#include "coupling/deposit.hpp"

#include <omp.h>

#include <algorithm>

namespace gf::coupling {

void depositToFields(const ParticleStencils& stencils, const double* values, int channels,
                     const std::vector<Field*>& fields) {
  const std::size_t cells = fields.front()->data().size();
  for (Field* f : fields) f->fill(0.0);
  const auto n = static_cast<std::int64_t>(stencils.size());
  const int threads = omp_get_max_threads();
  if (threads == 1 || n < 1024) {
    for (std::int64_t p = 0; p < n; ++p) {
      const std::size_t base = static_cast<std::size_t>(p) * stencils.capacity;
      for (int e = 0; e < stencils.count[p]; ++e) {
        const std::size_t c = stencils.cell[base + e];
        const double w = stencils.weight[base + e];
        for (int ch = 0; ch < channels; ++ch) fields[ch]->data()[c] += w * values[p * channels + ch];
      }
    }
    return;
  }
  std::vector<std::vector<double>> buffers(threads);
  int team = 1;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
#pragma omp single
    team = omp_get_num_threads();  // implicit barrier: every member sees it
    std::vector<double>& buf = buffers[t];
    buf.assign(cells * channels, 0.0);
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::size_t base = static_cast<std::size_t>(p) * stencils.capacity;
      for (int e = 0; e < stencils.count[p]; ++e) {
        const std::size_t c = stencils.cell[base + e];
        const double w = stencils.weight[base + e];
        for (int ch = 0; ch < channels; ++ch) buf[c * channels + ch] += w * values[p * channels + ch];
      }
    }
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(cells); ++c)
      for (int ch = 0; ch < channels; ++ch) {
        double sum = 0.0;
        for (int tt = 0; tt < team; ++tt) sum += buffers[tt][c * channels + ch];
        fields[ch]->data()[c] = sum;
      }
  }
}

}  // namespace gf::coupling
