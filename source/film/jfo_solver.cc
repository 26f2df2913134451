#include <sealfe/film/jfo_krylov.h>
#include <sealfe/film/jfo_solver.h>

#include <sealfe/film/band_round_rule.h>
#include <sealfe/film/cell_sparsity.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace sealfe
{
using namespace dealii;

namespace
{
/// Calls visit(row, entries, values, columns, first) for each local row of M in storage order;
/// `first` is the row's first entry in a flat copy of M's values (the layout of global_PA and
/// global_G). The values are M's own storage (deal.II 9.4 hands out the Epetra matrix read-only;
/// writing them changes neither the pattern nor the filled state).
template <typename Visit>
void for_each_row(const Epetra_CrsMatrix &M, Visit &&visit)
{
  std::size_t first = 0;
  for (int row = 0; row < M.NumMyRows(); ++row)
  {
    int entries;
    double *values;
    int *columns;
    M.ExtractMyRowView(row, entries, values, columns);
    visit(row, entries, values, columns, first);
    first += entries;
  }
}

/// for_each_row with the rows split over deal.II's threads (grains of 2048 rows; on one thread
/// the same loop, unsplit) where M's values are one array (a filled matrix of optimised storage,
/// always the case here), else for_each_row. For visits that write their own row only and read
/// what no other row's visit writes: each row gets the operations of the serial loop, so the
/// same bits on any number of threads.
template <typename Visit>
void for_each_row_on_threads(const Epetra_CrsMatrix &M, const Visit &visit)
{
  int *offsets = nullptr, *columns = nullptr;
  double *values = nullptr;
  if (!M.Filled() || !M.StorageOptimized() ||
      M.ExtractCrsDataPointers(offsets, columns, values) != 0)
  {
    for_each_row(M, visit);
    return;
  }
  parallel::apply_to_subranges(
      0, M.NumMyRows(),
      [&](const int first_row, const int end_row)
      {
        for (int row = first_row; row < end_row; ++row)
          visit(row, offsets[row + 1] - offsets[row], values + offsets[row], columns + offsets[row],
                static_cast<std::size_t>(offsets[row]));
      },
      2048);
}

/// A cell's constant terms (JFOSolver::assemble_by_products): its residual r and active-set
/// right-hand side b with a = v = 0 on the unconstrained dofs, fixed(j) giving the fixed values
/// {a_j, v_j} of a constrained local dof j ({0, 0} for the others).
template <typename Fixed>
void cell_constant_terms(const FullMatrix<double> &A, const FullMatrix<double> &G,
                         const Vector<double> &F, const double p_cav, const double P, Fixed &&fixed,
                         Vector<double> &r, Vector<double> &b)
{
  const unsigned int n = F.size();
  for (unsigned int i = 0; i < n; ++i)
  {
    r(i) = b(i) = F(i);
    for (unsigned int j = 0; j < n; ++j)
    {
      const auto [a_j, v_j] = fixed(j);
      r(i) -= A(i, j) * (p_cav + P * a_j) + G(i, j) * v_j;
      b(i) -= A(i, j) * p_cav + (a_j >= v_j ? P * A(i, j) * a_j : G(i, j) * v_j);
    }
  }
}

/// Fischer-Burmeister function phi(a, b) = a + b - sqrt(a^2 + b^2): zero iff a >= 0, b >= 0,
/// a b = 0. Returns phi and its partial derivatives (the generalised ones at the origin).
struct FischerBurmeister
{
  double value, d_a, d_b;
  FischerBurmeister(const double a, const double b)
  {
    const double rho = std::hypot(a, b);
    value = a + b - rho;
    d_a = rho > 0 ? 1 - a / rho : 1 - M_SQRT1_2;
    d_b = rho > 0 ? 1 - b / rho : 1 - M_SQRT1_2;
  }
  /// Which unknown a node keeps in the reduced Newton system: the one whose complementarity
  /// derivative is smaller is eliminated (d_a + d_b >= 2 - sqrt 2, so the kept one is >= 0.29).
  bool keeps_pressure() const { return d_b >= d_a; }
};
} // namespace

// JFO by Fischer-Burmeister-Newton-Schur (Woloszynski et al. 2015): nodal unknowns a_j = (p_j -
// p_cav)/P and v_j, equations R_j(a, v) = 0 (mass balance, see above) and phi(a_j, v_j) = 0.
// Each node's complementarity row is used to eliminate one of its two unknowns, so the Newton
// system stays N x N with the sparsity of the pressure matrix; unlike the universal variable, a
// node near the cavity boundary sees both its pressure and its void derivative, which is what
// lets the active set settle. Globalised by backtracking on 1/2 (|R|^2 + |phi|^2).
JFOSolver::JFOSolver(ReynoldsSolver &solver)
    : s(solver), best_merit(std::numeric_limits<double>::max())
{
  const IndexSet &owned = s.locally_owned_dofs, &relevant = s.locally_relevant_dofs;
  const MPI_Comm comm = s.mpi_communicator;
  for (VectorType *x :
       {&a_owned, &v_owned, &residual, &newton_rhs, &w, &da, &dv, &trial_a, &trial_v})
    x->reinit(owned, comm);
  // the ghosted vectors share a's map (its data, not a copy of its elements), so that
  // find_ghosted_positions knows their layout by a pointer
  a.reinit(owned, relevant, comm);
  for (VectorType *x : {&v, &ta, &tv})
    x->reinit(a);
}

bool JFOSolver::prepare_global_matrices()
{
  // The Jacobian of an active-set round has column j of P A where node j keeps its pressure and
  // of G where it is cavitated. Without constraints that couple dofs (hanging nodes) the
  // condensed global matrix is that column selection of the assembled P A and G, entry by entry
  // the same sums of cell values in the same order (bitwise the matrix of the cell-by-cell
  // assembly; the constrained rows keep their diagonal from P A, as every constrained node
  // keeps its pressure). The cell-by-cell insertion into the Trilinos matrix was most of the
  // JFO assembly time (doc/performance.md), repeated on every active-set round.
  if (global_matrices != 0)
    return global_matrices > 0;
  if (assemble_by_cells)
    return false; // tests: the cell-by-cell path throughout
  TimerOutput::Scope timer_scope(s.timer, "jfo cell matrices");
  return make_global_matrices(false);
}

void JFOSolver::keep_cell_matrices()
{
  if (cell_matrices_kept)
    return;
  s.compute_cell_matrices(true, cell_A, cell_G, cell_F);
  std::vector<double>().swap(interior_constant); // (its memory too)
  cell_matrices_kept = true;
}

bool JFOSolver::make_global_matrices(const bool first_pass)
{
  const bool several_ranks = Utilities::MPI::n_mpi_processes(s.mpi_communicator) != 1;
  // (several ranks: every rank alike, before any collective call; matrices already kept: the
  // cell loops read them, so the pass has nothing to save)
  if (first_pass && (several_ranks || cell_matrices_kept))
    return false;
  global_matrices = -1;
  bool dirichlet_only = true;
  for (const auto i : s.locally_owned_dofs)
    if (s.homogeneous_constraints.is_constrained(i) &&
        (!s.homogeneous_constraints.get_constraint_entries(i)->empty() ||
         s.homogeneous_constraints.is_inhomogeneously_constrained(i)))
      dirichlet_only = false;
  // every rank takes the same path (the several-rank one is collective)
  if (Utilities::MPI::min(dirichlet_only ? 1 : 0, s.mpi_communicator) == 0)
    return false;
  if (several_ranks)
  {
    keep_cell_matrices();
    // Several ranks: a cell at the partition boundary adds to rows another rank owns, which
    // reach it in compress(). P A and G are therefore assembled into the system matrix itself,
    // once each, with the per-round assembly's additions in its order (by position where
    // CellSparsity built the matrix, else distribute_local_to_global, then compress's sums), and
    // their values copied out in its storage order: a round's column selection is then bitwise
    // the matrix the round's cell loop would assemble.
    const unsigned int n = s.fe->n_dofs_per_cell();
    FullMatrix<double> J(n, n);
    std::vector<types::global_dof_index> dofs(n);
    for (auto [cell_matrices, scale, values] :
         {std::tuple{&cell_A, s.pressure_scale, &global_PA}, std::tuple{&cell_G, 1.0, &global_G}})
    {
      s.system_matrix = 0;
      for (const auto &cell : s.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
        {
          const FullMatrix<double> &C = (*cell_matrices)[cell->active_cell_index()];
          // the products of the cell-by-cell assembly (P * A(i, j); G(i, j), times 1 exactly)
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              J(i, j) = scale * C(i, j);
          cell->get_dof_indices(dofs);
          CellSparsity::distribute(s.homogeneous_constraints, s.matrix_by_position, J, dofs,
                                   s.system_matrix);
        }
      s.system_matrix.compress(VectorOperation::add);
      values->clear();
      values->reserve(s.system_matrix.trilinos_matrix().NumMyNonzeros());
      for_each_row(s.system_matrix.trilinos_matrix(),
                   [&](int, const int entries, const double *row_values, const int *, std::size_t)
                   { values->insert(values->end(), row_values, row_values + entries); });
    }
    global_matrices = 1;
    return true;
  }
  // The values are summed straight into flat arrays in the system matrix's storage order, both
  // matrices in one pass over the cells: the same additions in the same order as
  // AffineConstraints::distribute_local_to_global into the Trilinos matrix (each entry gets one
  // term per cell, cells in order; a constrained row gets only its diagonal, |J(i,i)| or, where
  // that is zero, the mean |J(k,k)| of the cell, deal.II's set_matrix_diagonals), so bitwise the
  // matrices of that assembly, without its two passes of index translation and search
  // (Epetra LID, SumIntoGlobalValues: ~40 % of "jfo cell matrices" at 1.3e5 dofs).
  const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
  const std::size_t n_dofs = s.dof_handler.n_dofs();
  std::vector<int> row_of(n_dofs, -1), column_of(n_dofs, -1);
  for (int r = 0; r < M.NumMyRows(); ++r)
    row_of[M.RowMap().GID64(r)] = r;
  for (int c = 0; c < M.NumMyCols(); ++c)
    column_of[M.ColMap().GID64(c)] = c;
  std::vector<std::size_t> row_first(M.NumMyRows());
  std::vector<const int *> row_columns(M.NumMyRows());
  std::vector<int> row_entries(M.NumMyRows());
  bool sorted = true; // Epetra sorts the column indices of a filled matrix; checked
  for_each_row(M,
               [&](const int row, const int entries, const double *, const int *columns,
                   const std::size_t first)
               {
                 row_first[row] = first;
                 row_columns[row] = columns;
                 row_entries[row] = entries;
                 sorted = sorted && std::is_sorted(columns, columns + entries);
               });
  // position of (row, column) in the flat arrays; `missing` if the pattern lacks it
  const std::size_t missing = std::numeric_limits<std::size_t>::max();
  auto position = [&](const types::global_dof_index i, const types::global_dof_index j)
  {
    const int r = row_of[i], c = column_of[j];
    if (r < 0 || c < 0)
      return missing;
    const int *begin = row_columns[r], *end = begin + row_entries[r];
    const int *e = sorted ? std::lower_bound(begin, end, c) : std::find(begin, end, c);
    return e != end && *e == c ? row_first[r] + (e - begin) : missing;
  };
  // a later call (the lazy one of prepare_global_matrices, the test hooks) reads kept matrices:
  // the partial state of a first pass is left by solve() alone, whose constant terms it fills
  if (!first_pass)
    keep_cell_matrices();
  const std::size_t nnz = M.NumMyNonzeros();
  std::vector<double> PA(nnz, 0.0), G(nnz, 0.0);
  const unsigned int n = s.fe->n_dofs_per_cell();
  const double P = s.pressure_scale;
  FullMatrix<double> J_PA(n, n), J_G(n, n);
  std::vector<types::global_dof_index> dofs(n);
  Vector<double> r(n), b(n);
  std::vector<char> is_constrained(n);
  std::vector<std::size_t> where(n * n);
  // The first pass keeps what the later uses of the cell matrices read: the flow scale's
  // full-film right-hand side (ReynoldsSolver::full_film_flow_scale), and for the constant terms
  // of assemble_by_products the matrices of the cells with a constrained dof and the others'
  // terms at a = v = 0
  if (first_pass)
  {
    const unsigned int n_cells = s.triangulation.n_active_cells();
    cell_A.assign(n_cells, FullMatrix<double>());
    cell_G.assign(n_cells, FullMatrix<double>());
    cell_F.assign(n_cells, Vector<double>());
    interior_constant.assign(std::size_t(n_cells) * n, 0.0);
    s.system_rhs = 0;
  }
  bool pattern_holds = true;
  auto add_cell = [&](const DoFHandler<2>::active_cell_iterator &cell, const FullMatrix<double> &A,
                      const FullMatrix<double> &G_k, const Vector<double> &F)
  {
    if (!pattern_holds)
      return;
    const auto k = cell->active_cell_index();
    cell->get_dof_indices(dofs);
    bool any_constrained = false;
    for (unsigned int i = 0; i < n; ++i)
    {
      is_constrained[i] = s.homogeneous_constraints.is_constrained(dofs[i]);
      any_constrained = any_constrained || is_constrained[i];
    }
    if (first_pass)
    {
      s.add_to_full_film_rhs(A, F, dofs);
      if (any_constrained)
      {
        cell_A[k] = A;
        cell_G[k] = G_k;
        cell_F[k] = F;
      }
      else
      {
        // assemble_by_products' constant terms of a cell without constrained dofs (its residual
        // and right-hand side are then the same values, b = r)
        cell_constant_terms(
            A, G_k, F, s.cavitation.pressure, P,
            [](unsigned int) {
              return std::pair{0.0, 0.0};
            },
            r, b);
        std::copy(r.begin(), r.end(), interior_constant.begin() + std::size_t(k) * n);
      }
    }
    // the same products as the cell-by-cell assembly (P * A(i, j), G(i, j))
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
      {
        J_PA(i, j) = P * A(i, j);
        J_G(i, j) = G_k(i, j);
      }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
      {
        // constrained rows and columns: homogeneous constraints drop the entry
        const bool kept = !is_constrained[i] && !is_constrained[j];
        where[i * n + j] = kept ? position(dofs[i], dofs[j]) : 0;
        if (kept && where[i * n + j] == missing)
        {
          pattern_holds = false;
          return;
        }
      }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        if (!is_constrained[i] && !is_constrained[j])
        {
          PA[where[i * n + j]] += J_PA(i, j);
          G[where[i * n + j]] += J_G(i, j);
        }
    if (any_constrained)
      for (auto [J, values] : {std::pair{&J_PA, &PA}, std::pair{&J_G, &G}})
      {
        // deal.II's set_matrix_diagonals, operation for operation
        double average_diagonal = 0;
        for (unsigned int i = 0; i < n; ++i)
          average_diagonal += std::abs((*J)(i, i));
        average_diagonal /= static_cast<double>(n);
        if (average_diagonal == 0.)
        {
          average_diagonal = J->l1_norm() / static_cast<double>(n);
          if (average_diagonal == 0.)
            average_diagonal = 1.;
        }
        for (unsigned int i = 0; i < n; ++i)
          if (is_constrained[i])
          {
            const std::size_t d = position(dofs[i], dofs[i]);
            if (d == missing)
            {
              pattern_holds = false;
              return;
            }
            const double diagonal = (*J)(i, i);
            (*values)[d] += std::abs(diagonal) != 0. ? std::abs(diagonal) : average_diagonal;
          }
      }
  };
  if (!first_pass) // (kept above)
  {
    for (const auto &cell : s.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const auto k = cell->active_cell_index();
        add_cell(cell, cell_A[k], cell_G[k], cell_F[k]);
      }
  }
  else
    s.for_each_cell_film_matrices(true, add_cell);
  if (!pattern_holds)
    return false; // (the first pass's partial results are made again by its caller)
  if (first_pass)
    flow_scale = s.flow_scale_of_full_film_rhs();
  global_PA = std::move(PA);
  global_G = std::move(G);
  global_matrices = 1;
  return true;
}

namespace
{
/// The local values of a one-rank Trilinos vector whose entries are the dofs 0 .. n-1 in order
/// (owned or ghosted: on one rank both hold every dof); null otherwise.
const double *plain_values(const TrilinosWrappers::MPI::Vector &x, const std::size_t n)
{
  // deal.II lists the indices of its maps explicitly (sorted), so the map is the identity when it
  // holds n entries from 0 to n - 1
  const auto &e = x.trilinos_vector();
  const auto &map = e.Map();
  // one rank only: a ghosted vector on a rank of several can hold every dof too (a small mesh),
  // and a sum over it would count the other ranks' dofs again (review, session 12)
  if (e.Comm().NumProc() != 1)
    return nullptr;
  if (n == 0 || static_cast<std::size_t>(map.NumMyElements()) != n || map.MinMyGID64() != 0 ||
      map.MaxMyGID64() != static_cast<long long>(n) - 1 || map.GID64(0) != 0)
    return nullptr;
  return e[0];
}

} // namespace

const double *JFOSolver::owned_values(const VectorType &x) const
{
  return owned_values(const_cast<VectorType &>(x));
}

double *JFOSolver::owned_values(VectorType &x) const
{
  // deal.II's map of an owned vector lists the owned indices in increasing order
  AssertThrow(!x.has_ghost_elements() &&
                  static_cast<std::size_t>(x.trilinos_vector().Map().NumMyElements()) ==
                      s.locally_owned_dofs.n_elements(),
              ExcInternalError());
  return x.trilinos_vector()[0];
}

unsigned int JFOSolver::find_ghosted_positions(const VectorType &x)
{
  // No MPI here (Epetra's SameAs is collective: it would pair with other ranks' calls where
  // the callers' conditions differ between ranks): the layout is known by its map's data, which
  // a, v, ta and tv share (the copy kept holds that data, so its address is not reused).
  if (!x.has_ghost_elements())
    return 0;
  const Epetra_BlockMap &layout = x.trilinos_vector().Map();
  if (ghosted_layout && layout.DataPtr() == ghosted_layout->DataPtr())
    return ghosted_layout_id;
  list_global_indices();
  column_in_ghosted.resize(column_gid.size());
  for (std::size_t c = 0; c < column_gid.size(); ++c)
    column_in_ghosted[c] = layout.LID(column_gid[c]);
  owned_in_ghosted.clear();
  owned_in_ghosted.reserve(s.locally_owned_dofs.n_elements());
  for (const auto i : s.locally_owned_dofs)
    owned_in_ghosted.push_back(layout.LID(static_cast<long long>(i)));
  ghosted_layout = std::make_unique<Epetra_BlockMap>(layout);
  return ++ghosted_layout_id;
}

void JFOSolver::list_global_indices()
{
  if (indices_listed)
    return;
  const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
  row_gid.resize(M.NumMyRows());
  for (int r = 0; r < M.NumMyRows(); ++r)
    row_gid[r] = M.RowMap().GID64(r);
  column_gid.resize(M.NumMyCols());
  for (int c = 0; c < M.NumMyCols(); ++c)
    column_gid[c] = M.ColMap().GID64(c);
  // by global index; the dofs of this rank's cells (on one rank every dof)
  constrained.assign(s.dof_handler.n_dofs(), 0);
  for (const auto i : s.locally_relevant_dofs)
    constrained[i] = s.homogeneous_constraints.is_constrained(i);
  indices_listed = true;
}

bool JFOSolver::values_at_columns(const VectorType &x, std::vector<double> &values)
{
  // on one rank from the plain layout, on several from the ghosted vector, which holds every
  // column of an owned row (a dof of a cell around it, owned or ghost, so locally relevant)
  list_global_indices();
  const std::size_t columns = column_gid.size();
  values.resize(columns);
  if (const double *plain = plain_values(x, s.dof_handler.n_dofs()))
  {
    for (std::size_t c = 0; c < columns; ++c)
      values[c] = plain[column_gid[c]];
    return true;
  }
  if (find_ghosted_positions(x) == 0)
    return false;
  const double *held = x.trilinos_vector()[0];
  for (std::size_t c = 0; c < columns; ++c)
  {
    if (column_in_ghosted[c] < 0)
      return false;
    values[c] = held[column_in_ghosted[c]];
  }
  return true;
}

bool JFOSolver::jacobian_by_columns(const VectorType &a, const VectorType &v)
{
  // Column j of the FB-Newton Jacobian (assemble(), reduced to the unknown each node keeps) is
  // P A(:, j) - (d_a / d_b) G(:, j) where node j keeps its pressure, else
  // G(:, j) - (d_b / d_a) P A(:, j). At a solution with a_j v_j = 0 and a_j + v_j > 0 the ratio is
  // zero and the column is bitwise the cell-by-cell one (the same sums; x - 0 y = x); at a node
  // with a_j = v_j = 0 the two differ by round-off. Constrained columns keep P A (their rows hold
  // only the diagonal, and their unknowns are fixed).
  // On several ranks each rank sets its own rows, from a and v at their columns (the ghosted
  // vectors); every rank takes the same path, as the caller's alternative (the cell loop) is
  // collective.
  if (global_matrices != 1 || assemble_by_cells)
    return false;
  TimerOutput::Scope timer_scope(s.timer, "jfo assembly");
  std::vector<double> column_a, column_v;
  const bool here =
      !row_gid.empty() && values_at_columns(a, column_a) && values_at_columns(v, column_v);
  if (Utilities::MPI::min(here ? 1 : 0, s.mpi_communicator) == 0)
    return false;
  const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
  std::vector<double> alpha(M.NumMyCols(), 1.0), beta(M.NumMyCols(), 0.0);
  for (int c = 0; c < M.NumMyCols(); ++c)
  {
    if (constrained[column_gid[c]])
      continue;
    const FischerBurmeister fb(column_a[c], column_v[c]);
    if (fb.keeps_pressure())
      beta[c] = -(fb.d_a / fb.d_b);
    else
    {
      alpha[c] = -(fb.d_b / fb.d_a);
      beta[c] = 1;
    }
  }
  for_each_row_on_threads(
      M,
      [&](int, const int entries, double *row_values, const int *columns, const std::size_t first)
      {
        for (int e = 0; e < entries; ++e)
          row_values[e] =
              alpha[columns[e]] * global_PA[first + e] + beta[columns[e]] * global_G[first + e];
      });
  return true;
}

bool JFOSolver::assemble_by_products(const VectorType &a, const VectorType &v, const bool with_rhs,
                                     const std::vector<bool> *only_rows)
{
  // residual = F - A p - G v with p = p_cav + P a; the active-set right-hand side adds back the
  // term of the unknown each node keeps: F - A p_cav - sum_j (a_j >= v_j ? P A_:j a_j : G_:j v_j)
  // (the cell-by-cell assemble() below, summed in another order). The constrained dofs' terms
  // are constant during a solve (their a and v never change) and sit in constant_residual and
  // constant_rhs, computed once by a loop over the cells. Rows by local index (this rank's
  // owned dofs in order), a and v by the matrix's local column index.
  if (global_matrices != 1 || assemble_by_cells)
    return false;
  const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
  list_global_indices();
  // the owned vectors' entry k is the k-th owned dof, the matrix's row k the same dof
  double *res = owned_values(residual), *rhs = owned_values(newton_rhs);
  const IndexSet &owned = s.locally_owned_dofs;
  bool layout =
      static_cast<std::size_t>(M.NumMyRows()) == owned.n_elements() &&
      (M.NumMyRows() == 0 ||
       (row_gid.front() == static_cast<long long>(owned.nth_index_in_set(0)) &&
        row_gid.back() == static_cast<long long>(owned.nth_index_in_set(owned.n_elements() - 1))));
  std::vector<double> column_a, column_v;
  layout = layout && values_at_columns(a, column_a) && values_at_columns(v, column_v);
  // every rank takes the same path (the constant terms' sums over the ranks are collective)
  if (Utilities::MPI::min(layout ? 1 : 0, s.mpi_communicator) == 0)
    return false;
  // the constrained dofs of this rank's cells: the same values as when the constant terms were
  // computed? (every rank recomputes together: the sums over the ranks are collective)
  std::vector<double> now_a, now_v;
  for (const auto i : s.locally_relevant_dofs)
    if (constrained[i])
    {
      now_a.push_back(a[i]);
      now_v.push_back(v[i]);
    }
  const bool same_here =
      !constant_residual.empty() && now_a == constrained_a && now_v == constrained_v;
  if (Utilities::MPI::min(same_here ? 1 : 0, s.mpi_communicator) == 0)
  {
    constrained_a = std::move(now_a);
    constrained_v = std::move(now_v);
    const unsigned int dofs_per_cell = s.fe->n_dofs_per_cell();
    const double P = s.pressure_scale;
    Vector<double> r(dofs_per_cell), b(dofs_per_cell);
    std::vector<types::global_dof_index> dofs(dofs_per_cell);
    VectorType c_res(s.locally_owned_dofs, s.mpi_communicator),
        c_rhs(s.locally_owned_dofs, s.mpi_communicator);
    for (const auto &cell : s.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const auto k = cell->active_cell_index();
        const FullMatrix<double> &A = cell_A[k], &G = cell_G[k];
        cell->get_dof_indices(dofs);
        if (A.m() == 0)
          // a cell without constrained dofs whose matrices the first pass did not keep
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            r(i) = b(i) = interior_constant[std::size_t(k) * dofs_per_cell + i];
        else
          cell_constant_terms(
              A, G, cell_F[k], s.cavitation.pressure, P,
              [&](const unsigned int j)
              {
                const auto J = dofs[j];
                return std::pair{constrained[J] ? a[J] : 0.0, constrained[J] ? v[J] : 0.0};
              },
              r, b);
        s.homogeneous_constraints.distribute_local_to_global(r, dofs, c_res);
        s.homogeneous_constraints.distribute_local_to_global(b, dofs, c_rhs);
      }
    c_res.compress(VectorOperation::add);
    c_rhs.compress(VectorOperation::add);
    const double *cr = owned_values(c_res), *cb = owned_values(c_rhs);
    constant_residual.assign(cr, cr + M.NumMyRows());
    constant_rhs.assign(cb, cb + M.NumMyRows());
  }
  std::vector<char> &keep_pressure = column_keeps_pressure;
  keep_pressure.clear();
  if (with_rhs)
  {
    keep_pressure.resize(column_a.size());
    for (std::size_t c = 0; c < column_a.size(); ++c)
      keep_pressure[c] = column_a[c] >= column_v[c];
  }
  for_each_row_on_threads(M,
                          [&](const int row, const int entries, const double *, const int *columns,
                              const std::size_t first)
                          {
                            if (only_rows && !(*only_rows)[row_gid[row]])
                              return;
                            if (constrained[row_gid[row]])
                            {
                              res[row] = 0;
                              if (with_rhs)
                                rhs[row] = 0;
                              return;
                            }
                            // constrained columns hold zeros in the condensed P A and G (their
                            // terms are constant)
                            double r = constant_residual[row], b = constant_rhs[row];
                            for (int e = 0; e < entries; ++e)
                            {
                              const int c = columns[e];
                              const double pa_e = global_PA[first + e] * column_a[c],
                                           g_e = global_G[first + e] * column_v[c];
                              r -= pa_e + g_e;
                              if (with_rhs)
                                b -= keep_pressure[c] ? pa_e : g_e;
                            }
                            res[row] = r;
                            if (with_rhs)
                              rhs[row] = b;
                          });
  return true;
}

double JFOSolver::assemble(const VectorType &a, const VectorType &v, const bool with_jacobian,
                           const bool active_set_step, const std::vector<bool> *only_rows)
{
  // the global matrices are prepared outside this timer (in "jfo cell matrices")
  // the global matrices serve the active-set Jacobians and every residual (a polish, which
  // needs them, is the first thing every solve does after its first residual)
  const bool select_columns =
      (!with_jacobian || active_set_step) && prepare_global_matrices() && with_jacobian;
  TimerOutput::Scope timer_scope(s.timer, "jfo assembly");
  const bool by_products =
      (select_columns || !with_jacobian) && assemble_by_products(a, v, with_jacobian, only_rows);
  // (the cell-by-cell path makes every row)
  if (!by_products)
    only_rows = nullptr;
  const unsigned int n = s.fe->n_dofs_per_cell();
  FullMatrix<double> J(n, n);
  Vector<double> R(n), correction(n), local_a(n), local_v(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  const double P = s.pressure_scale;

  if (with_jacobian && !by_products)
  {
    if (!select_columns)
      s.system_matrix = 0;
    newton_rhs = 0;
  }
  if (!by_products)
  {
    residual = 0;
    // (outside the one pass's reach: the matrices of every cell, made here a second time after a
    // one pass, under this timer, at a cost not measured; the measured cases never get here:
    // they end on a polish and take the Jacobian at the solution by columns)
    keep_cell_matrices();
  }
  if (!by_products)
    for (const auto &cell : s.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const auto k = cell->active_cell_index();
        const FullMatrix<double> &A = cell_A[k], &G = cell_G[k];
        cell->get_dof_indices(dofs);
        cell->get_dof_values(a, local_a);
        cell->get_dof_values(v, local_v);
        for (unsigned int j = 0; j < n; ++j)
          local_p(j) = s.cavitation.pressure + P * local_a(j);
        A.vmult(R, local_p);
        R -= cell_F[k];
        G.vmult_add(R, local_v);
        R *= -1.0; // residual vector holds -R
        // A cell without constrained dofs by position (CellSparsity, where the system matrix was
        // built by it): the same additions in the same order as distribute_local_to_global,
        // without its index translation (adding a zero to an owned entry leaves its bits). The
        // FB-Newton steps' Jacobians and the rounds on meshes with hanging nodes take this path
        CellSparsity::distribute(s.homogeneous_constraints, s.matrix_by_position, R, dofs,
                                 residual);
        if (with_jacobian)
        {
          correction = 0;
          for (unsigned int j = 0; j < n; ++j)
          {
            const FischerBurmeister fb(local_a(j), local_v(j));
            if (active_set_step)
            {
              // Active-set step: the node keeps the larger of its two unknowns, the other is set
              // to zero (its current value moves to the right-hand side).
              const bool keep_pressure = local_a(j) >= local_v(j);
              for (unsigned int i = 0; i < n; ++i)
              {
                if (!select_columns) // else the global matrix takes its columns whole
                  J(i, j) = keep_pressure ? P * A(i, j) : G(i, j);
                correction(i) += keep_pressure ? G(i, j) * local_v(j) : P * A(i, j) * local_a(j);
              }
            }
            else if (fb.keeps_pressure())
            {
              const double ratio = fb.d_a / fb.d_b, shift = fb.value / fb.d_b;
              for (unsigned int i = 0; i < n; ++i)
              {
                J(i, j) = P * A(i, j) - G(i, j) * ratio;
                correction(i) += G(i, j) * shift;
              }
            }
            else
            {
              const double ratio = fb.d_b / fb.d_a, shift = fb.value / fb.d_a;
              for (unsigned int i = 0; i < n; ++i)
              {
                J(i, j) = G(i, j) - P * A(i, j) * ratio;
                correction(i) += P * A(i, j) * shift;
              }
            }
          }
          R += correction;
          if (select_columns)
            CellSparsity::distribute(s.homogeneous_constraints, s.matrix_by_position, R, dofs,
                                     newton_rhs);
          else
            CellSparsity::distribute(s.homogeneous_constraints, s.matrix_by_position, J, R, dofs,
                                     s.system_matrix, newton_rhs);
        }
      }
  if (!by_products)
    residual.compress(VectorOperation::add);
  if (with_jacobian)
  {
    if (select_columns)
    {
      // column j from P A where node j keeps its pressure (a_j >= v_j), else from G
      // the values are set in place (for_each_row); the flags are those of the residual by
      // products just made, else gathered here
      const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
      if (!by_products)
      {
        std::vector<double> column_a, column_v;
        AssertThrow(values_at_columns(a, column_a) && values_at_columns(v, column_v),
                    ExcMessage("JFO: a column of the Jacobian without its value on this rank"));
        column_keeps_pressure.resize(M.NumMyCols());
        for (int c = 0; c < M.NumMyCols(); ++c)
          column_keeps_pressure[c] = column_a[c] >= column_v[c];
      }
      const std::vector<char> &keep_pressure = column_keeps_pressure;
      AssertThrow(keep_pressure.size() == static_cast<std::size_t>(M.NumMyCols()),
                  ExcInternalError());
      for_each_row_on_threads(M,
                              [&](const int row, const int entries, double *row_values,
                                  const int *columns, const std::size_t first)
                              {
                                if (only_rows && !(*only_rows)[row_gid[row]])
                                  return;
                                for (int e = 0; e < entries; ++e)
                                  row_values[e] = keep_pressure[columns[e]] ? global_PA[first + e]
                                                                            : global_G[first + e];
                              });
    }
    else
      s.system_matrix.compress(VectorOperation::add);
    if (!by_products)
      newton_rhs.compress(VectorOperation::add);
  }
  // a band round's rows only: no merit of the whole system (the polish does not read it)
  if (only_rows)
    return std::numeric_limits<double>::quiet_NaN();
  double fb_squared = 0;
  const std::size_t n_dofs = s.dof_handler.n_dofs();
  if (const double *pa = plain_values(a, n_dofs), *pv = plain_values(v, n_dofs); pa && pv)
  {
    // one rank: the same sum without a map lookup per entry
    for (std::size_t i = 0; i < n_dofs; ++i)
      if (!s.homogeneous_constraints.is_constrained(i))
        fb_squared += Utilities::fixed_power<2>(FischerBurmeister(pa[i], pv[i]).value);
  }
  else if (const unsigned int layout = find_ghosted_positions(a);
           layout != 0 && find_ghosted_positions(v) == layout)
  {
    // several ranks: a and v of one layout (a lookup per dof was 0.08 s at 1.05e6 dofs)
    const double *held_a = a.trilinos_vector()[0], *held_v = v.trilinos_vector()[0];
    std::size_t k = 0;
    for (const auto i : s.locally_owned_dofs)
    {
      if (!s.homogeneous_constraints.is_constrained(i))
        fb_squared += Utilities::fixed_power<2>(
            FischerBurmeister(held_a[owned_in_ghosted[k]], held_v[owned_in_ghosted[k]]).value);
      ++k;
    }
  }
  else
    for (const auto i : s.locally_owned_dofs)
      if (!s.homogeneous_constraints.is_constrained(i))
        fb_squared += Utilities::fixed_power<2>(FischerBurmeister(a[i], v[i]).value);
  fb_squared = Utilities::MPI::sum(fb_squared, s.mpi_communicator);
  const double r = residual.l2_norm() / flow_scale;
  return 0.5 * (r * r + fb_squared);
}
void JFOSolver::warm_start()
{
  // Warm start. The Newton iteration moves the cavity boundary by about one cell per iteration
  // (measured: 17, 63, 168, 400 iterations on 32, 64, 128, 256 cells around), so it starts from
  // the converged JFO state of the mesh twice as coarse (recursively, mesh sequencing), evaluated
  // at this mesh's nodes; on the coarsest mesh from the full film: a = (p - p_cav)/P where
  // positive, else a = 0 with a small void.
  // The full film is solved only when there is no coarse start (ReynoldsSolver::run does not).
  // On textured faces the sequencing stops at the coarsest level that still resolves the
  // dimples, and never regenerates a gmsh mesh (AnnulusMesh::sequences_jfo): such levels gave no
  // better start (the same global factorisations on the finest mesh) and cost their own solves,
  // or another gmsh run (doc/textures.md, Cost of JFO on resolved faces).
  const bool started_coarse = coarse_start();
  // (the coarse level's band start decides this level's, JFOSolver::polish)
  band_first = band_start && started_coarse && !s.coarse_solver->jfo_band_start_failed;
  // every rank takes the same path (the band rounds are collective); the coarse levels solved
  // whole on each rank (MPI_COMM_SELF) should agree, but nothing makes them
  band_first = Utilities::MPI::min(band_first ? 1 : 0, s.mpi_communicator) != 0;
  s.jfo_band_start_failed = started_coarse && !band_first;
  if (!started_coarse)
  {
    // the full film, assembled here only (not in ReynoldsSolver::run)
    s.assemble_system();
    s.solve();
    s.pressure_scale = s.full_film_pressure_scale();
    for (const auto i : s.locally_owned_dofs)
    {
      const double d = (s.locally_relevant_solution[i] - s.cavitation.pressure) / s.pressure_scale;
      a_owned[i] = std::max(d, 0.0);
      v_owned[i] = d < 0 ? std::min(-d, 1e-3) : 0.0;
    }
  }
  a_owned.compress(VectorOperation::insert);
  v_owned.compress(VectorOperation::insert);
  a = a_owned;
  v = v_owned;
  best_a = a_owned;
  best_v = v_owned;
}

bool JFOSolver::coarse_start()
{
  std::vector<double> pressure, void_fraction;
  if (!s.coarse_level_state(pressure, void_fraction)) // sets s.pressure_scale
    return false;
  double *pa = owned_values(a_owned), *pv = owned_values(v_owned);
  for (std::size_t k = 0; k < pressure.size(); ++k)
  {
    pa[k] = std::max((pressure[k] - s.cavitation.pressure) / s.pressure_scale, 0.0);
    pv[k] = std::clamp(void_fraction[k], 0.0, 1.0);
  }
  return true;
}

double JFOSolver::complementarity(const VectorType &aa, const VectorType &vv) const
{
  double m = 0;
  const double *pa = owned_values(aa), *pv = owned_values(vv);
  std::size_t k = 0;
  for (const auto i : s.locally_owned_dofs)
  {
    if (!s.homogeneous_constraints.is_constrained(i))
      m = std::max(m, std::abs(FischerBurmeister(pa[k], pv[k]).value));
    ++k;
  }
  return Utilities::MPI::max(m, s.mpi_communicator);
}

void JFOSolver::recover()
{
  // Newton update of (a, v) from the reduced unknown w (each node's eliminated unknown from its
  // linearised complementarity row).
  for (const auto i : s.locally_owned_dofs)
  {
    if (s.homogeneous_constraints.is_constrained(i))
    {
      da[i] = dv[i] = 0;
      continue;
    }
    const FischerBurmeister fb(a_owned[i], v_owned[i]);
    if (fb.keeps_pressure())
    {
      da[i] = w[i];
      dv[i] = (-fb.value - fb.d_a * w[i]) / fb.d_b;
    }
    else
    {
      dv[i] = w[i];
      da[i] = (-fb.value - fb.d_b * w[i]) / fb.d_a;
    }
  }
  da.compress(VectorOperation::insert);
  dv.compress(VectorOperation::insert);
}

void JFOSolver::newton_direction()
{
  s.factorize(false, true);
  w = 0;
  s.solve_linear_system(newton_rhs, w);
  s.homogeneous_constraints.set_zero(w);
  recover();
}

void JFOSolver::remember_factored_set(const VectorType &set_a, const VectorType &set_v)
{
  factored_keep_pressure.clear();
  const std::size_t n = s.dof_handler.n_dofs();
  const double *pa = plain_values(set_a, n), *pv = plain_values(set_v, n);
  if (global_matrices != 1 || assemble_by_cells || low_rank_limit == 0 || !pa || !pv ||
      !s.linear_system_solver.factorization())
    return;
  factored_keep_pressure.resize(n);
  for (std::size_t j = 0; j < n; ++j)
    factored_keep_pressure[j] = pa[j] >= pv[j];
  factored_count = s.linear_system_solver.statistics().factorizations;
}

bool JFOSolver::low_rank_solve(const VectorType &set_a, const VectorType &set_v)
{
  // The Jacobian of a fixed set takes column j from P A where node j keeps its pressure, else
  // from G, so that of the set (set_a, set_v) is the factorised one plus a rank-k term, k the
  // nodes whose set differs: A1 = A0 + U E^T with U(:, d) = +-(P A - G)(:, j_d). With A0's
  // factors, two solves and the k x k entries E^T A0^-1 U (MUMPS: selected entries of A0^-1;
  // KLU: a block solve of k + 1 columns) and a k x k system cost less than a new factorisation
  // for small k (doc/performance.md, Sessions 11 and 18). The accepted round (no flips) may be one
  // of these: solve_column_update checks the backward error of A1's true residual <= 128 u, else
  // the round factorises; the converged state is verified by the nonlinear residual.
  SparseDirect *lu = s.linear_system_solver.factorization();
  if (factored_keep_pressure.empty() || !lu || row_gid.empty() ||
      s.linear_system_solver.statistics().factorizations != factored_count)
    return false;
  const std::size_t n = s.dof_handler.n_dofs();
  const double *pa = plain_values(set_a, n), *pv = plain_values(set_v, n),
               *b = plain_values(newton_rhs, n);
  double *x = const_cast<double *>(plain_values(w, n));
  if (!pa || !pv || !b || !x)
    return false;
  std::vector<int> position(n, -1);
  std::vector<unsigned int> columns;
  for (std::size_t j = 0; j < n; ++j)
    if (!constrained[j] && (pa[j] >= pv[j]) != static_cast<bool>(factored_keep_pressure[j]))
    {
      if (columns.size() == low_rank_limit)
        return false;
      position[j] = columns.size();
      columns.push_back(j);
    }
  TimerOutput::Scope timer_scope(s.timer, "jfo low-rank update");
  std::vector<SparseColumn> U(columns.size());
  const Epetra_CrsMatrix &M = s.system_matrix.trilinos_matrix();
  for_each_row(M,
               [&](const int row, const int entries, const double *, const int *row_columns,
                   const std::size_t first)
               {
                 for (int e = 0; e < entries; ++e)
                 {
                   const auto j = column_gid[row_columns[e]];
                   if (position[j] >= 0)
                   {
                     const double difference = global_PA[first + e] - global_G[first + e];
                     U[position[j]].emplace_back(row_gid[row],
                                                 pa[j] >= pv[j] ? difference : -difference);
                   }
                 }
               });
  // C is refused below rcond sqrt(u): its solve would lose more than half the digits. The
  // backward error bound 128 u (2^-46, 1.4e-14; u = 2^-53) is a guard against a failed update, with
  // a margin over the round-off of a backward-stable solve (the factorised rounds' solves measure
  // 7e-19..4e-17, the updates 4e-19..4e-17 on the tilted seal at 3.3e4 and 1.3e5 dofs)
  double rcond, backward_error;
  const LowRankSolve result = solve_column_update(*lu, s.system_matrix, columns, U, b, x,
                                                  std::sqrt(std::numeric_limits<double>::epsilon()),
                                                  0x1p-46, rcond, backward_error);
  if (result != LowRankSolve::solved)
    return false;
  ++low_rank_updates;
  return true;
}

void JFOSolver::probe_krylov(const VectorType &set_a, const VectorType &set_v,
                             const double direct_seconds, const unsigned int round,
                             const char *variants)
{
  // Stage-1 measurement of session 13 (doc/performance.md): the global round's system by GMRES
  // with the block-triangular preconditioner, against the direct solution w just computed.
  const std::size_t n = s.dof_handler.n_dofs();
  // SEALFE_JFO_KRYLOV_PROBE_MIN_DOFS: probe only the levels this large (the coarse levels of a
  // 5e5-dof run would otherwise cost as much again)
  if (const char *min_dofs = std::getenv("SEALFE_JFO_KRYLOV_PROBE_MIN_DOFS");
      min_dofs && n < std::strtoull(min_dofs, nullptr, 10))
    return;
  const double *pa = owned_values(set_a), *pv = owned_values(set_v);
  std::vector<char> full_film(n), is_constrained(n);
  std::vector<double> base_value(n), x(n), y(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    is_constrained[i] = s.homogeneous_constraints.is_constrained(i);
    full_film[i] = is_constrained[i] || pa[i] >= pv[i];
    base_value[i] = pa[i] >= pv[i] ? pa[i] : pv[i];
  }
  // (one rank: owned index = dof number)
  const std::vector<Point<2>> support = s.owned_support_points();
  for (std::size_t i = 0; i < n; ++i)
  {
    x[i] = support[i][0];
    y[i] = support[i][1];
  }
  probe_active_set_round(s.system_matrix, newton_rhs, w, full_film, is_constrained, base_value, x,
                         y, s.polynomial_degree, flow_scale, direct_seconds, round, variants,
                         std::cerr);
}

bool JFOSolver::polish()
{
  // Active-set polish: with the cavitated set fixed the discrete problem is linear. Starting
  // from the set read off the current iterate (v > a), nodes whose solution is inconsistent
  // (a < 0 on a pressure node, v < 0 on a cavitated one) switch set and the linear problem is
  // solved again (primal-dual active set). A consistent solution is the exact JFO solution
  // and ends the iteration at the next check; after a few unsuccessful rounds the polish is
  // abandoned for this iteration and the FB-Newton step is taken.
  // Band rounds: a set change moves the solution mostly near the nodes that flipped,
  // so after a global round with flips the next rounds solve only for the nodes within
  // band_layers graph layers of the last flips (the rest held), a small factorisation; when a
  // band round flips nothing, a global round checks the set. Only a global round without flips
  // is accepted, so the answer is that of global rounds.
  VectorType set_a(a_owned), set_v(v_owned);
  bool consistent = false, band = false;
  const bool serial = Utilities::MPI::n_mpi_processes(s.mpi_communicator) == 1;
  // by global index on every rank: each rank marks its own dofs, grow_in_graph unites them
  // (and the last round's: a node that flips again in the next round marks a set that goes back
  // and forth; longer cycles run into the cap of 10 band rounds in a row)
  std::vector<bool> flipped(s.dof_handler.n_dofs(), false), last_flipped(flipped);
  // a band is seeded by fewer than this many nodes (flips, or the start's boundary); more are
  // found faster by a global round
  const std::size_t max_band_seeds = s.dof_handler.n_dofs() / 20;
  // flips of the band rounds from the start, and whether the first global round is still due
  unsigned int band_start_flips = 0;
  bool in_band_start = band_first;
  if (band_first)
  {
    // A start interpolated from the mesh twice as coarse has its cavity boundary within about a
    // coarse cell of the right place: the set changes near that boundary (811 nodes in the first
    // round of the tilted seal at 5.3e5 dofs), and a global round made from that set would be
    // factorised for nothing but those flips. Band rounds about the start's boundary move it
    // first, so that the first global round flips few nodes (34 on that seal) and the confirming
    // round is a low-rank update of its factorisation (low_rank_solve). Where the coarse level's
    // error lies away from the boundary, the global round still flips many (the wavy example:
    // 2854 after 4276 in band rounds); the finer levels then start with a global round.
    band_first = false;
    TimerOutput::Scope timer_scope(s.timer, "jfo band rounds");
    std::vector<bool> cavitated(flipped.size(), false), full_film(flipped.size(), false);
    const double *pa = owned_values(set_a), *pv = owned_values(set_v);
    std::size_t k = 0;
    for (const auto i : s.locally_owned_dofs)
    {
      if (!s.homogeneous_constraints.is_constrained(i))
        (pa[k] >= pv[k] ? full_film : cavitated)[i] = true;
      ++k;
    }
    // the boundary: nodes with a neighbour in the other set, on both sides
    const std::vector<bool> near_cavity = grow_in_graph(s.system_matrix, cavitated, 1),
                            near_film = grow_in_graph(s.system_matrix, full_film, 1);
    // (the seeds of the first band)
    std::size_t seeds = 0;
    for (std::size_t i = 0; i < flipped.size(); ++i)
    {
      flipped[i] = near_cavity[i] && near_film[i];
      seeds += flipped[i];
    }
    band = seeds > 0 && seeds < max_band_seeds;
    // not taken (no boundary, or one too long: small coarse levels): no verdict on the start,
    // the finer level tries its own
    in_band_start = band;
  }
  // 4 layers: measured 1.17 s against 1.12 s (2 layers) on the tilted 64 x 128 case, 0.88 s
  // against 1.19 s on wavy_jfo 16 x 512; 0 layers (the flipped nodes only) took 19 rounds
  constexpr unsigned int band_layers = 4;
  unsigned int global_rounds = 0;
  BandRoundRule band_rule(max_band_seeds);
  for (unsigned int round = 0; global_rounds < 40 && round < 400 && !consistent; ++round)
  {
    ta = set_a;
    tv = set_v;
    // a band round needs only its band's rows (on the tilted seal at 5.3e5 dofs 11 of the 13
    // rounds of the finest level are band rounds, each band a few % of the dofs)
    std::vector<bool> band_dofs;
    if (band)
    {
      TimerOutput::Scope timer_scope(s.timer, "jfo band rounds");
      band_dofs = grow_in_graph(s.system_matrix, flipped, band_layers);
    }
    assemble(ta, tv, true, true, band ? &band_dofs : nullptr);
    ++active_set_rounds;
    w = 0;
    if (band)
    {
      ++band_rounds;
      TimerOutput::Scope timer_scope(s.timer, "jfo band rounds");
      band_workspace_retries += solve_on_subset(s.system_matrix, band_dofs, newton_rhs, w,
                                                s.linear_system_solver.direct_team());
    }
    else
    {
      ++global_rounds;
      // the confirming rounds differ from the last factorised one in few columns
      if (!low_rank_solve(set_a, set_v))
      {
        const auto direct_start = std::chrono::steady_clock::now();
        s.factorize(false, true);
        s.solve_linear_system(newton_rhs, w);
        if (const char *probe = std::getenv("SEALFE_JFO_KRYLOV_PROBE"); probe && serial)
          probe_krylov(
              set_a, set_v,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - direct_start)
                  .count(),
              global_rounds, probe);
        remember_factored_set(set_a, set_v);
      }
    }
    s.homogeneous_constraints.set_zero(w);
    last_flipped.swap(flipped);
    std::fill(flipped.begin(), flipped.end(), false);
    // flips of nodes that also flipped in the round before: the set goes back and forth
    unsigned int flips = 0, flips_back = 0;
    // the owned entries by local index (k-th owned dof): an access by global index looks the
    // index up in the vector's map, 8 times per dof and round
    double *sa = owned_values(set_a), *sv = owned_values(set_v), *xa = owned_values(trial_a),
           *xv = owned_values(trial_v);
    const double *dw = owned_values(w);
    std::size_t k = 0;
    for (const auto i : s.locally_owned_dofs)
    {
      if (s.homogeneous_constraints.is_constrained(i))
      {
        xa[k] = sa[k];
        xv[k] = sv[k];
        ++k;
        continue;
      }
      const bool keep_pressure = sa[k] >= sv[k];
      const double value = (keep_pressure ? sa[k] : sv[k]) + dw[k];
      // round-off of the linear solve (values are O(1)) is not a set change
      xa[k] = keep_pressure ? std::max(value, 0.0) : 0.0;
      xv[k] = keep_pressure ? 0.0 : std::max(value, 0.0);
      if (value < -1e-12)
      {
        // switch set: a tiny value of the other unknown marks the new set
        ++flips;
        flips_back += last_flipped[i];
        flipped[i] = true;
        sa[k] = keep_pressure ? 0.0 : 1e-300;
        sv[k] = keep_pressure ? 1e-300 : 0.0;
      }
      else
      {
        sa[k] = xa[k];
        sv[k] = xv[k];
      }
      ++k;
    }
    trial_a.compress(VectorOperation::insert);
    trial_v.compress(VectorOperation::insert);
    set_a.compress(VectorOperation::insert);
    set_v.compress(VectorOperation::insert);
    {
      // one reduction for both counts
      std::array<unsigned int, 2> counts{{flips, flips_back}};
      Utilities::MPI::sum(ArrayView<const unsigned int>(counts), s.mpi_communicator,
                          ArrayView<unsigned int>(counts));
      flips = counts[0];
      flips_back = counts[1];
    }
    if (in_band_start && band)
      band_start_flips += flips;
    else if (in_band_start)
    {
      // The band start failed when its global round flips more than a tenth of what the band
      // rounds flipped (measured: 0-3 % on the tilted seal from 544 to 5.3e5 dofs, 37-105 %
      // on the wavy example from 640 dofs)
      in_band_start = false;
      s.jfo_band_start_failed = 10 * flips > band_start_flips;
    }
    // A start for the next finer mesh (mesh sequencing) needs no global check.
    // (a band round before any global round holds values interpolated from the coarse level)
    consistent = (!band || (s.start_only && global_rounds > 0)) && flips == 0;
    // band or global next (band_round_rule.h: at most 10 band rounds in a row, going on while
    // their flips fall or a front creeps; none after a global round that flipped more)
    band = band_rule.next_is_band(band, flips, flips_back);
  }
  if (consistent)
  {
    a_owned = trial_a;
    v_owned = trial_v;
    a = a_owned;
    v = v_owned;
  }
  return consistent;
}

void JFOSolver::step(double merit)
{
  // Projected full steps with a watchdog: the Newton step with a and v clipped at zero keeps
  // the iterate feasible and moves the cavity boundary as far as the linearisation says, which
  // the FB merit line search alone does not (it creeps when a full step trades mass residual
  // for complementarity residual: 31 instead of 5 iterations on the default mesh). Such steps
  // may raise the merit for a while; after 10 of them without a new best merit the iteration
  // returns to the best iterate and continues with Armijo backtracking on the merit, along
  // which the FB-Newton direction is a descent direction (so the method cannot cycle).
  double step = 1;
  if (merit < best_merit)
  {
    best_merit = merit;
    best_a = a_owned;
    best_v = v_owned;
    steps_without_progress = 0;
  }
  else
    ++steps_without_progress;
  if (!monotone && steps_without_progress >= 10)
  {
    // Back to the best iterate; from there on plain FB-Newton with backtracking.
    monotone = true;
    a_owned = best_a;
    v_owned = best_v;
    a = a_owned;
    v = v_owned;
    merit = assemble(a, v, true);
    newton_direction();
  }
  if (!monotone)
  {
    trial_a = a_owned;
    trial_a.add(1.0, da);
    trial_v = v_owned;
    trial_v.add(1.0, dv);
    for (const auto i : s.locally_owned_dofs)
    {
      trial_a[i] = std::max(static_cast<double>(trial_a[i]), 0.0);
      trial_v[i] = std::max(static_cast<double>(trial_v[i]), 0.0);
    }
    trial_a.compress(VectorOperation::insert);
    trial_v.compress(VectorOperation::insert);
    da = trial_a;
    da -= a_owned;
    dv = trial_v;
    dv -= v_owned;
  }
  else
    for (unsigned int ls = 0; ls < 30; ++ls, step *= 0.5)
    {
      trial_a = a_owned;
      trial_a.add(step, da);
      trial_v = v_owned;
      trial_v.add(step, dv);
      ta = trial_a;
      tv = trial_v;
      if (assemble(ta, tv, false) <= (1 - 1e-4 * step) * merit)
        break;
    }
  a_owned.add(step, da);
  v_owned.add(step, dv);
  a = a_owned;
  v = v_owned;
}

void JFOSolver::solve()
{
  // (the start sets the pressure scale P of the global P A; a full-film start assembles and
  // solves the full film, whose right-hand side the flow scale then makes again, the same bits)
  warm_start();
  // One rank with Dirichlet conditions only: the cell matrices are read once, in one pass that
  // makes the global P A and G, the flow scale and the constant terms (0.36 GB not held at
  // 1.05e6 dofs, doc/performance.md "Session 31"); else they are kept for the cell loops.
  bool one_pass = false;
  {
    TimerOutput::Scope timer_scope(s.timer, "jfo cell matrices");
    one_pass = !assemble_by_cells && make_global_matrices(true);
    if (!one_pass)
      keep_cell_matrices();
  }
  if (!one_pass) // (its own timer, "assemble")
    flow_scale = s.full_film_flow_scale(cell_A, cell_F);
  else if (!s.start_only)
    ++solves_in_one_pass;
  unsigned int next_polish = 0, polish_gap = 1;
  double mass_residual = 0, complementarity_residual = 0;
  bool converged = false;
  unsigned int it = 0;
  // progress on stderr (rank 0) once a solve runs longer than 2 s, then every 2 s
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  // merits at the start of each iteration: the failure message says how fast the last ten fell
  std::vector<double> merits;
  // whether the system matrix holds the FB-Newton Jacobian at the current iterate
  bool jacobian_at_iterate = false;
  for (; it < s.cavitation.maximum_iterations; ++it)
  {
    // Where a polish follows, it assembles its own systems (and after a failed polish the
    // Jacobian is assembled again), so only the residual is needed here: the FB-Newton Jacobian
    // of this point was never used (a cell-by-cell matrix assembly, 4 % of the JFO time at
    // 1.3e5 dofs).
    const bool polish_due = it >= next_polish;
    double merit = assemble(a, v, !polish_due);
    jacobian_at_iterate = !polish_due;
    merits.push_back(merit);
    mass_residual = residual.l2_norm() / flow_scale;
    complementarity_residual = complementarity(a_owned, v_owned);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_report > std::chrono::seconds(2) && s.reports_progress &&
        Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0)
    {
      std::cerr << "sealfe: JFO Newton iteration " << it << ", relative mass residual "
                << mass_residual << ", complementarity " << complementarity_residual
                << " (tolerance " << s.cavitation.tolerance << ", "
                << std::chrono::duration<double>(now - start).count() << " s)" << std::endl;
      last_report = now;
    }
    if (mass_residual < s.cavitation.tolerance && complementarity_residual < s.cavitation.tolerance)
    {
      converged = true;
      break;
    }
    if (it >= next_polish)
    {
      const bool consistent = polish();
      // After a failed polish the next one waits twice as long (it costs up to 40 solves).
      next_polish = it + polish_gap;
      polish_gap *= 2;
      if (consistent && s.start_only)
      {
        converged = true;
        break;
      }
      if (consistent)
        continue;
      merit = assemble(a, v, true);
      jacobian_at_iterate = true;
    }
    newton_direction();
    step(merit);
  }
  // Every linearised solve counts: FB-Newton steps and active-set rounds.
  s.cavitation_iterations = it + active_set_rounds;
  s.jfo_newton_steps = it;
  s.jfo_active_set_rounds = active_set_rounds;
  s.jfo_band_rounds = band_rounds;
  s.jfo_band_workspace_retries = band_workspace_retries;
  s.jfo_low_rank_updates = low_rank_updates;
  s.cavitation_residual = std::max(mass_residual, complementarity_residual);
  if (!converged)
  {
    std::ostringstream m;
    m << "Cavitation (jfo): no convergence in " << s.cavitation.maximum_iterations
      << " Newton iterations (relative mass residual " << mass_residual
      << ", complementarity residual " << complementarity_residual << ", tolerance "
      << s.cavitation.tolerance << ")";
    // A creeping iteration (the merit falling by less than half in ten iterations) is not
    // helped by more iterations: say so, with the rate, instead of advising a higher cap.
    constexpr unsigned int window = 10;
    const double ratio =
        merits.size() > window ? merits.back() / merits[merits.size() - 1 - window] : 0.0;
    if (ratio > 0.5)
    {
      const double target = 0.5 * s.cavitation.tolerance * s.cavitation.tolerance;
      m << "; the iteration creeps: its merit fell by only "
        << std::max(0.0, std::round(100 * (1 - ratio))) << " % in the last " << window
        << " iterations";
      if (ratio < 1 && merits.back() > target)
        m << " (at that rate about "
          << std::ceil(window * std::log(target / merits.back()) / std::log(ratio))
          << " more to the tolerance)";
      m << ", so raising Cavitation/Maximum iterations will not help";
      if (s.polynomial_degree > 1 && s.settings.geometry.features)
        m << "; surface features whose steps cut cells in a cavitated zone (dimples on a tilted "
             "face) can defeat the degree-2 iteration where Polynomial degree = 1 or a mesh "
             "fitted to the features (Discretization/Mesh size) converges (doc/cavitation.md)";
    }
    else
      m << "; refine the mesh or raise Cavitation/Maximum iterations";
    throw std::runtime_error(m.str());
  }
  s.last_iterations += it;
  // the Jacobian at the solution, for the linearised loads (a start-only level has none)
  if (!s.start_only)
  {
    const bool by_columns = !jacobian_at_iterate && jacobian_by_columns(a, v);
    if (!jacobian_at_iterate && !by_columns)
      assemble(a, v, true);
    ++(by_columns ? jacobians_by_columns : jacobians_by_cells);
  }
  store_solution();
}

JFOSolver::GlobalMatricesAndAssembly JFOSolver::global_matrices_and_assembly()
{
  GlobalMatricesAndAssembly m;
  keep_cell_matrices();
  if (!prepare_global_matrices())
    return m;
  m.PA = global_PA;
  m.G = global_G;
  const unsigned int n = s.fe->n_dofs_per_cell();
  FullMatrix<double> J(n, n);
  std::vector<types::global_dof_index> dofs(n);
  for (std::vector<double> *values : {&m.assembled_PA, &m.assembled_G})
  {
    const bool pressure = values == &m.assembled_PA;
    TrilinosWrappers::SparseMatrix M;
    M.copy_from(s.system_matrix); // its pattern, maps and storage order
    M = 0;
    for (const auto &cell : s.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const auto k = cell->active_cell_index();
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            J(i, j) = pressure ? s.pressure_scale * cell_A[k](i, j) : cell_G[k](i, j);
        cell->get_dof_indices(dofs);
        s.homogeneous_constraints.distribute_local_to_global(J, dofs, M);
      }
    M.compress(VectorOperation::add);
    for_each_row(M.trilinos_matrix(),
                 [&](int, const int entries, const double *row_values, const int *, std::size_t)
                 { values->insert(values->end(), row_values, row_values + entries); });
  }
  return m;
}

std::pair<std::vector<double>, std::vector<double>> JFOSolver::full_film_rhs_both_ways()
{
  const std::size_t n = s.locally_owned_dofs.n_elements();
  keep_cell_matrices();
  s.full_film_flow_scale(cell_A, cell_F);
  const double *from_cells = owned_values(s.system_rhs);
  std::pair<std::vector<double>, std::vector<double>> rhs;
  rhs.first.assign(from_cells, from_cells + n);
  s.assemble_system();
  const double *assembled = owned_values(s.system_rhs);
  rhs.second.assign(assembled, assembled + n);
  return rhs;
}

std::vector<double> JFOSolver::jacobian_at_solution(const bool by_columns)
{
  keep_cell_matrices();
  // The solution's unknowns: v as stored, a = (p - p_cav)/P from p = p_cav + P a, exact where
  // a = 0 and within round-off elsewhere, which the Jacobian does not see where v = 0 (there
  // d_a = 1 - a/|a| = 0 for every a > 0). Checked: the complementarity derivatives must give
  // the stored choice and elimination of every node bitwise.
  for (const auto i : s.locally_owned_dofs)
  {
    a_owned[i] = (s.locally_relevant_solution[i] - s.cavitation.pressure) / s.pressure_scale;
    v_owned[i] = s.locally_relevant_void[i];
  }
  a_owned.compress(VectorOperation::insert);
  v_owned.compress(VectorOperation::insert);
  a = a_owned;
  v = v_owned;
  const VectorType keep = s.jfo_keep_pressure, elimination = s.jfo_elimination;
  if (by_columns)
  {
    if (!prepare_global_matrices())
      return {};
    assemble(a, v, false); // the residual by products: its index maps serve jacobian_by_columns
    if (!jacobian_by_columns(a, v))
      return {};
  }
  else
    assemble(a, v, true);
  store_solution();
  for (const auto i : s.locally_owned_dofs)
    if (s.jfo_keep_pressure[i] != keep[i] || s.jfo_elimination[i] != elimination[i])
      return {};
  std::vector<double> values;
  for_each_row(s.system_matrix.trilinos_matrix(),
               [&](int, const int entries, const double *row_values, const int *, std::size_t)
               { values.insert(values.end(), row_values, row_values + entries); });
  return values;
}

void JFOSolver::store_solution()
{
  // The last assembly built the Jacobian at the solution: linearized_loads solves with it (it is
  // factorised at its first solve, so a run without linearised loads, and every mesh-sequencing
  // level, never pays for it; on a mesh-sequencing level, which may end on a band round, it is
  // what that round assembled and is never solved with). Keep which unknown each node kept with its
  // complementarity derivatives.
  s.factorize(false, true, true);
  s.jfo_keep_pressure.reinit(s.locally_owned_dofs, s.mpi_communicator);
  s.jfo_elimination.reinit(s.locally_owned_dofs, s.mpi_communicator);
  const double *pa = owned_values(a_owned), *pv = owned_values(v_owned);
  double *keep = owned_values(s.jfo_keep_pressure), *elimination = owned_values(s.jfo_elimination);
  for (std::size_t k = 0; k < s.locally_owned_dofs.n_elements(); ++k)
  {
    const FischerBurmeister fb(pa[k], pv[k]);
    keep[k] = fb.keeps_pressure() ? 1.0 : 0.0;
    elimination[k] = fb.keeps_pressure() ? -fb.d_a / fb.d_b : -fb.d_b / fb.d_a;
  }
  s.jfo_keep_pressure.compress(VectorOperation::insert);
  s.jfo_elimination.compress(VectorOperation::insert);

  VectorType p(s.locally_owned_dofs, s.mpi_communicator);
  double *pp = owned_values(p);
  for (std::size_t k = 0; k < s.locally_owned_dofs.n_elements(); ++k)
    pp[k] = s.cavitation.pressure + s.pressure_scale * pa[k];
  p.compress(VectorOperation::insert);
  s.locally_relevant_solution = p;
  s.locally_relevant_void = v_owned;
}

} // namespace sealfe
