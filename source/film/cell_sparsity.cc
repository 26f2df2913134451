#include <sealfe/film/cell_sparsity.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_accessor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/exceptions.h>

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace sealfe
{
using namespace dealii;

bool CellSparsity::applies(const IndexSet &owned, const AffineConstraints<double> &constraints,
                           MPI_Comm comm)
{
  if (Utilities::MPI::n_mpi_processes(comm) != 1 || owned.n_elements() != owned.size() ||
      owned.size() > types::global_dof_index(std::numeric_limits<int>::max()))
    return false;
  for (const auto &line : constraints.get_lines())
    if (!line.entries.empty()) // e.g. a hanging node: it couples other dofs
      return false;
  return true;
}

void CellSparsity::reinit(TrilinosWrappers::SparseMatrix &matrix, const IndexSet &owned,
                          const std::vector<unsigned int> &cell_dofs,
                          const unsigned int dofs_per_cell,
                          const AffineConstraints<double> &constraints,
                          const bool keep_constrained_dofs, MPI_Comm comm)
{
  AssertThrow(applies(owned, constraints, comm),
              ExcMessage("CellSparsity: one rank and Dirichlet constraints only"));
  const unsigned int n = owned.n_elements(), m = dofs_per_cell;
  const std::size_t n_cells = cell_dofs.size() / m;
  std::vector<char> constrained(n, 0);
  if (!keep_constrained_dofs)
    for (const auto &line : constraints.get_lines())
      if (line.index < n)
        constrained[line.index] = 1;
  // the cells around each dof (compressed rows)
  std::vector<unsigned int> first(n + 1, 0);
  for (const unsigned int d : cell_dofs)
  {
    AssertThrow(d < n, ExcMessage("CellSparsity: a cell's dof is not an owned one"));
    ++first[d + 1];
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<unsigned int> around(cell_dofs.size()), next(first.begin(), first.end() - 1);
  for (std::size_t c = 0; c < n_cells; ++c)
    for (unsigned int k = 0; k < m; ++k)
      around[next[cell_dofs[c * m + k]]++] = c;
  // row i: the (unconstrained) dofs of those cells, each once (marked by the row), sorted
  std::vector<int> length(n), columns, row;
  columns.reserve(std::size_t(n) * 2 * m);
  std::vector<unsigned int> mark(n, numbers::invalid_unsigned_int);
  for (unsigned int i = 0; i < n; ++i)
  {
    row.clear();
    if (constrained[i])
      row.push_back(int(i));
    else
      for (unsigned int p = first[i]; p < first[i + 1]; ++p)
      {
        const unsigned int *dofs = &cell_dofs[std::size_t(around[p]) * m];
        for (unsigned int k = 0; k < m; ++k)
          if (!constrained[dofs[k]] && mark[dofs[k]] != i)
          {
            mark[dofs[k]] = i;
            row.push_back(int(dofs[k]));
          }
      }
    std::sort(row.begin(), row.end());
    length[i] = int(row.size());
    columns.insert(columns.end(), row.begin(), row.end());
  }
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
  for (const auto &cell : dof_handler.mg_cell_iterators_on_level(level))
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
  // the cell's dofs in increasing order: one merge along each (sorted) row
  unsigned int order[max_dofs];
  std::iota(order, order + m, 0u);
  std::sort(order, order + m, [&](unsigned int a, unsigned int b) { return dofs[a] < dofs[b]; });
  for (unsigned int i = 0; i < m; ++i)
  {
    int length;
    double *values;
    int *columns;
    const int ierr = E.ExtractMyRowView(int(dofs[i]), length, values, columns);
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    int p = 0;
    for (unsigned int k = 0; k < m; ++k)
    {
      const unsigned int j = order[k];
      const int column = int(dofs[j]);
      while (p < length && columns[p] < column)
        ++p;
      AssertThrow(p < length && columns[p] == column,
                  ExcMessage("CellSparsity: a cell entry outside the matrix pattern"));
      values[p] += cell_matrix(i, j);
    }
  }
}

} // namespace sealfe
