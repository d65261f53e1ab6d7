#include "deform/biharmonic_solver.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace adasculpt::deform {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
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

struct BiharmonicSolver::Impl {
  Eigen::SimplicialLDLT<SpMat> ldlt;
  bool has_pattern = false, has_factor = false;
  std::vector<SpMat::StorageIndex> outer, inner;  // pattern of the analysed matrix
  std::vector<Eigen::Triplet<double>> triplets;
  BiharmonicStats stats;

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
BiharmonicSolver::~BiharmonicSolver() = default;
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

}  // namespace adasculpt::deform
