#include <sealfe/film/reynolds_cavitation_solver.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <limits>
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
  const unsigned int n = s.fe->n_dofs_per_cell();
  // The Jacobian P A is the same at every iteration (the problem is linear in p): assembled
  // from the cells once, then copied (the same entries, bit for bit).
  const bool assemble_matrix = with_jacobian && !have_pressure_jacobian;
  FullMatrix<double> J(n, n);
  Vector<double> R(n), local_u(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  if (assemble_matrix)
    s.system_matrix = 0;
  rhs = 0;
  for (const auto &cell : s.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      const auto k = cell->active_cell_index();
      cell->get_dof_indices(dofs);
      cell->get_dof_values(u, local_u);
      for (unsigned int j = 0; j < n; ++j)
        local_p(j) = s.cavitation.pressure + s.pressure_scale * local_u(j);
      cell_A[k].vmult(R, local_p);
      R -= cell_F[k];
      R *= -1.0; // rhs holds -R
      if (assemble_matrix)
      {
        J = cell_A[k];
        J *= s.pressure_scale;
        s.homogeneous_constraints.distribute_local_to_global(J, R, dofs, s.system_matrix, rhs);
      }
      else
        s.homogeneous_constraints.distribute_local_to_global(R, dofs, rhs);
    }
  if (assemble_matrix)
  {
    s.system_matrix.compress(VectorOperation::add);
    pressure_jacobian.copy_from(s.system_matrix);
    have_pressure_jacobian = true;
  }
  else if (with_jacobian)
    s.system_matrix.copy_from(pressure_jacobian);
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
  {
    TimerOutput::Scope timer_scope(s.timer, "reynolds cell matrices");
    s.compute_cell_matrices(false, cell_A, cell_G, cell_F);
  }
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
  // SEALFE_REYNOLDS_TRACE: one line per iteration on stderr (residual, set size, nodes that
  // entered and left the set), the evidence of doc/performance.md's iteration counts.
  const bool trace = std::getenv("SEALFE_REYNOLDS_TRACE") && s.reports_progress &&
                     Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0;
  double residual = 0;
  bool converged = false;
  unsigned int it = 0;
  for (; it < s.cavitation.maximum_iterations; ++it)
  {
    residual = assemble(u, true, rhs) / flow_scale;
    const auto &set = s.active_set;
    if (trace)
    {
      std::vector<types::global_dof_index> entered, left;
      if (it > 0)
      {
        std::set_difference(set.begin(), set.end(), previous_set.begin(), previous_set.end(),
                            std::back_inserter(entered));
        std::set_difference(previous_set.begin(), previous_set.end(), set.begin(), set.end(),
                            std::back_inserter(left));
      }
      std::cerr << "sealfe: reynolds iteration " << it << " (" << s.dof_handler.n_dofs()
                << " dofs): relative residual " << residual << ", cavitated nodes " << set.size()
                << ", entered " << entered.size() << ", left " << left.size() << std::endl;
    }
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
