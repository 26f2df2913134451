#include <sealfe/film/cell_sparsity.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_accessor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/exceptions.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Util.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace sealfe
{
using namespace dealii;

namespace
{
/// The first dof of each rank's range and, last, the number of dofs: rank r owns
/// first[r] .. first[r + 1] - 1 where the ranks own consecutive ranges in rank order.
std::vector<types::global_dof_index> rank_ranges(const IndexSet &owned, MPI_Comm comm)
{
  const std::vector<types::global_dof_index> counts =
      Utilities::MPI::all_gather(comm, owned.n_elements());
  std::vector<types::global_dof_index> first(counts.size() + 1, 0);
  std::partial_sum(counts.begin(), counts.end(), first.begin() + 1);
  return first;
}

/// The rows of a matrix assembled over cells, one after the other: for each dof t < n_dofs
/// (`cell_dofs` numbered in 0 .. n_dofs - 1, `m` per cell), the unconstrained dofs of the cells
/// around t, each once, in the order the cells meet them, or t alone where t is constrained;
/// `take_row(t, row)` receives each. Shared by the one-rank and several-rank patterns.
template <class TakeRow>
void for_each_row_of_cells(const std::vector<unsigned int> &cell_dofs, const unsigned int n_dofs,
                           const unsigned int m, const std::vector<char> &constrained,
                           TakeRow &&take_row)
{
  const std::size_t n_cells = cell_dofs.size() / m;
  // the cells around each dof (compressed rows)
  std::vector<unsigned int> first_cell(n_dofs + 1, 0);
  for (const unsigned int t : cell_dofs)
    ++first_cell[t + 1];
  std::partial_sum(first_cell.begin(), first_cell.end(), first_cell.begin());
  std::vector<unsigned int> around(cell_dofs.size()),
      next(first_cell.begin(), first_cell.end() - 1);
  for (std::size_t c = 0; c < n_cells; ++c)
    for (unsigned int k = 0; k < m; ++k)
      around[next[cell_dofs[c * m + k]]++] = c;
  std::vector<unsigned int> row, mark(n_dofs, numbers::invalid_unsigned_int);
  for (unsigned int t = 0; t < n_dofs; ++t)
  {
    row.clear();
    if (constrained[t])
      row.push_back(t);
    else
      for (unsigned int p = first_cell[t]; p < first_cell[t + 1]; ++p)
      {
        const unsigned int *dofs = &cell_dofs[std::size_t(around[p]) * m];
        for (unsigned int k = 0; k < m; ++k)
          if (!constrained[dofs[k]] && mark[dofs[k]] != t)
          {
            mark[dofs[k]] = t;
            row.push_back(dofs[k]);
          }
      }
    take_row(t, row);
  }
}

/// CellSparsity::reinit on several ranks. Each rank makes the rows of the dofs of its own cells
/// (owned dofs and ghosts), sends the ghosts' rows to their owners and merges the rows it
/// receives: the rows DoFTools' (MGTools') pattern gets from SparsityTools::
/// distribute_sparsity_pattern. The column map is the one Epetra makes for deal.II's matrix
/// (FillComplete without a column map): the owned dofs in order, then the other columns in the
/// order the rows meet them, grouped by owner; so every row is stored in the same order as
/// deal.II's and a matrix-vector product sums in the same order.
void reinit_distributed(TrilinosWrappers::SparseMatrix &matrix, const IndexSet &owned,
                        const std::vector<unsigned int> &cell_dofs, const unsigned int m,
                        const AffineConstraints<double> &constraints,
                        const bool keep_constrained_dofs, MPI_Comm comm)
{
  const std::vector<types::global_dof_index> first = rank_ranges(owned, comm);
  const unsigned int n_ranks = first.size() - 1, rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned int begin = first[rank], end = first[rank + 1], n_owned = end - begin;
  const auto is_owned = [&](const types::global_dof_index d) { return d >= begin && d < end; };
  const auto owner = [&](const unsigned int d)
  { return unsigned(std::upper_bound(first.begin(), first.end(), d) - first.begin()) - 1; };

  // the dofs by local (touched) index: an owned dof d at d - begin, the others (ghosts) after
  // them in increasing number
  std::vector<unsigned int> ghosts;
  for (const unsigned int d : cell_dofs)
  {
    AssertThrow(d < owned.size(), ExcMessage("CellSparsity: a cell's dof is not a dof"));
    if (!is_owned(d))
      ghosts.push_back(d);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  const unsigned int n_touched = n_owned + ghosts.size();
  const auto ghost_index = [&](const unsigned int d) {
    return n_owned + unsigned(std::lower_bound(ghosts.begin(), ghosts.end(), d) - ghosts.begin());
  };
  std::vector<unsigned int> touched(cell_dofs.size());
  for (std::size_t k = 0; k < cell_dofs.size(); ++k)
    touched[k] = is_owned(cell_dofs[k]) ? cell_dofs[k] - begin : ghost_index(cell_dofs[k]);
  std::vector<char> constrained(n_touched, 0);
  if (!keep_constrained_dofs)
    for (const auto &line : constraints.get_lines())
    {
      if (is_owned(line.index))
        constrained[line.index - begin] = 1;
      else if (std::binary_search(ghosts.begin(), ghosts.end(), line.index))
        constrained[ghost_index(line.index)] = 1;
    }

  // row t: an owned row kept by local index, a ghost's row packed for its owner as
  // (dof, length, dofs...)
  std::vector<int> length(n_owned);
  std::vector<unsigned int> columns;
  columns.reserve(std::size_t(n_owned) * 2 * m);
  std::vector<std::vector<unsigned int>> send(n_ranks);
  for_each_row_of_cells(touched, n_touched, m, constrained,
                        [&](const unsigned int t, const std::vector<unsigned int> &row)
                        {
                          if (t < n_owned)
                          {
                            length[t] = int(row.size());
                            columns.insert(columns.end(), row.begin(), row.end());
                            return;
                          }
                          const unsigned int dof = ghosts[t - n_owned];
                          auto &buffer = send[owner(dof)];
                          buffer.push_back(dof);
                          buffer.push_back(row.size());
                          for (const unsigned int c : row)
                            buffer.push_back(c < n_owned ? begin + c : ghosts[c - n_owned]);
                        });

  // the ghosts' rows to their owners
  std::vector<int> send_counts(n_ranks), receive_counts(n_ranks), send_offsets(n_ranks + 1, 0),
      receive_offsets(n_ranks + 1, 0);
  for (unsigned int r = 0; r < n_ranks; ++r)
  {
    send_counts[r] = int(send[r].size());
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
  }
  int ierr = MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
  AssertThrowMPI(ierr);
  for (unsigned int r = 0; r < n_ranks; ++r)
    receive_offsets[r + 1] = receive_offsets[r] + receive_counts[r];
  std::vector<unsigned int> sent(send_offsets.back()), received(receive_offsets.back());
  for (unsigned int r = 0; r < n_ranks; ++r)
    std::copy(send[r].begin(), send[r].end(), sent.begin() + send_offsets[r]);
  ierr = MPI_Alltoallv(sent.data(), send_counts.data(), send_offsets.data(), MPI_UNSIGNED,
                       received.data(), receive_counts.data(), receive_offsets.data(), MPI_UNSIGNED,
                       comm);
  AssertThrowMPI(ierr);
  // (owned row, column number) of the received rows
  std::vector<std::pair<unsigned int, unsigned int>> extra;
  for (std::size_t p = 0; p < received.size();)
  {
    const unsigned int dof = received[p], n = received[p + 1];
    AssertThrow(is_owned(dof),
                ExcMessage("CellSparsity: a row sent to a rank that does not own it"));
    for (unsigned int k = 0; k < n; ++k)
      extra.emplace_back(dof - begin, received[p + 2 + k]);
    p += 2 + n;
  }
  std::sort(extra.begin(), extra.end());

  // each owned row by dof number, sorted: the rows deal.II's graph receives (the dynamic
  // pattern's rows, by increasing number, through InsertGlobalIndices)
  std::vector<unsigned int> global_columns;
  global_columns.reserve(columns.size() + extra.size());
  std::size_t offset = 0, q = 0;
  for (unsigned int i = 0; i < n_owned; ++i)
  {
    const std::size_t start = global_columns.size();
    for (int k = 0; k < length[i]; ++k)
    {
      const unsigned int c = columns[offset + k];
      global_columns.push_back(c < n_owned ? begin + c : ghosts[c - n_owned]);
    }
    offset += length[i];
    for (; q < extra.size() && extra[q].first == i; ++q)
      global_columns.push_back(extra[q].second);
    std::sort(global_columns.begin() + start, global_columns.end());
    global_columns.erase(std::unique(global_columns.begin() + start, global_columns.end()),
                         global_columns.end());
    length[i] = int(global_columns.size() - start);
  }

  // the column map Epetra makes for deal.II's graph (Epetra_CrsGraph::MakeColMap, Trilinos
  // 13.2): the owned dofs in order (each is in its own row), then the others in the order the
  // rows meet them, sorted by owner with Epetra's own (shell) sort, which is not stable, so
  // called here on the same lists
  std::vector<unsigned int> others;
  for (const unsigned int c : global_columns)
    if (!is_owned(c))
      others.push_back(c);
  std::sort(others.begin(), others.end());
  others.erase(std::unique(others.begin(), others.end()), others.end());
  const auto other_index = [&](const unsigned int d)
  { return std::size_t(std::lower_bound(others.begin(), others.end(), d) - others.begin()); };
  std::vector<int> met(others.size(), -1), remote_dofs, remote_owners;
  std::vector<char> owned_met(n_owned, 0);
  for (const unsigned int c : global_columns)
    if (is_owned(c))
      owned_met[c - begin] = 1;
    else if (int &order = met[other_index(c)]; order < 0)
    {
      order = int(remote_dofs.size());
      remote_dofs.push_back(int(c));
      remote_owners.push_back(int(owner(c)));
    }
  AssertThrow(std::find(owned_met.begin(), owned_met.end(), 0) == owned_met.end(),
              ExcMessage("CellSparsity: an owned dof without its column"));
  if (!remote_dofs.empty())
  {
    int *companions[1] = {remote_dofs.data()};
    Epetra_Util::Sort(true, int(remote_dofs.size()), remote_owners.data(), 0, nullptr, 1,
                      companions);
  }
  std::vector<int> column_dofs(n_owned);
  std::iota(column_dofs.begin(), column_dofs.end(), int(begin));
  column_dofs.insert(column_dofs.end(), remote_dofs.begin(), remote_dofs.end());
  std::vector<int> other_column(others.size());
  for (std::size_t r = 0; r < remote_dofs.size(); ++r)
    other_column[other_index(remote_dofs[r])] = int(n_owned + r);

  // the rows by local column index, sorted (as Epetra stores them): the owned columns keep
  // their order, a row with others is sorted again
  std::vector<int> local_columns(global_columns.size());
  offset = 0;
  for (unsigned int i = 0; i < n_owned; ++i)
  {
    bool with_others = false;
    for (int k = 0; k < length[i]; ++k)
    {
      const unsigned int c = global_columns[offset + k];
      with_others = with_others || !is_owned(c);
      local_columns[offset + k] = is_owned(c) ? int(c - begin) : other_column[other_index(c)];
    }
    if (with_others)
      std::sort(local_columns.begin() + offset, local_columns.begin() + offset + length[i]);
    offset += length[i];
  }

  const Epetra_Map row_map = owned.make_trilinos_map(comm, false);
  const Epetra_Map column_map(-1, int(column_dofs.size()), column_dofs.data(), 0, row_map.Comm());
  Epetra_CrsGraph graph(Copy, row_map, column_map, length.data(), true);
  offset = 0;
  for (unsigned int i = 0; i < n_owned; ++i)
  {
    if (length[i] > 0)
    {
      ierr = graph.InsertMyIndices(int(i), length[i], &local_columns[offset]);
      AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    }
    offset += length[i];
  }
  ierr = graph.FillComplete(row_map, row_map);
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  ierr = graph.OptimizeStorage();
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  const Epetra_CrsMatrix pattern(View, graph);
  matrix.reinit(pattern, false);
}
} // namespace

bool CellSparsity::applies(const IndexSet &owned, const AffineConstraints<double> &constraints,
                           MPI_Comm comm)
{
  bool fits = owned.size() <= types::global_dof_index(std::numeric_limits<int>::max());
  for (const auto &line : constraints.get_lines())
    if (!line.entries.empty()) // e.g. a hanging node: it couples other dofs
      fits = false;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  if (n_ranks == 1)
    return fits && owned.n_elements() == owned.size();
  // several ranks: each owns one range, the ranges one after the other in rank order and
  // together every dof (deal.II's numbering on a distributed mesh), so that a dof's owner
  // follows from the ranges; every rank must take the same path (the set-up is collective)
  const std::vector<types::global_dof_index> first = rank_ranges(owned, comm);
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  IndexSet range(owned.size());
  range.add_range(first[rank], first[rank + 1]);
  fits = fits && first.back() == owned.size() && owned == range;
  return Utilities::MPI::min(fits ? 1 : 0, comm) == 1;
}

void CellSparsity::reinit(TrilinosWrappers::SparseMatrix &matrix, const IndexSet &owned,
                          const std::vector<unsigned int> &cell_dofs,
                          const unsigned int dofs_per_cell,
                          const AffineConstraints<double> &constraints,
                          const bool keep_constrained_dofs, MPI_Comm comm)
{
  AssertThrow(applies(owned, constraints, comm),
              ExcMessage("CellSparsity: Dirichlet constraints and one owned range per rank only"));
  if (Utilities::MPI::n_mpi_processes(comm) > 1)
  {
    reinit_distributed(matrix, owned, cell_dofs, dofs_per_cell, constraints, keep_constrained_dofs,
                       comm);
    return;
  }
  const unsigned int n = owned.n_elements(), m = dofs_per_cell;
  for (const unsigned int d : cell_dofs)
    AssertThrow(d < n, ExcMessage("CellSparsity: a cell's dof is not an owned one"));
  std::vector<char> constrained(n, 0);
  if (!keep_constrained_dofs)
    for (const auto &line : constraints.get_lines())
      if (line.index < n)
        constrained[line.index] = 1;
  // row i: the (unconstrained) dofs of the cells around i, each once, sorted
  std::vector<int> length(n), columns;
  columns.reserve(std::size_t(n) * 2 * m);
  for_each_row_of_cells(cell_dofs, n, m, constrained,
                        [&](const unsigned int i, std::vector<unsigned int> &row)
                        {
                          std::sort(row.begin(), row.end());
                          length[i] = int(row.size());
                          columns.insert(columns.end(), row.begin(), row.end());
                        });
  // the graph by local index (column map = row map: local index = dof number), then the matrix
  const Epetra_Map map = owned.make_trilinos_map(comm, false);
  Epetra_CrsGraph graph(Copy, map, map, length.data(), true);
  std::size_t offset = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    if (length[i] > 0)
    {
      const int ierr = graph.InsertMyIndices(int(i), length[i], &columns[offset]);
      AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    }
    offset += length[i];
  }
  int ierr = graph.FillComplete(map, map);
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  ierr = graph.OptimizeStorage();
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  // the matrix only passes the graph and maps: in View mode it allocates no values (the
  // deal.II matrix allocates its own, zeroed, from the graph)
  const Epetra_CrsMatrix pattern(View, graph);
  matrix.reinit(pattern, false);
}

std::vector<unsigned int> CellSparsity::active_cell_dofs(const DoFHandler<2> &dof_handler)
{
  const unsigned int n = dof_handler.get_fe().n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  std::vector<unsigned int> cell_dofs;
  cell_dofs.reserve(std::size_t(dof_handler.get_triangulation().n_active_cells()) * n);
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell->get_dof_indices(dofs);
      cell_dofs.insert(cell_dofs.end(), dofs.begin(), dofs.end());
    }
  return cell_dofs;
}

std::vector<unsigned int> CellSparsity::level_cell_dofs(const DoFHandler<2> &dof_handler,
                                                        const unsigned int level)
{
  const unsigned int n = dof_handler.get_fe().n_dofs_per_cell();
  std::vector<types::global_dof_index> dofs(n);
  std::vector<unsigned int> cell_dofs;
  cell_dofs.reserve(std::size_t(dof_handler.get_triangulation().n_cells(level)) * n);
  // the cells MGTools::make_sparsity_pattern takes: this rank's (every cell on a serial mesh)
  const types::subdomain_id own = dof_handler.get_triangulation().locally_owned_subdomain();
  for (const auto &cell : dof_handler.mg_cell_iterators_on_level(level))
    if (own == numbers::invalid_subdomain_id || cell->level_subdomain_id() == own)
    {
      cell->get_mg_dof_indices(dofs);
      cell_dofs.insert(cell_dofs.end(), dofs.begin(), dofs.end());
    }
  return cell_dofs;
}

bool CellSparsity::unconstrained(const AffineConstraints<double> &constraints,
                                 const std::vector<types::global_dof_index> &dofs)
{
  for (const auto d : dofs)
    if (constraints.is_constrained(d))
      return false;
  return true;
}

void CellSparsity::add(TrilinosWrappers::SparseMatrix &matrix,
                       const FullMatrix<double> &cell_matrix,
                       const std::vector<types::global_dof_index> &dofs)
{
  // deal.II gives the Epetra matrix only as const; its row views point into the values, which
  // this writes (hence the non-const `matrix`)
  const Epetra_CrsMatrix &E = matrix.trilinos_matrix();
  constexpr unsigned int max_dofs = 64;
  const unsigned int m = dofs.size();
  AssertThrow(m <= max_dofs, ExcMessage("CellSparsity: more than 64 dofs per cell"));
  // the local column of each dof: an owned dof's is its place in the owned range (one rank:
  // the dof number), another's from the column map
  const types::global_dof_index begin = E.RowMap().MinMyGID();
  const unsigned int n_owned = E.NumMyRows();
  const auto owned = [&](const types::global_dof_index d)
  { return d >= begin && d - begin < n_owned; };
  // a cell without owned dofs (several ranks): every row another rank's, and its dofs need
  // not be columns here
  if (std::none_of(dofs.begin(), dofs.end(), owned))
  {
    for (unsigned int i = 0; i < m; ++i)
      matrix.add(dofs[i], m, dofs.data(), &cell_matrix(i, 0), true, false);
    return;
  }
  int column[max_dofs];
  for (unsigned int k = 0; k < m; ++k)
  {
    column[k] = owned(dofs[k]) ? int(dofs[k] - begin) : E.ColMap().LID(int(dofs[k]));
    AssertThrow(column[k] >= 0,
                ExcMessage("CellSparsity: a cell entry outside the matrix pattern"));
  }
  // the cell's dofs in increasing column order: one merge along each (sorted) row
  unsigned int order[max_dofs];
  std::iota(order, order + m, 0u);
  std::sort(order, order + m,
            [&](unsigned int a, unsigned int b) { return column[a] < column[b]; });
  for (unsigned int i = 0; i < m; ++i)
  {
    if (!owned(dofs[i]))
    {
      // another rank's row: kept by the Epetra matrix until compress(), as for
      // distribute_local_to_global (which leaves out the zeros)
      matrix.add(dofs[i], m, dofs.data(), &cell_matrix(i, 0), true, false);
      continue;
    }
    int length;
    double *values;
    int *columns;
    const int ierr = E.ExtractMyRowView(int(dofs[i] - begin), length, values, columns);
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    int p = 0;
    for (unsigned int k = 0; k < m; ++k)
    {
      const unsigned int j = order[k];
      while (p < length && columns[p] < column[j])
        ++p;
      AssertThrow(p < length && columns[p] == column[j],
                  ExcMessage("CellSparsity: a cell entry outside the matrix pattern"));
      values[p] += cell_matrix(i, j);
    }
  }
}

void CellSparsity::add(TrilinosWrappers::MPI::Vector &vector, const Vector<double> &cell_vector,
                       const std::vector<types::global_dof_index> &dofs)
{
  const Epetra_MultiVector &V = vector.trilinos_vector();
  const types::global_dof_index begin = V.Map().MinMyGID();
  const unsigned int n_owned = V.MyLength();
  double *const owned_values = vector.begin();
  for (unsigned int i = 0; i < dofs.size(); ++i)
    if (dofs[i] >= begin && dofs[i] - begin < n_owned)
      owned_values[dofs[i] - begin] += cell_vector(i);
    else if (const double value = cell_vector(i); value != 0)
      vector.add(1, &dofs[i], &value); // kept until compress(); zeros left out, as by deal.II
}

void CellSparsity::distribute(const AffineConstraints<double> &constraints, const bool by_position,
                              const FullMatrix<double> &cell_matrix,
                              const Vector<double> &cell_vector,
                              const std::vector<types::global_dof_index> &dofs,
                              TrilinosWrappers::SparseMatrix &matrix,
                              TrilinosWrappers::MPI::Vector &vector)
{
  if (by_position && unconstrained(constraints, dofs))
  {
    add(matrix, cell_matrix, dofs);
    add(vector, cell_vector, dofs);
  }
  else
    constraints.distribute_local_to_global(cell_matrix, cell_vector, dofs, matrix, vector);
}

void CellSparsity::distribute(const AffineConstraints<double> &constraints, const bool by_position,
                              const FullMatrix<double> &cell_matrix,
                              const std::vector<types::global_dof_index> &dofs,
                              TrilinosWrappers::SparseMatrix &matrix)
{
  if (by_position && unconstrained(constraints, dofs))
    add(matrix, cell_matrix, dofs);
  else
    constraints.distribute_local_to_global(cell_matrix, dofs, matrix);
}

void CellSparsity::distribute(const AffineConstraints<double> &constraints, const bool by_position,
                              const Vector<double> &cell_vector,
                              const std::vector<types::global_dof_index> &dofs,
                              TrilinosWrappers::MPI::Vector &vector)
{
  if (by_position && unconstrained(constraints, dofs))
    add(vector, cell_vector, dofs);
  else
    constraints.distribute_local_to_global(cell_vector, dofs, vector);
}

} // namespace sealfe
