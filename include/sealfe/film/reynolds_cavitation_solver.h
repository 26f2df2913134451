// ReynoldsCavitationSolver: the Swift-Stieber (Reynolds) cavitation condition p >= p_cav on a
// ReynoldsSolver's discretisation, by the primal-dual active-set method.
#pragma once

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace sealfe
{
class ReynoldsSolver;

/// Solves p_j = p_cav + P u_j with the complementarity min(u_j, R_j/J_jj) = 0 (an obstacle
/// problem; Hintermueller, Ito & Kunisch 2002) starting from the solution of the mesh twice as
/// coarse (mesh sequencing), else from the full film clipped at p_cav. Leaves the pressure, the
/// active set (nodes held at p_cav) and the Jacobian at the solution, prepared for the linear
/// solver (factorised, or factorised at its first solve), in the solver.
/// One object per solve.
class ReynoldsCavitationSolver
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  explicit ReynoldsCavitationSolver(ReynoldsSolver &solver);
  /// Throws std::runtime_error if the iteration does not converge.
  void solve();

  /// Tests: false starts every mesh from its clipped full film (the start before mesh
  /// sequencing), to compare the two.
  static inline bool sequenced_start = true;
  /// Tests: false takes every step in the row form, factorised (as on several ranks), to compare
  /// the column form's low-rank steps with it.
  static inline bool column_form = true;
  /// Test hook: the complementarity data at the solution a solve left in `solver`, for its
  /// owned dofs without constraints (in increasing index): u = (p - p_cav)/P, the mass residual
  /// R = A p - F over the flow scale |F| (recomputed from the stored pressure), the Jacobian's
  /// diagonal P A_ii over |F|, whether the node is in the cavitated set, and |F|.
  struct Complementarity
  {
    std::vector<double> u, residual, jacobian_diagonal;
    std::vector<char> cavitated;
    double flow_scale = 0;
  };
  static Complementarity complementarity_at_solution(ReynoldsSolver &solver);

private:
  /// Residual (-R in `rhs`, |rhs| returned) at the owned u, and with `with_jacobian` the Newton
  /// matrix in the solver's system matrix; both with the active set's rows made u_i = 0.
  double assemble(const VectorType &u, bool with_jacobian, VectorType &rhs);
  /// The row-form Newton matrix of the active set in the solver's system matrix: P A with the
  /// cavitated rows made u_i rows (identity).
  void make_row_form();
  /// The mass residual -R = F - A p at the ghosted u (into `rhs`, every row), cell by cell from
  /// cell_A, cell_F: complementarity_at_solution's own path, apart from solve()'s products.
  void mass_residual(const VectorType &u, VectorType &rhs);
  /// One pass over the cells (after start(), which sets the pressure scale P): P A into
  /// pressure_jacobian, the residual's constant part into constant_rhs and the flow scale;
  /// `u` (ghosted) gives the constrained dofs' values.
  void make_global_system(const VectorType &u);
  /// The mass residual -R = c - (P A) u at the owned `u_owned`, zero on the constrained rows.
  void residual_by_products(const VectorType &u_owned, VectorType &rhs);
  /// The Newton step du of the current set (s.active_set) and right-hand side `rhs` (one rank),
  /// by the column form: a low-rank update of its last factorisation where few columns changed
  /// (low_rank_solve), else a factorisation.
  void column_form_step(const VectorType &rhs, VectorType &du);
  /// M1 w = c by a low-rank update of the factorised M0 (the set factored_cavitated) where at
  /// most JFOSolver::low_rank_limit nodes changed set; false where it does not apply.
  bool low_rank_solve(const std::vector<char> &cavitated, const VectorType &c, VectorType &w);
  /// The start u: the coarse mesh's solution at this mesh's nodes, else the clipped full film
  /// (solved here); sets the solver's pressure scale.
  void start(VectorType &u_owned);

  ReynoldsSolver &s;
  /// The scale of the mass residual: the size of the full-film right-hand side (set by
  /// make_global_system, or complementarity_at_solution).
  double flow_scale = 1;
  /// complementarity_at_solution's film matrices A and F of every cell
  /// (ReynoldsSolver::compute_cell_matrices); solve() holds none.
  std::vector<dealii::FullMatrix<double>> cell_A, cell_G;
  std::vector<dealii::Vector<double>> cell_F;
  /// P A assembled once (the Jacobian of every iteration before its active rows are replaced):
  /// the residual's product, and copied into the system matrix for each step's row or column
  /// form.
  dealii::TrilinosWrappers::SparseMatrix pressure_jacobian;
  /// The residual -R at u = 0 on the unconstrained dofs (make_global_system).
  VectorType constant_rhs;
  /// The cavitated set (by dof) of the last factorised column form, and the linear solver's
  /// factorisation count then (another factorisation in between voids it).
  std::vector<char> factored_cavitated;
  unsigned int factored_count = 0;
  /// Steps solved by a low-rank update (summary.json: cavitation/low_rank_updates).
  unsigned int low_rank_updates = 0;
};

} // namespace sealfe
