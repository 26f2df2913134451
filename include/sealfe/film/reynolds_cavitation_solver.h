// ReynoldsCavitationSolver: the Swift-Stieber (Reynolds) cavitation condition p >= p_cav on a
// ReynoldsSolver's discretisation, by the primal-dual active-set method.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

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
};

} // namespace sealfe
