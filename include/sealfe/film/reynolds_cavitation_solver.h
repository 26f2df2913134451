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
/// problem; Hintermueller, Ito & Kunisch 2002) starting from the solver's full-film solution
/// clipped at p_cav. Leaves the pressure, the active set (nodes held at p_cav) and the
/// factorised Jacobian at the solution in the solver. One object per solve.
class ReynoldsCavitationSolver
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  /// `flow_scale`: the size of the full-film right-hand side, the scale of the mass residual.
  ReynoldsCavitationSolver(ReynoldsSolver &solver, double flow_scale);
  /// Throws std::runtime_error if the iteration does not converge.
  void solve();

private:
  /// Residual (-R in `rhs`, |rhs| returned) at u, and with `with_jacobian` the Newton matrix in
  /// the solver's system matrix; both with the rows of the active set replaced by u_i = 0.
  double assemble(const VectorType &u, bool with_jacobian, VectorType &rhs);

  ReynoldsSolver &s;
  const double flow_scale;
  /// The film matrices A and F of every cell (ReynoldsSolver::compute_cell_matrices): the
  /// problem is linear in p, so they serve every iteration.
  std::vector<dealii::FullMatrix<double>> cell_A, cell_G;
  std::vector<dealii::Vector<double>> cell_F;
  /// P A assembled once (the Jacobian of every iteration before its active rows are replaced):
  /// copied into the system matrix instead of assembling the cells again.
  dealii::TrilinosWrappers::SparseMatrix pressure_jacobian;
  bool have_pressure_jacobian = false;
};

} // namespace sealfe
