#include <sealfe/film/level_transfer.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/exceptions.h>
#include <deal.II/lac/full_matrix.h>

#include <algorithm>
#include <limits>

namespace sealfe
{
using namespace dealii;

bool LevelTransfer::build(const DoFHandler<2> &dof_handler,
                          const MGConstrainedDoFs &constrained_dofs, const bool fine_active,
                          const MPI_Comm comm)
{
  const auto &tria = dof_handler.get_triangulation();
  const auto &fe = dof_handler.get_fe();
  const unsigned int n_levels = tria.n_global_levels(), n = fe.n_dofs_per_cell();
  std::vector<types::global_dof_index> parent(n), child(n);
  std::vector<bool> boundary(n);
  prolongation.clear();
  prolongation.resize(n_levels);
  maps.clear();
  // The Epetra matrices take int global indices (the int() casts below): every level must
  // number its dofs below 2^31 (as the Trilinos wrappers of deal.II's 32-bit indices do).
  for (unsigned int l = 0; l < n_levels; ++l)
    AssertThrow(dof_handler.n_dofs(l) <= types::global_dof_index(std::numeric_limits<int>::max()),
                ExcMessage("FilmMultigrid: level dofs beyond 32-bit Epetra indices"));
  const unsigned int fine = n_levels - 1;
  // the rows of level l: its own level dofs, or the active ones on the finest level
  auto owned_rows = [&](const unsigned int l) -> const IndexSet &
  {
    return fine_active && l == fine ? dof_handler.locally_owned_dofs()
                                    : dof_handler.locally_owned_mg_dofs(l);
  };
  for (unsigned int l = 0; l < n_levels; ++l)
    maps.push_back(std::make_unique<Epetra_Map>(owned_rows(l).make_trilinos_map(comm, true)));
  bool complete = true;
  for (unsigned int l = 1; l < n_levels; ++l)
  {
    const IndexSet &owned = owned_rows(l);
    const bool active_rows = fine_active && l == fine;
    const std::size_t n_rows = owned.n_elements();
    // (row, column, value) of each owned row, the row from the first child cell that has it
    std::vector<bool> done(n_rows, false);
    std::vector<unsigned int> row_of;
    std::vector<int> columns;
    std::vector<double> values;
    row_of.reserve(4 * n_rows);
    columns.reserve(4 * n_rows);
    values.reserve(4 * n_rows);
    for (const auto &cell : dof_handler.mg_cell_iterators_on_level(l - 1))
      if (cell->has_children() && cell->level_subdomain_id() != numbers::artificial_subdomain_id)
      {
        cell->get_mg_dof_indices(parent);
        for (unsigned int j = 0; j < n; ++j)
          boundary[j] = constrained_dofs.is_boundary_index(l - 1, parent[j]);
        for (unsigned int c = 0; c < cell->n_children(); ++c)
        {
          const auto child_cell = cell->child(c);
          if (child_cell->level_subdomain_id() == numbers::artificial_subdomain_id)
            continue;
          // active rows: a cell of the finest level that is not active, or whose active
          // dofs this rank does not know, is skipped (its rows stay missing: build() fails)
          if (active_rows && (!child_cell->is_active() || child_cell->is_artificial()))
            continue;
          const FullMatrix<double> &P =
              fe.get_prolongation_matrix(c, RefinementCase<2>::isotropic_refinement);
          if (active_rows)
            child_cell->get_dof_indices(child);
          else
            child_cell->get_mg_dof_indices(child);
          for (unsigned int i = 0; i < n; ++i)
          {
            if (!owned.is_element(child[i]))
              continue;
            const auto row = owned.index_within_set(child[i]);
            if (done[row])
              continue;
            done[row] = true;
            for (unsigned int j = 0; j < n; ++j)
              if (P(i, j) != 0 && !boundary[j])
              {
                row_of.push_back(row);
                columns.push_back(int(parent[j]));
                values.push_back(P(i, j));
              }
          }
        }
      }
    complete = complete && std::find(done.begin(), done.end(), false) == done.end();
    // rows in order (counting sort), then one InsertGlobalValues per row
    std::vector<int> count(n_rows, 0);
    for (const unsigned int r : row_of)
      ++count[r];
    std::vector<std::size_t> start(n_rows + 1, 0);
    for (std::size_t r = 0; r < n_rows; ++r)
      start[r + 1] = start[r] + count[r];
    std::vector<int> sorted_columns(columns.size());
    std::vector<double> sorted_values(values.size());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t e = 0; e < row_of.size(); ++e)
    {
      const std::size_t k = next[row_of[e]]++;
      sorted_columns[k] = columns[e];
      sorted_values[k] = values[e];
    }
    std::unique_ptr<Epetra_CrsMatrix> matrix;
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
    {
      // one rank: every column is an owned coarse dof, so the coarse map is the column map
      // and the entries go in by local index (no column map to build from global indices)
      const IndexSet &owned_coarse = dof_handler.locally_owned_mg_dofs(l - 1);
      for (int &c : sorted_columns)
        c = int(owned_coarse.index_within_set(c));
      matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *maps[l], *maps[l - 1], count.data(), true);
      for (std::size_t r = 0; r < n_rows; ++r)
        if (count[r] > 0)
        {
          const int ierr = matrix->InsertMyValues(int(r), count[r], &sorted_values[start[r]],
                                                  &sorted_columns[start[r]]);
          AssertThrow(ierr == 0, ExcTrilinosError(ierr));
        }
    }
    else
    {
      matrix = std::make_unique<Epetra_CrsMatrix>(Copy, *maps[l], count.data(), true);
      for (std::size_t r = 0; r < n_rows; ++r)
        if (count[r] > 0)
        {
          const int ierr =
              matrix->InsertGlobalValues(int(owned.nth_index_in_set(r)), count[r],
                                         &sorted_values[start[r]], &sorted_columns[start[r]]);
          AssertThrow(ierr == 0, ExcTrilinosError(ierr));
        }
    }
    const int ierr = matrix->FillComplete(*maps[l - 1], *maps[l]);
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    prolongation[l] = std::move(matrix);
  }
  return Utilities::MPI::min(complete ? 1 : 0, comm) == 1;
}

void LevelTransfer::prolongate_and_add(const unsigned int l, VectorType &dst, const VectorType &src)
{
  VectorType &t = work(l, dst);
  const int ierr = prolongation[l]->Multiply(false, src.trilinos_vector(), t.trilinos_vector());
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  dst += t;
}

void LevelTransfer::restrict_and_add(const unsigned int l, VectorType &dst, const VectorType &src)
{
  VectorType &t = work(l - 1, dst);
  const int ierr = prolongation[l]->Multiply(true, src.trilinos_vector(), t.trilinos_vector());
  AssertThrow(ierr == 0, ExcTrilinosError(ierr));
  dst += t;
}

LevelTransfer::VectorType &LevelTransfer::work(const unsigned int l, const VectorType &like)
{
  VectorType &t = scratch[l];
  if (t.size() != like.size())
    t.reinit(like, true);
  return t;
}

} // namespace sealfe
