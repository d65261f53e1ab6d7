#include "deform/biharmonic_solver.h"
#include "mesh/clock.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace adasculpt::deform {

namespace {
using SpMat = Eigen::SparseMatrix<double>;
}  // namespace

void BiharmonicSystem::clear(int free, int rows) {
  n_free = free;
  n_rows = rows;
  row.clear();
  col.clear();
  value.clear();
  inv_mass.assign(rows, 0.0);
  known_rhs.assign(rows, 0.0);
}

struct AmortizedLdlt;

struct BiharmonicSolver::Impl {
  Eigen::SimplicialLDLT<SpMat> ldlt;
  bool has_pattern = false, has_factor = false;
  std::vector<SpMat::StorageIndex> outer, inner;  // pattern of the analysed matrix
  std::vector<Eigen::Triplet<double>> triplets;
  BiharmonicStats stats;
  std::unique_ptr<AmortizedLdlt> amortized;
  double amortized_work = 0;  // of the last advance_amortized()

  bool same_pattern(const SpMat& a) const {
    if (!has_pattern || a.rows() + 1 != static_cast<Eigen::Index>(outer.size())) return false;
    if (a.nonZeros() != static_cast<Eigen::Index>(inner.size())) return false;
    return std::equal(outer.begin(), outer.end(), a.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), a.innerIndexPtr());
  }
  void remember_pattern(const SpMat& a) {
    outer.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.rows() + 1);
    inner.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
    has_pattern = true;
  }
};

BiharmonicSolver::BiharmonicSolver() : impl_(std::make_unique<Impl>()) {}

const BiharmonicStats& BiharmonicSolver::stats() const { return impl_->stats; }
void BiharmonicSolver::reset() {
  impl_->has_pattern = false;
  impl_->has_factor = false;
}

void BiharmonicSolver::solve(const BiharmonicSystem& sys, std::vector<double>& x, FieldReuse reuse,
                             int max_refinement_steps, double refinement_tolerance,
                             std::vector<double>* laplacian) {
  Impl& m = *impl_;
  m.stats = BiharmonicStats{};
  x.assign(sys.n_free, 0.0);
  if (sys.n_free == 0) return;
  auto t = Clock::now();
  m.triplets.clear();
  m.triplets.reserve(sys.value.size());
  for (size_t i = 0; i < sys.value.size(); ++i) m.triplets.emplace_back(sys.row[i], sys.col[i], sys.value[i]);
  SpMat b_mat(sys.n_rows, sys.n_free);
  b_mat.setFromTriplets(m.triplets.begin(), m.triplets.end());
  Eigen::Map<const Eigen::VectorXd> inv_mass(sys.inv_mass.data(), sys.n_rows);
  Eigen::Map<const Eigen::VectorXd> g(sys.known_rhs.data(), sys.n_rows);
  SpMat bt = b_mat.transpose();
  SpMat a = bt * inv_mass.asDiagonal() * b_mat;
  a.makeCompressed();
  Eigen::VectorXd rhs = -(bt * inv_mass.cwiseProduct(g));
  m.stats.assemble_ms = ms_since(t);

  Eigen::Map<Eigen::VectorXd> xv(x.data(), sys.n_free);
  const bool same = m.same_pattern(a);
  const double bn = std::max(rhs.norm(), 1e-300);
  bool carried = false;
  if (reuse == FieldReuse::CarryFactorization && same && m.has_factor) {
    // Conjugate gradients preconditioned with the old factors (plain iterative refinement
    // diverges: the bi-Laplacian is so ill-conditioned that a 1% change of the cotan weights
    // already takes the spectral radius of I - F_old^-1 A above 1). Falls back to a fresh
    // factorisation when the residual is not below the tolerance after the allowed steps.
    t = Clock::now();
    xv = m.ldlt.solve(rhs);
    Eigen::VectorXd r = rhs - a * xv;
    Eigen::VectorXd z = m.ldlt.solve(r);
    Eigen::VectorXd p = z;
    double rz = r.dot(z);
    for (int k = 0; k < max_refinement_steps && r.norm() / bn > refinement_tolerance; ++k) {
      const Eigen::VectorXd ap = a * p;
      const double alpha = rz / p.dot(ap);
      xv += alpha * p;
      r -= alpha * ap;
      z = m.ldlt.solve(r);
      const double rz_new = r.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
      ++m.stats.refinement_steps;
    }
    m.stats.solve_ms = ms_since(t);
    carried = (rhs - a * xv).norm() / bn <= refinement_tolerance;
  }
  if (!carried) {
    if (!same) {
      t = Clock::now();
      m.ldlt.analyzePattern(a);
      m.remember_pattern(a);
      m.stats.analyzed = true;
      m.stats.analyze_ms = ms_since(t);
    }
    t = Clock::now();
    m.ldlt.factorize(a);
    m.stats.factorize_ms = ms_since(t);
    if (m.ldlt.info() != Eigen::Success) {
      m.has_factor = false;
      throw std::runtime_error("biharmonic field: factorisation failed (degenerate region of interest)");
    }
    m.has_factor = true;
    m.stats.factorized = true;
    t = Clock::now();
    xv = m.ldlt.solve(rhs);
    m.stats.solve_ms = ms_since(t);
  }
  m.stats.relative_residual = (rhs - a * xv).norm() / bn;
  if (laplacian) {
    laplacian->resize(sys.n_rows);
    Eigen::Map<Eigen::VectorXd>(laplacian->data(), sys.n_rows) = inv_mass.cwiseProduct(b_mat * xv + g);
  }
}

// ---------------------------------------------------------------------------------------------
// Amortised solve. The factorisation is the up-looking LDL^T: row k of L solves a sparse
// triangular system with the rows above, whose pattern is the set of elimination-tree paths from
// the nonzeros of column k of the (permuted, upper) matrix; the symbolic pass counts each
// column's entries the same way. Everything lives in flat arrays, so the loop over k can stop
// after any row and resume at the next call.
struct AmortizedLdlt {
  enum Stage { kIdle, kAssemble, kOrder, kPermute, kSymbolic, kNumeric, kSolve, kDone } stage = kIdle;
  BiharmonicSystem system;
  SpMat a, upper;  // the product matrix; its permuted upper triangle (column k: rows <= k)
  Eigen::VectorXd rhs;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;  // perm.indices()[old] = new
  std::vector<int> parent, flag, lnz, lp, li, pattern;
  std::vector<double> lx, d, y;
  int next_row = 0;
  std::vector<double> solution, laplacian;

  // Scratch of assemble() and order(), kept between refreshes (no allocation once warm).
  std::vector<int> row_ptr, row_cols, col_ptr, col_rows, mark, a_outer, a_inner, column;
  std::vector<double> row_vals, col_vals, acc, a_vals;
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> pattern_copy;

  // A = B^T M^-1 B column by column with a dense accumulator (B by rows and by columns through
  // counting sorts), and rhs = -B^T M^-1 g. Eigen's triplets, transpose and sparse product did the
  // same in about 6x the instructions (34M of a 10k-vertex ROI's first grab frame, callgrind).
  void assemble() {
    const int nr = system.n_rows, nf = system.n_free;
    const size_t ne = system.value.size();
    auto bucket = [&](const std::vector<int>& key, int n, const std::vector<int>& other, std::vector<int>& ptr,
                      std::vector<int>& idx, std::vector<double>& val) {
      ptr.assign(size_t(n) + 1, 0);
      for (size_t e = 0; e < ne; ++e) ++ptr[size_t(key[e]) + 1];
      for (int i = 0; i < n; ++i) ptr[size_t(i) + 1] += ptr[size_t(i)];
      idx.resize(ne);
      val.resize(ne);
      column.assign(ptr.begin(), ptr.end() - 1);  // fill positions
      for (size_t e = 0; e < ne; ++e) {
        const int at = column[size_t(key[e])]++;
        idx[size_t(at)] = other[e];
        val[size_t(at)] = system.value[e];
      }
    };
    bucket(system.row, nr, system.col, row_ptr, row_cols, row_vals);
    bucket(system.col, nf, system.row, col_ptr, col_rows, col_vals);
    mark.assign(size_t(nf), -1);
    acc.assign(size_t(nf), 0.0);
    a_outer.assign(size_t(nf) + 1, 0);
    size_t bound = 0;  // the scatter's length: an upper bound of nnz(A)
    for (int r = 0; r < nr; ++r) {
      const size_t len = size_t(row_ptr[size_t(r) + 1] - row_ptr[size_t(r)]);
      bound += len * len;
    }
    a_inner.resize(bound);
    a_vals.resize(bound);
    rhs.resize(nf);
    const int *cpp = col_ptr.data(), *crow = col_rows.data(), *rpp = row_ptr.data(), *rcol = row_cols.data();
    const double *cval = col_vals.data(), *rval = row_vals.data(), *im = system.inv_mass.data(),
                 *g = system.known_rhs.data();
    int* mk = mark.data();
    int* inner = a_inner.data();
    double* ac = acc.data();
    int nnz = 0;
    for (int j = 0; j < nf; ++j) {
      const int first = nnz;
      double r_j = 0;
      for (int p = cpp[j]; p < cpp[j + 1]; ++p) {
        const int r = crow[p];
        const double s = cval[p] * im[r];
        r_j -= s * g[r];
        for (int q = rpp[r]; q < rpp[r + 1]; ++q) {
          const int k = rcol[q];
          if (mk[k] != j) {
            mk[k] = j;
            ac[k] = 0.0;
            inner[nnz++] = k;
          }
          ac[k] += s * rval[q];
        }
      }
      std::sort(inner + first, inner + nnz);  // ~20 entries: Eigen wants them sorted
      for (int p = first; p < nnz; ++p) a_vals[size_t(p)] = ac[inner[p]];
      a_outer[size_t(j) + 1] = nnz;
      rhs[j] = r_j;
    }
    // Straight into a's arrays (assigning an Eigen::Map copied entry by entry: 9M instructions).
    a.resize(nf, nf);
    a.resizeNonZeros(nnz);
    std::copy(a_outer.begin(), a_outer.end(), a.outerIndexPtr());
    std::copy(a_inner.begin(), a_inner.begin() + nnz, a.innerIndexPtr());
    std::copy(a_vals.begin(), a_vals.begin() + nnz, a.valuePtr());
  }
  void order() {
    // AMD on the product's own pattern: it is complete and symmetric with its diagonal, so
    // AMDOrdering's A + A^T (a third of the ordering's cost) is not needed.
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> pinv;
    pattern_copy = a;  // minimum_degree_ordering works in place
    Eigen::internal::minimum_degree_ordering(pattern_copy, pinv);
    perm = pinv.inverse();
  }
  // A step of its own: with the ordering, one frame of a 10k-vertex ROI's pull did 29M
  // instructions of solver work (the permutation 5M of them).
  void permute() {
    upper.resize(a.rows(), a.cols());
    upper.selfadjointView<Eigen::Upper>() = a.selfadjointView<Eigen::Lower>().twistedBy(perm);
    upper.makeCompressed();
  }
  // The work of the next step when it runs in one piece, in multiply-adds (about 10
  // instructions each natively, as the numeric rows count them); 0 for the numeric rows, which
  // stop at their allowance. From sizes only, so that a replay does the same steps everywhere.
  double estimate() const {
    switch (stage) {
      // Calibrated with callgrind on the dragon's 10k-vertex ROI (instructions / 10).
      case kAssemble: return 25.0 * double(system.value.size());
      case kOrder: return 14.0 * double(a.nonZeros());
      case kPermute: return 3.0 * double(a.nonZeros());
      case kSymbolic: return 20.0 * double(upper.nonZeros());
      case kSolve: return 2.0 * double(lp.back()) + double(system.value.size());
      default: return 0.0;
    }
  }
  void symbolic() {
    const int n = int(upper.cols());
    const int* cp = upper.outerIndexPtr();
    const int* ci = upper.innerIndexPtr();
    parent.assign(n, -1);
    flag.assign(n, -1);
    lnz.assign(n, 0);
    for (int k = 0; k < n; ++k) {
      flag[k] = k;
      for (int p = cp[k]; p < cp[k + 1]; ++p)
        for (int i = ci[p]; i < k && flag[i] != k; i = parent[i]) {
          if (parent[i] == -1) parent[i] = k;
          ++lnz[i];
          flag[i] = k;
        }
    }
    lp.assign(n + 1, 0);
    for (int k = 0; k < n; ++k) lp[k + 1] = lp[k] + lnz[k];
    li.resize(lp[n]);
    lx.resize(lp[n]);
    d.assign(n, 0.0);
    y.assign(n, 0.0);
    pattern.assign(n, 0);
    std::fill(lnz.begin(), lnz.end(), 0);
    std::fill(flag.begin(), flag.end(), -1);
    next_row = 0;
  }
  // Rows of L and D from next_row on, until `allowance` multiply-adds are done (at least one
  // row); returns the multiply-adds done.
  double numeric(double allowance) {
    const int n = int(upper.cols());
    const int* cp = upper.outerIndexPtr();
    const int* ci = upper.innerIndexPtr();
    const double* cx = upper.valuePtr();
    double work = 0;
    int k = next_row;
    for (; k < n && (k == next_row || work < allowance); ++k) {
      work += cp[k + 1] - cp[k];
      int top = n;
      flag[k] = k;
      for (int p = cp[k]; p < cp[k + 1]; ++p) {
        int i = ci[p];
        y[i] += cx[p];
        int len = 0;
        for (; flag[i] != k; i = parent[i]) {  // the path up the tree to an already visited node
          pattern[len++] = i;
          flag[i] = k;
        }
        while (len > 0) pattern[--top] = pattern[--len];
      }
      d[k] = y[k];
      y[k] = 0.0;
      for (; top < n; ++top) {
        const int i = pattern[top];
        const double yi = y[i];
        y[i] = 0.0;
        const int p_end = lp[i] + lnz[i];
        work += lnz[i] + 1;
        for (int p = lp[i]; p < p_end; ++p) y[li[p]] -= lx[p] * yi;
        const double l_ki = yi / d[i];
        d[k] -= l_ki * yi;
        li[p_end] = k;
        lx[p_end] = l_ki;
        ++lnz[i];
      }
      if (d[k] == 0 || !std::isfinite(d[k]))  // (as Eigen's LDLT: only a zero pivot fails)
        throw std::runtime_error("biharmonic field: factorisation failed (degenerate region of interest)");
    }
    next_row = k;
    return work;
  }
  void solve() {
    const int n = int(upper.cols());
    Eigen::VectorXd x = perm * rhs;
    for (int j = 0; j < n; ++j)
      for (int p = lp[j]; p < lp[j + 1]; ++p) x[li[p]] -= lx[p] * x[j];
    for (int j = 0; j < n; ++j) x[j] /= d[j];
    for (int j = n - 1; j >= 0; --j)
      for (int p = lp[j]; p < lp[j + 1]; ++p) x[j] -= lx[p] * x[li[p]];
    const Eigen::VectorXd xo = perm.inverse() * x;
    solution.assign(xo.data(), xo.data() + n);
    // Per row: M^-1 (B x + g).
    laplacian.assign(system.known_rhs.begin(), system.known_rhs.end());
    for (size_t e = 0; e < system.value.size(); ++e) laplacian[system.row[e]] += system.value[e] * xo[system.col[e]];
    for (int r = 0; r < system.n_rows; ++r) laplacian[r] *= system.inv_mass[r];
  }
};

BiharmonicSolver::~BiharmonicSolver() = default;

void BiharmonicSolver::begin_amortized(const BiharmonicSystem& system) {
  if (!impl_->amortized) impl_->amortized = std::make_unique<AmortizedLdlt>();
  AmortizedLdlt& j = *impl_->amortized;
  j.system = system;
  j.stage = AmortizedLdlt::kAssemble;
}

// Work is counted in multiply-adds (estimated for the steps that run in one piece), not in time,
// so that a grab gives the same result on every machine and in WebAssembly (replays are exact).
bool BiharmonicSolver::advance_amortized(double work_budget) {
  impl_->amortized_work = 0;
  if (!impl_->amortized) return false;
  AmortizedLdlt& j = *impl_->amortized;
  double used = 0;
  bool worked = false;
  try {
    while (j.stage != AmortizedLdlt::kDone && j.stage != AmortizedLdlt::kIdle) {
      // A step that runs in one piece starts only as the call's first work or when its estimate
      // fits in what is left: the product and the ordering used to share the first frame of a
      // grab (together 80M instructions on a 10k-vertex ROI, against the budget's 30M).
      if (worked && (used >= work_budget || used + j.estimate() > work_budget)) break;
      worked = true;
      switch (j.stage) {
        case AmortizedLdlt::kAssemble:
          if (j.system.n_free == 0) {
            j.solution.clear();
            j.laplacian.assign(j.system.n_rows, 0.0);
            j.stage = AmortizedLdlt::kDone;
            break;
          }
          used += j.estimate();
          j.assemble();
          j.stage = AmortizedLdlt::kOrder;
          break;
        case AmortizedLdlt::kOrder:
          used += j.estimate();
          j.order();
          j.stage = AmortizedLdlt::kPermute;
          break;
        case AmortizedLdlt::kPermute:
          used += j.estimate();
          j.permute();
          j.stage = AmortizedLdlt::kSymbolic;
          break;
        case AmortizedLdlt::kSymbolic:
          used += j.estimate();
          j.symbolic();
          j.stage = AmortizedLdlt::kNumeric;
          break;
        case AmortizedLdlt::kNumeric:
          used += j.numeric(std::max(0.0, work_budget - used));
          if (j.next_row == int(j.upper.cols())) j.stage = AmortizedLdlt::kSolve;
          break;
        case AmortizedLdlt::kSolve:
          used += j.estimate();
          j.solve();
          j.stage = AmortizedLdlt::kDone;
          break;
        default:
          break;
      }
    }
  } catch (...) {
    j.stage = AmortizedLdlt::kIdle;
    throw;
  }
  impl_->amortized_work = used;
  return j.stage == AmortizedLdlt::kDone;
}

double BiharmonicSolver::amortized_work_done() const { return impl_->amortized_work; }

bool BiharmonicSolver::amortized_running() const {
  return impl_->amortized && impl_->amortized->stage != AmortizedLdlt::kIdle &&
         impl_->amortized->stage != AmortizedLdlt::kDone;
}
double BiharmonicSolver::amortized_next_step_work() const {
  return amortized_running() ? impl_->amortized->estimate() : 0.0;
}
void BiharmonicSolver::cancel_amortized() {
  if (impl_->amortized) impl_->amortized->stage = AmortizedLdlt::kIdle;
}
const std::vector<double>& BiharmonicSolver::amortized_solution() const { return impl_->amortized->solution; }
const std::vector<double>& BiharmonicSolver::amortized_laplacian() const { return impl_->amortized->laplacian; }

}  // namespace adasculpt::deform
