#include "fluid/hypre_pressure.hpp"

#include <HYPRE_struct_ls.h>
#include <HYPRE_utilities.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "parallel/environment.hpp"

namespace gf::fluid {

namespace {
// Stencil entries: the cell, then its low and high neighbour along x, y and z.
constexpr int kEntries = 7;
constexpr int kOffsets[kEntries][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

void check(HYPRE_Int code, const char* what) {
  if (code == 0) return;
  char message[256] = {};
  HYPRE_DescribeError(code, message);
  HYPRE_ClearAllErrors();
  throw Error(std::string("hypre: ") + what + " failed: " + message);
}

/// hypre's library state (HYPRE_Init after MPI_Init, HYPRE_Finalize before MPI_Finalize), once.
void initialiseHypre() {
  static bool done = false;
  if (done) return;
  parallel::Environment& env = parallel::Environment::instance();
  HYPRE_Init();
  env.atFinalize([] { HYPRE_Finalize(); });
  done = true;
}
}  // namespace

struct HyprePressure::Impl {
  HYPRE_StructGrid grid = nullptr;
  HYPRE_StructStencil stencil = nullptr;
  HYPRE_StructMatrix A = nullptr;
  HYPRE_StructVector b = nullptr, x = nullptr;
  HYPRE_StructSolver pcg = nullptr, pfmg = nullptr;
  std::array<HYPRE_Int, 3> lower{}, upper{};  // the box, inclusive upper corner
  // The preconditioner's gauge (singular problems): z = PFMG(r), then the mean over the coupled
  // cells removed, as the multigrid's preconditioner does (MultigridPoisson::solveMgpcg). Without it, round-off lets the
  // preconditioned residual pick up the constant null vector, which PFMG's relaxation on the
  // coarsest (singular) level does not damp, and CG breaks down (alpha <= 0) before the tolerance.
  bool gauge = false;
  bool own = false;  // the whole grid on this process (sums stay local)
  const std::vector<double>* diag = nullptr;
  double activeCells = 0.0;
  std::vector<double> scratch;

  static HYPRE_Int preconditionSetup(HYPRE_StructSolver data, HYPRE_StructMatrix A, HYPRE_StructVector b,
                                     HYPRE_StructVector x) {
    return HYPRE_StructPFMGSetup(reinterpret_cast<Impl*>(data)->pfmg, A, b, x);
  }
  static HYPRE_Int precondition(HYPRE_StructSolver data, HYPRE_StructMatrix A, HYPRE_StructVector r,
                                HYPRE_StructVector z) {
    Impl& h = *reinterpret_cast<Impl*>(data);
    const HYPRE_Int code = HYPRE_StructPFMGSolve(h.pfmg, A, r, z);
    if (!h.gauge || h.activeCells == 0.0) return code;
    HYPRE_StructVectorGetBoxValues(z, h.lower.data(), h.upper.data(), h.scratch.data());
    const std::vector<double>& d = *h.diag;
    double local = 0.0;
    for (std::size_t c = 0; c < d.size(); ++c) local += d[c] > 0.0 ? h.scratch[c] : 0.0;
    const double mean = (h.own ? local : parallel::Environment::instance().sum(local)) / h.activeCells;
    for (std::size_t c = 0; c < d.size(); ++c) h.scratch[c] = d[c] > 0.0 ? h.scratch[c] - mean : 0.0;
    HYPRE_StructVectorSetBoxValues(z, h.lower.data(), h.upper.data(), h.scratch.data());
    return code;
  }

  void destroySolvers() {
    if (pcg) HYPRE_StructPCGDestroy(pcg);
    if (pfmg) HYPRE_StructPFMGDestroy(pfmg);
    pcg = pfmg = nullptr;
  }
  void destroyLayout() {
    destroySolvers();
    if (x) HYPRE_StructVectorDestroy(x);
    if (b) HYPRE_StructVectorDestroy(b);
    if (A) HYPRE_StructMatrixDestroy(A);
    if (stencil) HYPRE_StructStencilDestroy(stencil);
    if (grid) HYPRE_StructGridDestroy(grid);
    x = b = nullptr;
    A = nullptr;
    stencil = nullptr;
    grid = nullptr;
  }
  ~Impl() { destroyLayout(); }
};

HyprePressure::HyprePressure(bool own) : own_(own) {}
HyprePressure::~HyprePressure() = default;

void HyprePressure::setup(const PressureBox& box, const std::array<bool, 3>& periodic,
                          const std::array<std::vector<double>, 3>& T, const std::array<bool, 6>& dirichlet) {
  const std::size_t cells = static_cast<std::size_t>(box.n[0]) * box.n[1] * box.n[2];
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = box.n;
    fn[a] += 1;
    if (T[a].size() != static_cast<std::size_t>(fn[0]) * fn[1] * fn[2])
      throw Error("HyprePressure::setup: face array " + std::to_string(a) + " does not match the box");
  }
  initialiseHypre();
  parallel::Environment& env = parallel::Environment::instance();
  MPI_Comm comm = own_ ? MPI_COMM_SELF : env.communicator();
  singular_ = true;
  for (bool d : dirichlet) singular_ = singular_ && !d;

  // Grid, stencil and vectors: once per layout (box and periodic axes).
  const bool newLayout = !impl_ || !(box == box_) || periodic != periodic_;
  if (newLayout) {
    if (!impl_) impl_ = std::make_unique<Impl>();
    impl_->destroyLayout();
    box_ = box;
    periodic_ = periodic;
    Impl& h = *impl_;
    for (int a = 0; a < 3; ++a) {
      h.lower[a] = box.lower[a];
      h.upper[a] = box.lower[a] + box.n[a] - 1;
    }
    check(HYPRE_StructGridCreate(comm, 3, &h.grid), "StructGridCreate");
    check(HYPRE_StructGridSetExtents(h.grid, h.lower.data(), h.upper.data()), "StructGridSetExtents");
    // A periodic axis of one cell couples a cell to itself only: no coupling, not periodic for hypre.
    HYPRE_Int period[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) period[a] = periodic[a] && box.global[a] > 1 ? box.global[a] : 0;
    check(HYPRE_StructGridSetPeriodic(h.grid, period), "StructGridSetPeriodic");
    check(HYPRE_StructGridAssemble(h.grid), "StructGridAssemble");
    check(HYPRE_StructStencilCreate(3, kEntries, &h.stencil), "StructStencilCreate");
    for (int e = 0; e < kEntries; ++e) {
      HYPRE_Int offset[3] = {kOffsets[e][0], kOffsets[e][1], kOffsets[e][2]};
      check(HYPRE_StructStencilSetElement(h.stencil, e, offset), "StructStencilSetElement");
    }
    check(HYPRE_StructMatrixCreate(comm, h.grid, h.stencil, &h.A), "StructMatrixCreate");
    check(HYPRE_StructMatrixInitialize(h.A), "StructMatrixInitialize");
    check(HYPRE_StructVectorCreate(comm, h.grid, &h.b), "StructVectorCreate");
    check(HYPRE_StructVectorInitialize(h.b), "StructVectorInitialize");
    check(HYPRE_StructVectorCreate(comm, h.grid, &h.x), "StructVectorCreate");
    check(HYPRE_StructVectorInitialize(h.x), "StructVectorInitialize");
  }
  Impl& h = *impl_;

  // Matrix entries per cell (entries fastest, cells x fastest: hypre's box order), the operator of
  // MultigridPoisson: off-diagonal -T_f to each coupled neighbour, diagonal = sum of the coupled
  // faces' T (2 T on a Dirichlet boundary face, nothing on a Neumann one).
  values_.assign(cells * kEntries, 0.0);
  diag_.assign(cells, 0.0);
  double active = 0.0;
  const int nx = box.n[0], ny = box.n[1];
  for (int k = 0; k < box.n[2]; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int idx[3] = {i, j, k};
        const std::size_t c = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
        double* v = values_.data() + kEntries * c;
        double d = 0.0;
        for (int a = 0; a < 3; ++a) {
          if (box.global[a] == 1 && periodic[a]) continue;  // one periodic cell couples to itself only
          std::array<int, 3> fn = box.n;
          fn[a] += 1;
          int hi[3] = {i, j, k};
          hi[a] += 1;
          const auto face = [&](const int* f) {
            return static_cast<std::size_t>(f[0]) + static_cast<std::size_t>(fn[0]) * (f[1] + static_cast<std::size_t>(fn[1]) * f[2]);
          };
          const double tl = T[a][face(idx)], th = T[a][face(hi)];
          const int g = box.lower[a] + idx[a];
          const bool lowBoundary = g == 0 && !periodic[a], highBoundary = g == box.global[a] - 1 && !periodic[a];
          if (lowBoundary) {
            d += dirichlet[2 * a] ? 2.0 * tl : 0.0;
          } else {
            d += tl;
            v[1 + 2 * a] = -tl;
          }
          if (highBoundary) {
            d += dirichlet[2 * a + 1] ? 2.0 * th : 0.0;
          } else {
            d += th;
            v[2 + 2 * a] = -th;
          }
        }
        diag_[c] = d;
        // A cell without coupling (blocked): the identity row, x = 0 from b = 0.
        v[0] = d > 0.0 ? d : 1.0;
        active += d > 0.0 ? 1.0 : 0.0;
      }
  activeCells_ = own_ ? active : env.sum(active);
  HYPRE_Int entries[kEntries] = {0, 1, 2, 3, 4, 5, 6};
  check(HYPRE_StructMatrixSetBoxValues(h.A, h.lower.data(), h.upper.data(), kEntries, entries, values_.data()),
        "StructMatrixSetBoxValues");
  check(HYPRE_StructMatrixAssemble(h.A), "StructMatrixAssemble");

  // PCG + one PFMG V-cycle as preconditioner (symmetric: weighted Jacobi smoothing, as many sweeps
  // after as before), set up on the new coefficients.
  h.destroySolvers();
  check(HYPRE_StructPCGCreate(comm, &h.pcg), "StructPCGCreate");
  HYPRE_StructPCGSetTwoNorm(h.pcg, 1);  // the test ||r||_2 <= tol ||b||_2 of MultigridPoisson
  HYPRE_StructPCGSetRelChange(h.pcg, 0);
  HYPRE_StructPCGSetLogging(h.pcg, 1);
  check(HYPRE_StructPFMGCreate(comm, &h.pfmg), "StructPFMGCreate");
  HYPRE_StructPFMGSetMaxIter(h.pfmg, 1);
  HYPRE_StructPFMGSetTol(h.pfmg, 0.0);
  HYPRE_StructPFMGSetZeroGuess(h.pfmg);
  HYPRE_StructPFMGSetRelaxType(h.pfmg, 1);
  HYPRE_StructPFMGSetNumPreRelax(h.pfmg, 1);
  HYPRE_StructPFMGSetNumPostRelax(h.pfmg, 1);
  h.gauge = singular_;
  h.own = own_;
  h.diag = &diag_;
  h.activeCells = activeCells_;
  h.scratch.resize(cells);
  HYPRE_StructPCGSetPrecond(h.pcg, Impl::precondition, Impl::preconditionSetup, reinterpret_cast<HYPRE_StructSolver>(&h));
  check(HYPRE_StructPCGSetup(h.pcg, h.A, h.b, h.x), "StructPCGSetup");
  ++setups_;
}

PoissonResult HyprePressure::solve(std::vector<double>& x, const std::vector<double>& b, double tol, int maxIterations) {
  if (!impl_) throw Error("HyprePressure::solve before setup");
  Impl& h = *impl_;
  parallel::Environment& env = parallel::Environment::instance();
  const std::size_t cells = diag_.size();
  if (x.size() != cells || b.size() != cells) throw Error("HyprePressure::solve: vectors do not match the box");
  PoissonResult result;
  // Right-hand side on the coupled cells, with the mean removed for a singular problem (a
  // compatible right-hand side, as MultigridPoisson does).
  values_.resize(cells);
  auto removeMean = [&](std::vector<double>& v) {
    if (activeCells_ == 0.0) return;
    double local = 0.0;
    for (std::size_t c = 0; c < cells; ++c) local += diag_[c] > 0.0 ? v[c] : 0.0;
    const double mean = (own_ ? local : env.sum(local)) / activeCells_;
    for (std::size_t c = 0; c < cells; ++c) v[c] = diag_[c] > 0.0 ? v[c] - mean : 0.0;
  };
  for (std::size_t c = 0; c < cells; ++c) values_[c] = diag_[c] > 0.0 ? b[c] : 0.0;
  if (singular_) removeMean(values_);
  double local = 0.0;
  for (double v : values_) local += v * v;
  if ((own_ ? local : env.sum(local)) == 0.0) {
    std::fill(x.begin(), x.end(), 0.0);
    return result;
  }
  check(HYPRE_StructVectorSetBoxValues(h.b, h.lower.data(), h.upper.data(), values_.data()), "StructVectorSetBoxValues");
  check(HYPRE_StructVectorAssemble(h.b), "StructVectorAssemble");
  for (std::size_t c = 0; c < cells; ++c) values_[c] = diag_[c] > 0.0 ? x[c] : 0.0;
  check(HYPRE_StructVectorSetBoxValues(h.x, h.lower.data(), h.upper.data(), values_.data()), "StructVectorSetBoxValues");
  check(HYPRE_StructVectorAssemble(h.x), "StructVectorAssemble");

  HYPRE_StructPCGSetTol(h.pcg, tol);
  HYPRE_StructPCGSetMaxIter(h.pcg, maxIterations);
  const HYPRE_Int code = HYPRE_StructPCGSolve(h.pcg, h.A, h.b, h.x);
  // Not converging within maxIterations is reported through the result, not as an error.
  if (code != 0 && !HYPRE_CheckError(code, HYPRE_ERROR_CONV)) check(code, "StructPCGSolve");
  HYPRE_ClearAllErrors();
  HYPRE_Int iterations = 0;
  double residual = 0.0;
  HYPRE_StructPCGGetNumIterations(h.pcg, &iterations);
  HYPRE_StructPCGGetFinalRelativeResidualNorm(h.pcg, &residual);
  check(HYPRE_StructVectorGetBoxValues(h.x, h.lower.data(), h.upper.data(), x.data()), "StructVectorGetBoxValues");
  if (singular_) removeMean(x);
  for (std::size_t c = 0; c < cells; ++c)
    if (!(diag_[c] > 0.0)) x[c] = 0.0;
  result.iterations = static_cast<int>(iterations);
  result.relativeResidual = residual;
  result.converged = residual <= tol;
  return result;
}

}  // namespace gf::fluid
