#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_cavitation_solver.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace sealfe
{
using namespace dealii;

ReynoldsCavitationSolver::ReynoldsCavitationSolver(ReynoldsSolver &solver, const double flow_scale)
    : s(solver), flow_scale(flow_scale)
{
}

double ReynoldsCavitationSolver::assemble(const VectorType &u, const bool with_jacobian,
                                          VectorType &rhs)
{
  const QGauss<2> quadrature(s.polynomial_degree + 2);
  FEValues<2> fe_values(*s.mapping, *s.fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n = s.fe->n_dofs_per_cell();
  FullMatrix<double> A(n, n), G(n, n), J(n, n);
  Vector<double> F(n), R(n), local_u(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  // The built-in annulus: each cell's geometry from its radial row, as in the full-film and JFO
  // assemblies (PolarCellValues; a cell that is no rotation of its row's first cell takes
  // FEValues); the loads' leakage residual takes the same values (LoadIntegrator::polar_assembly).
  std::optional<PolarCellValues> polar;
  if (s.assembles_on_polar_rows())
    polar.emplace(*s.mapping, *s.fe, quadrature);
  if (with_jacobian)
    s.system_matrix = 0;
  rhs = 0;
  for (const auto &cell : s.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell->get_dof_indices(dofs);
      cell->get_dof_values(u, local_u);
      for (unsigned int j = 0; j < n; ++j)
        local_p(j) = s.cavitation.pressure + s.pressure_scale * local_u(j);
      s.cell_film_matrices(polar, fe_values, cell, false, A, G, F);
      A.vmult(R, local_p);
      R -= F;
      R *= -1.0; // rhs holds -R
      if (with_jacobian)
      {
        J = A;
        J *= s.pressure_scale;
        s.homogeneous_constraints.distribute_local_to_global(J, R, dofs, s.system_matrix, rhs);
      }
      else
        s.homogeneous_constraints.distribute_local_to_global(R, dofs, rhs);
    }
  if (with_jacobian)
    s.system_matrix.compress(VectorOperation::add);
  rhs.compress(VectorOperation::add);

  {
    // Primal-dual active set: dof i is cavitated if u_i - R_i / J_ii <= 0; there the equation is
    // replaced by u_i = 0 (the Newton row delta u_i = -u_i).
    s.active_set.clear();
    for (const auto i : s.locally_owned_dofs)
      if (!s.homogeneous_constraints.is_constrained(i))
      {
        const double diagonal =
            with_jacobian ? s.system_matrix.diag_element(i) : s.reynolds_diagonal[i];
        if (u[i] + rhs[i] / diagonal <= 0)
          s.active_set.push_back(i);
      }
    if (with_jacobian)
    {
      for (const auto i : s.locally_owned_dofs)
        s.reynolds_diagonal[i] = s.system_matrix.diag_element(i);
      s.reynolds_diagonal.compress(VectorOperation::insert);
      s.system_matrix.clear_rows(s.active_set, 1.0);
    }
    for (const auto i : s.active_set)
      rhs[i] = -u[i];
    rhs.compress(VectorOperation::insert);
  }
  return rhs.l2_norm();
}
void ReynoldsCavitationSolver::solve()
{
  s.reynolds_diagonal.reinit(s.locally_owned_dofs, s.mpi_communicator);
  // Reynolds: warm start from the full-film solution clipped at s.cavitation.pressure.
  TrilinosWrappers::MPI::Vector u_owned(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
    u_owned[i] =
        std::max((s.locally_relevant_solution[i] - s.cavitation.pressure) / s.pressure_scale, 0.0);
  u_owned.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs, s.locally_relevant_dofs,
                                  s.mpi_communicator);
  u = u_owned;

  TrilinosWrappers::MPI::Vector rhs(s.locally_owned_dofs, s.mpi_communicator),
      du(s.locally_owned_dofs, s.mpi_communicator);
  std::vector<types::global_dof_index> previous_set = {
      std::numeric_limits<types::global_dof_index>::max()};
  double residual = 0;
  bool converged = false;
  unsigned int it = 0;
  for (; it < s.cavitation.maximum_iterations; ++it)
  {
    residual = assemble(u, true, rhs) / flow_scale;
    const auto &set = s.active_set;
    const bool same_set =
        Utilities::MPI::min(static_cast<int>(set == previous_set), s.mpi_communicator) == 1;
    if (same_set && residual < s.cavitation.tolerance)
    {
      converged = true;
      break;
    }
    previous_set = set;
    s.factorize(false, true);
    du = 0;
    s.solve_linear_system(rhs, du);
    s.homogeneous_constraints.set_zero(du);
    u_owned.add(1.0, du);
    u = u_owned;
  }
  s.cavitation_iterations = it;
  s.cavitation_residual = residual;
  if (!converged)
  {
    std::ostringstream m;
    m << "Cavitation (reynolds): no convergence in " << s.cavitation.maximum_iterations
      << " Newton iterations (relative mass residual " << residual << ", tolerance "
      << s.cavitation.tolerance << "); refine the mesh or raise Cavitation/Maximum iterations";
    throw std::runtime_error(m.str());
  }
  // The last assembly built the Jacobian at the solution: factorise it for linearized_loads.
  s.factorize(false, true);
  TrilinosWrappers::MPI::Vector p(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
    p[i] = s.cavitation.pressure + s.pressure_scale * u_owned[i];
  p.compress(VectorOperation::insert);
  s.locally_relevant_solution = p;
  s.last_iterations += it;
}
} // namespace sealfe
