#pragma once
// The sparse solve behind the blending field; the only translation unit that instantiates
// Eigen's sparse solvers (they dominate WebAssembly compile time). Eigen stays out of this header.
//
// Discretisation (our choice, see PAPER.md section 4 and Botsch & Sorkine 2008): the bi-Laplacian
// Delta^2 = (M^-1 Lc)^2 with the symmetric cotan matrix Lc and the lumped (barycentric) mass M.
// Requiring (M^-1 Lc M^-1 Lc w)_i = 0 at a free vertex i is, after multiplying by M, the
// symmetric system  B^T M^-1 B w_free = -B^T M^-1 g  where B = Lc restricted to the rows that
// touch a free vertex and the free columns, and g = Lc applied to the known values (1 on the
// handle, 0 on the fixed rings). B^T M^-1 B is symmetric positive definite, so SimplicialLDLT
// applies; the L^2 of the uniformly normalised Laplacian would not be symmetric.
//
// Reuse between frames:
//  - the symbolic analysis (AMD ordering, elimination tree) is kept while the sparsity pattern
//    of the system is identical to the previous one;
//  - with FieldReuse::CarryFactorization the numeric factorisation is kept as well while the
//    pattern (= the ROI topology and local numbering) is unchanged, and the new system is solved
//    by conjugate gradients preconditioned with the old factors, warm-started from their solve.
//    If the relative residual is still above the tolerance after max_refinement_steps, the
//    matrix is factorised afresh, so the result is always a converged solve (stats() says which).
//
// The amortised solve (the carried field's refresh in a grab, see handle_deformer.h) is exact too
// but spread over calls: begin_amortized() takes a copy of the system, and each
// advance_amortized(budget) works on it for about `budget` multiply-adds (counted, not timed, so
// that results do not depend on the machine's speed: a replay is the same natively and in
// WebAssembly; 1e6 is roughly 1 ms natively): the product matrix, a
// fill-reducing ordering (Eigen's AMD), the symbolic analysis, then rows of an up-looking LDL^T
// factorisation (our own, so that it can stop after any row and go on at the next call), then the
// triangular solves. No frame of a grab pays for a whole factorisation.
#include <cstdint>
#include <memory>
#include <vector>

namespace adasculpt::deform {

enum class FieldReuse {
  Exact,               // factorise every call (analysis reused when the pattern is unchanged)
  CarryFactorization,  // keep the factors while the pattern is unchanged; refine iteratively
};

// B as coordinate triplets (row in [0, n_rows), col in [0, n_free)), one value per row for
// M^-1 (inv_mass) and for g (known_rhs).
struct BiharmonicSystem {
  int n_free = 0, n_rows = 0;
  std::vector<int> row, col;
  std::vector<double> value;
  std::vector<double> inv_mass, known_rhs;
  void clear(int free, int rows);
  void add(int r, int c, double v) {
    row.push_back(r);
    col.push_back(c);
    value.push_back(v);
  }
};

struct BiharmonicStats {
  bool analyzed = false, factorized = false;
  int refinement_steps = 0;
  double assemble_ms = 0, analyze_ms = 0, factorize_ms = 0, solve_ms = 0;
  double relative_residual = 0;  // |b - A x| / |b| of the returned solution
};

class BiharmonicSolver {
 public:
  BiharmonicSolver();
  ~BiharmonicSolver();
  BiharmonicSolver(const BiharmonicSolver&) = delete;
  BiharmonicSolver& operator=(const BiharmonicSolver&) = delete;

  // Solves for the free values (x.size() becomes n_free). Throws std::runtime_error when the
  // factorisation fails (a degenerate region). If laplacian is given it receives, per row, the
  // Laplacian M^-1 Lc w of the solution (used by the refinement's midpoint estimate).
  void solve(const BiharmonicSystem& system, std::vector<double>& x, FieldReuse reuse = FieldReuse::Exact,
             int max_refinement_steps = 8, double refinement_tolerance = 1e-6,
             std::vector<double>* laplacian = nullptr);
  // Amortised solve of a copy of `system` (see above); a running one is abandoned.
  void begin_amortized(const BiharmonicSystem& system);
  // Works for about work_budget multiply-adds (at least one step; the steps that run in one piece
  // count an estimate); true once the solution is ready. Throws std::runtime_error on a
  // degenerate region, as solve() does.
  bool advance_amortized(double work_budget);
  // The multiply-adds the last advance_amortized() did (the one-piece steps by their estimate):
  // what a frame's share of the solve actually cost, for the frame's plan (sculpt/grab.h).
  double amortized_work_done() const;
  bool amortized_running() const;
  // The estimated work of the amortised solve's next step when it runs in one piece (the
  // product, the ordering, the symbolic analysis, the triangular solves); 0 for the rows of the
  // factorisation, which stop at any budget.
  double amortized_next_step_work() const;
  void cancel_amortized();
  // Once advance_amortized() returned true: the free values and, per row, the Laplacian of the
  // solution (as solve()'s `laplacian`).
  const std::vector<double>& amortized_solution() const;
  const std::vector<double>& amortized_laplacian() const;
  // Forgets the cached pattern and factors (e.g. at the start of a grab).
  void reset();
  const BiharmonicStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adasculpt::deform
