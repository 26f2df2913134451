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

void ReynoldsCavitationSolver::mass_residual(const VectorType &u, VectorType &rhs)
{
  const unsigned int n = s.fe->n_dofs_per_cell();
  Vector<double> R(n), local_u(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
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
      s.homogeneous_constraints.distribute_local_to_global(R, dofs, rhs);
    }
  rhs.compress(VectorOperation::add);
}

void ReynoldsCavitationSolver::make_global_system(const VectorType &u)
{
  // The problem is linear in p = p_cav + P u, so one pass over the cells gives what every
  // iteration needs: P A (the Jacobian before its cavitated rows are replaced) and the residual
  // at u = 0 on the unconstrained dofs, c = F - A p with p = p_cav there and the Dirichlet
  // pressure p_cav + P u_j on the constrained dofs j, which keep their start value. The residual
  // at any u is then c - (P A) u (residual_by_products), and no cell's matrices are held
  // (doc/performance.md, "The reynolds (Swift-Stieber) model"). The same pass makes the full
  // film's right-hand side, whose norm scales the residual (ReynoldsSolver::add_to_full_film_rhs).
  TimerOutput::Scope timer_scope(s.timer, "reynolds cell matrices");
  const unsigned int n = s.fe->n_dofs_per_cell();
  FullMatrix<double> J(n, n);
  Vector<double> c(n), local_u(n), fixed_p(n);
  std::vector<types::global_dof_index> dofs(n);
  pressure_jacobian.copy_from(s.system_matrix); // (the system's layout)
  pressure_jacobian = 0;
  constant_rhs.reinit(s.locally_owned_dofs, s.mpi_communicator);
  s.system_rhs = 0;
  s.for_each_cell_film_matrices(
      false,
      [&](const DoFHandler<2>::active_cell_iterator &cell, const FullMatrix<double> &A,
          const FullMatrix<double> &, const Vector<double> &F)
      {
        cell->get_dof_indices(dofs);
        s.add_to_full_film_rhs(A, F, dofs);
        cell->get_dof_values(u, local_u);
        for (unsigned int j = 0; j < n; ++j)
          fixed_p(j) = s.cavitation.pressure + (s.homogeneous_constraints.is_constrained(dofs[j])
                                                    ? s.pressure_scale * local_u(j)
                                                    : 0.0);
        A.vmult(c, fixed_p);
        c.sadd(-1.0, 1.0, F);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            J(i, j) = s.pressure_scale * A(i, j);
        s.homogeneous_constraints.distribute_local_to_global(J, c, dofs, pressure_jacobian,
                                                             constant_rhs);
      });
  pressure_jacobian.compress(VectorOperation::add);
  constant_rhs.compress(VectorOperation::add);
  flow_scale = s.flow_scale_of_full_film_rhs();
}

void ReynoldsCavitationSolver::residual_by_products(const VectorType &u_owned, VectorType &rhs)
{
  // -R = c - (P A) u: the Jacobian has no entries in the constrained columns of unconstrained
  // rows (the homogeneous constraints drop them), and its constrained rows, which hold a
  // diagonal, are zero in the residual as in the cell-by-cell assembly
  pressure_jacobian.vmult(rhs, u_owned);
  rhs.sadd(-1.0, 1.0, constant_rhs);
  s.homogeneous_constraints.set_zero(rhs);
}

double ReynoldsCavitationSolver::assemble(const VectorType &u, const bool with_jacobian,
                                          VectorType &rhs)
{
  // The Jacobian P A is the same at every iteration (the problem is linear in p): assembled
  // once (make_global_system), then copied (the same entries, bit for bit).
  residual_by_products(u, rhs);
  if (with_jacobian)
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
  c.mass_residual(u, rhs);
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
  s.reynolds_diagonal.reinit(s.locally_owned_dofs, s.mpi_communicator);
  TrilinosWrappers::MPI::Vector u_owned(s.locally_owned_dofs, s.mpi_communicator);
  start(u_owned);
  {
    // (the constrained dofs' start values, read on the cells that hold them)
    TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs, s.locally_relevant_dofs,
                                    s.mpi_communicator);
    u = u_owned;
    make_global_system(u);
  }

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
    residual = assemble(u_owned, true, rhs) / flow_scale;
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
