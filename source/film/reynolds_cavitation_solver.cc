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

ReynoldsCavitationSolver::ReynoldsCavitationSolver(ReynoldsSolver &solver) : s(solver) {}

void ReynoldsCavitationSolver::mass_residual(const VectorType &u, const bool with_jacobian,
                                             VectorType &rhs)
{
  const unsigned int n = s.fe->n_dofs_per_cell();
  FullMatrix<double> J(n, n);
  Vector<double> R(n), local_u(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  if (with_jacobian)
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
      if (with_jacobian)
      {
        J = cell_A[k];
        J *= s.pressure_scale;
        s.homogeneous_constraints.distribute_local_to_global(J, R, dofs, s.system_matrix, rhs);
      }
      else
        s.homogeneous_constraints.distribute_local_to_global(R, dofs, rhs);
    }
  if (with_jacobian)
    s.system_matrix.compress(VectorOperation::add);
  rhs.compress(VectorOperation::add);
}

double ReynoldsCavitationSolver::assemble(const VectorType &u, const bool with_jacobian,
                                          VectorType &rhs)
{
  // The Jacobian P A is the same at every iteration (the problem is linear in p): assembled
  // from the cells once, then copied (the same entries, bit for bit).
  const bool assemble_matrix = with_jacobian && !have_pressure_jacobian;
  mass_residual(u, assemble_matrix, rhs);
  if (assemble_matrix)
  {
    pressure_jacobian.copy_from(s.system_matrix);
    have_pressure_jacobian = true;
  }
  else if (with_jacobian)
    s.system_matrix.copy_from(pressure_jacobian);

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

void ReynoldsCavitationSolver::start(VectorType &u_owned)
{
  // The active-set iteration moves the cavity boundary by about one layer of nodes per
  // iteration from the clipped full film (measured on the tilted seal: 13, 25, 50 iterations at
  // 32 x 64, 64 x 128, 128 x 256 cells, doc/performance.md), so it starts from the converged
  // solution of the mesh twice as coarse (recursively), as JFO does. The full film is solved
  // only where there is no such start (ReynoldsSolver::run does not).
  std::vector<double> coarse_pressure, coarse_void;
  const bool sequenced = sequenced_start && s.coarse_level_state(coarse_pressure, coarse_void);
  if (!sequenced)
  {
    // the full film, assembled here only (not in ReynoldsSolver::run)
    s.assemble_system();
    s.solve();
    s.pressure_scale = s.full_film_pressure_scale();
  }
  std::size_t k = 0;
  for (const auto i : s.locally_owned_dofs)
  {
    const double p = sequenced ? coarse_pressure[k++] : s.locally_relevant_solution[i];
    u_owned[i] = std::max((p - s.cavitation.pressure) / s.pressure_scale, 0.0);
  }
  u_owned.compress(VectorOperation::insert);
}

ReynoldsCavitationSolver::Complementarity
ReynoldsCavitationSolver::complementarity_at_solution(ReynoldsSolver &solver)
{
  ReynoldsCavitationSolver c(solver);
  ReynoldsSolver &s = solver;
  s.compute_cell_matrices(false, c.cell_A, c.cell_G, c.cell_F);
  // the solve left the full-film right-hand side in system_rhs (full_film_flow_scale, or the
  // assembly of the coarsest level); computing it again here would add the constrained cells'
  // terms to the system matrix, which holds the Jacobian at the solution
  c.flow_scale = std::max(s.system_rhs.l2_norm(), 1e-300);
  VectorType u_owned(s.locally_owned_dofs, s.mpi_communicator),
      rhs(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
    u_owned[i] = (s.locally_relevant_solution[i] - s.cavitation.pressure) / s.pressure_scale;
  u_owned.compress(VectorOperation::insert);
  VectorType u(s.locally_owned_dofs, s.locally_relevant_dofs, s.mpi_communicator);
  u = u_owned;
  c.mass_residual(u, false, rhs);
  Complementarity result;
  result.flow_scale = c.flow_scale;
  for (const auto i : s.locally_owned_dofs)
    if (!s.homogeneous_constraints.is_constrained(i))
    {
      result.u.push_back(u_owned[i]);
      result.residual.push_back(-rhs[i] / c.flow_scale);
      result.jacobian_diagonal.push_back(s.reynolds_diagonal[i] / c.flow_scale);
      result.cavitated.push_back(
          std::binary_search(s.active_set.begin(), s.active_set.end(), i) ? 1 : 0);
    }
  return result;
}

void ReynoldsCavitationSolver::solve()
{
  {
    TimerOutput::Scope timer_scope(s.timer, "reynolds cell matrices");
    s.compute_cell_matrices(false, cell_A, cell_G, cell_F);
  }
  flow_scale = s.full_film_flow_scale(cell_A, cell_F);
  s.reynolds_diagonal.reinit(s.locally_owned_dofs, s.mpi_communicator);
  TrilinosWrappers::MPI::Vector u_owned(s.locally_owned_dofs, s.mpi_communicator);
  start(u_owned);
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
  // The Jacobian at the solution, which linearized_loads solves with, is already factorised:
  // the iteration stopped because the set repeated, so the last assembly built the matrix of
  // the previous iteration again (the same copy of P A with the same rows replaced), and the
  // linear solver holds that one's factorisation from the last step.
  TrilinosWrappers::MPI::Vector p(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
    p[i] = s.cavitation.pressure + s.pressure_scale * u_owned[i];
  p.compress(VectorOperation::insert);
  s.locally_relevant_solution = p;
  s.last_iterations += it;
}
} // namespace sealfe
