#include <sealfe/film/jfo_solver.h>
#include <sealfe/film/reynolds_cavitation_solver.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/utilities.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cmath>
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
  // (constrained dofs held at their values: Dirichlet conditions; a hanging node's value follows
  // its neighbours', which c and the column form do not take into account)
  bool dirichlet_only = true;
  for (const auto i : s.locally_owned_dofs)
    dirichlet_only &= !s.homogeneous_constraints.is_constrained(i) ||
                      s.homogeneous_constraints.get_constraint_entries(i)->empty();
  if (Utilities::MPI::min(dirichlet_only ? 1 : 0, s.mpi_communicator) == 0)
    throw std::logic_error("Cavitation (reynolds): the mesh has constraints other than the "
                           "Dirichlet conditions (hanging nodes), which this solver does not take");
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
        J.equ(s.pressure_scale, A);
        s.homogeneous_constraints.distribute_local_to_global(J, c, dofs, pressure_jacobian,
                                                             constant_rhs);
      });
  pressure_jacobian.compress(VectorOperation::add);
  constant_rhs.compress(VectorOperation::add);
  flow_scale = s.flow_scale_of_full_film_rhs();
  // J_ii, the active set's test (assemble)
  for (const auto i : s.locally_owned_dofs)
    s.reynolds_diagonal[i] = pressure_jacobian.diag_element(i);
  s.reynolds_diagonal.compress(VectorOperation::insert);
}

void ReynoldsCavitationSolver::column_form_step(const VectorType &rhs, VectorType &du)
{
  // The Newton step of the set: du_i = rhs_i (= -u_i) on the cavitated nodes C, (P A du)_i =
  // rhs_i on the others. With du_C known, the same step solves the column form
  //   M w = rhs - P A du_C,  M(:, j) = P A(:, j) for j not in C, P A_jj e_j for j in C,
  // and du = w off C: a set change then changes M's columns only, and a few changed columns are
  // a low-rank update of the last factorised M (solve_column_update), as the JFO's confirming
  // rounds are (JFOSolver::low_rank_solve). The row form changed rows, which that cannot serve.
  const std::size_t n = s.dof_handler.n_dofs();
  std::vector<char> cavitated(n, 0);
  VectorType known(s.locally_owned_dofs, s.mpi_communicator), c(known), w(known);
  for (const auto i : s.active_set)
  {
    cavitated[i] = 1;
    known[i] = rhs[i];
  }
  pressure_jacobian.vmult(c, known);
  c.sadd(-1.0, 1.0, rhs);
  // M: the cavitated nodes' columns made P A_jj e_j. Their scale is free (w_C is not read), and
  // P A's own keeps the update's capacitance matrix of order one: with e_j it held P A's Schur
  // complements (1e-11 here) beside ones, and its condition test refused 7 of 26 updates
  // (tilted seal, 5.3e5 dofs, its levels together)
  s.system_matrix.copy_from(pressure_jacobian);
  {
    const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
    std::vector<long long> column_gid(M.NumMyCols());
    for (int k = 0; k < M.NumMyCols(); ++k)
      column_gid[k] = M.ColMap().GID64(k);
    for (int row = 0; row < M.NumMyRows(); ++row)
    {
      int entries;
      double *values;
      int *columns;
      M.ExtractMyRowView(row, entries, values, columns);
      const long long i = M.RowMap().GID64(row);
      for (int e = 0; e < entries; ++e)
        if (const long long j = column_gid[columns[e]]; cavitated[j] && j != i)
          values[e] = 0; // (the diagonal kept: a column of P A's scale, see above)
    }
  }
  if (!low_rank_solve(cavitated, c, w))
  {
    s.factorize(false, true);
    s.solve_linear_system(c, w);
    factored_cavitated = std::move(cavitated);
    factored_count = s.linear_system_solver.statistics().factorizations;
  }
  du = w;
  for (const auto i : s.active_set)
    du[i] = rhs[i];
  du.compress(VectorOperation::insert);
}

bool ReynoldsCavitationSolver::low_rank_solve(const std::vector<char> &cavitated,
                                              const VectorType &c, VectorType &w)
{
  SparseDirect *lu = s.linear_system_solver.factorization();
  // (a limit of 0 turns the updates off, as for JFO; an unchanged set would be a k = 0 update)
  if (JFOSolver::low_rank_limit == 0 || factored_cavitated.empty() || !lu ||
      s.linear_system_solver.statistics().factorizations != factored_count)
    return false;
  std::vector<unsigned int> columns;
  for (std::size_t j = 0; j < cavitated.size(); ++j)
    if (cavitated[j] != factored_cavitated[j])
    {
      if (columns.size() == JFOSolver::low_rank_limit)
        return false;
      columns.push_back(j);
    }
  TimerOutput::Scope timer_scope(s.timer, "reynolds low-rank update");
  // M1 = M0 + U E^T: column j goes from P A(:, j) to P A_jj e_j where j entered the cavity, back
  // where it left, so U's column is -+ P A(:, j) without its diagonal (P A's pattern is
  // symmetric: column j's rows are row j's columns)
  std::vector<SparseColumn> U(columns.size());
  for (std::size_t d = 0; d < columns.size(); ++d)
  {
    const unsigned int j = columns[d];
    const double sign = cavitated[j] ? -1.0 : 1.0;
    for (auto e = pressure_jacobian.begin(j); e != pressure_jacobian.end(j); ++e)
      if (const auto i = e->column(); i != j)
        U[d].emplace_back(i, sign * pressure_jacobian.el(i, j));
  }
  // the JFO's bounds (JFOSolver::low_rank_solve): C refused below rcond sqrt(u), the answer
  // below a backward error of 128 u in M1's true residual
  double rcond, backward_error;
  const LowRankSolve result = solve_column_update(
      *lu, s.system_matrix, columns, U, c.trilinos_vector()[0], w.trilinos_vector()[0],
      std::sqrt(std::numeric_limits<double>::epsilon()), 0x1p-46, rcond, backward_error);
  if (result != LowRankSolve::solved)
    return false;
  ++low_rank_updates;
  return true;
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
  // once (make_global_system); the row form copies it here (the same entries, bit for bit).
  residual_by_products(u, rhs);
  // Primal-dual active set: dof i is cavitated if u_i - R_i / J_ii <= 0; there the equation is
  // replaced by u_i = 0 (the Newton row delta u_i = -u_i).
  s.active_set.clear();
  for (const auto i : s.locally_owned_dofs)
    if (!s.homogeneous_constraints.is_constrained(i) && u[i] + rhs[i] / s.reynolds_diagonal[i] <= 0)
      s.active_set.push_back(i);
  if (with_jacobian)
    make_row_form();
  for (const auto i : s.active_set)
    rhs[i] = -u[i];
  rhs.compress(VectorOperation::insert);
  return rhs.l2_norm();
}

void ReynoldsCavitationSolver::make_row_form()
{
  s.system_matrix.copy_from(pressure_jacobian);
  s.system_matrix.clear_rows(s.active_set, 1.0);
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
  // the solve left the full-film right-hand side in system_rhs (make_global_system's
  // add_to_full_film_rhs); computing it again here would add the constrained cells' terms to the
  // system matrix, which holds the Jacobian at the solution
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
  // A solver of one rank takes the steps by the column form and its low-rank updates
  // (column_form_step): every one-rank run, and the coarse levels of a several-rank run, which
  // each rank solves whole (their factorisations shared over the ranks, whose updates take at
  // most SparseDirect::max_shared_update_columns columns). The distributed level of a
  // several-rank run takes the row form, factorised at every step.
  const bool by_columns = column_form && Utilities::MPI::n_mpi_processes(s.mpi_communicator) == 1;
  for (; it < s.cavitation.maximum_iterations; ++it)
  {
    residual = assemble(u_owned, !by_columns, rhs) / flow_scale;
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
    du = 0;
    if (by_columns)
      column_form_step(rhs, du);
    else
    {
      s.factorize(false, true);
      s.solve_linear_system(rhs, du);
    }
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
  // The Jacobian at the solution, which linearized_loads solves with: on several ranks already
  // factorised (the iteration stopped because the set repeated, so the last assembly built the
  // matrix of the previous iteration again, the same copy of P A with the same rows replaced,
  // and the linear solver holds that one's factorisation from the last step). On one rank the
  // steps solved the column form: the row form is made here and factorised at its first solve,
  // so a run without linearised loads never pays for it. Nothing may change the system matrix
  // before that solve (e.g. add_to_full_film_rhs adds to it).
  if (by_columns)
  {
    make_row_form();
    s.factorize(false, true, true);
  }
  s.jfo_low_rank_updates = low_rank_updates;
  TrilinosWrappers::MPI::Vector p(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
    p[i] = s.cavitation.pressure + s.pressure_scale * u_owned[i];
  p.compress(VectorOperation::insert);
  s.locally_relevant_solution = p;
  s.last_iterations += it;
}
} // namespace sealfe
