#include <sealfe/film/polar_node_grid.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sealfe
{
using namespace dealii;

bool polar_node_grid(const std::vector<Point<2>> &support, const unsigned int degree,
                     numerics::NodeGrid &grid, std::vector<unsigned int> &position_of_dof)
{
  const std::size_t n = support.size();
  if (n == 0 || degree == 0)
    return false;
  // The rows: the radii of the nodes on the ray theta = 0 (the angle of the mesh's column 0),
  // one node per row there
  auto on_ray = [](const Point<2> &x) { return x[0] > 0 && std::abs(x[1]) <= 1e-12 * x[0]; };
  std::vector<double> row_radius;
  for (const Point<2> &x : support)
    if (on_ray(x))
      row_radius.push_back(x[0]);
  const std::size_t rows = row_radius.size();
  if (rows < 2 || n % rows != 0)
    return false;
  const std::size_t columns = n / rows;
  if (columns % degree != 0 || columns < 2 * degree)
    return false;
  std::sort(row_radius.begin(), row_radius.end());
  double gap = std::numeric_limits<double>::max();
  for (std::size_t i = 1; i < rows; ++i)
    gap = std::min(gap, row_radius[i] - row_radius[i - 1]);
  if (!(gap > 0))
    return false;
  // The columns: the angles in [0, 2 pi) of the nodes on the inner circle (equal angles for
  // degrees 1 and 2, the Gauss-Lobatto points of FE_Q inside each cell from degree 3 on)
  std::vector<double> radius(n), angle(n);
  std::vector<double> column_angle;
  for (std::size_t q = 0; q < n; ++q)
  {
    radius[q] = support[q].norm();
    // (a node on the ray theta = 0, as counted above, at 0: not within round-off below 2 pi)
    const double t = std::atan2(support[q][1], support[q][0]);
    angle[q] = on_ray(support[q]) ? 0.0 : (t < 0 ? t + 2 * M_PI : t);
    if (std::abs(radius[q] - row_radius[0]) <= 0.25 * gap)
      column_angle.push_back(angle[q]);
  }
  if (column_angle.size() != columns)
    return false;
  std::sort(column_angle.begin(), column_angle.end());
  // (the node on the ray at 0: the first column)
  double spacing = 2 * M_PI - column_angle.back() + column_angle.front();
  for (std::size_t j = 1; j < columns; ++j)
    spacing = std::min(spacing, column_angle[j] - column_angle[j - 1]);
  if (!(spacing > 0) || column_angle.front() > 0.25 * spacing)
    return false;
  // Every node within a quarter of the spacings of a row's radius and a column's angle (the
  // support points of a curved cell's mapping leave the circles by its O(h^(m+1)) error only),
  // each position taken once
  auto nearest = [](const std::vector<double> &values, const double x)
  {
    const auto above = std::lower_bound(values.begin(), values.end(), x);
    std::size_t k = above - values.begin();
    if (k == values.size() || (k > 0 && x - values[k - 1] < values[k] - x))
      --k;
    return k;
  };
  position_of_dof.assign(n, 0);
  std::vector<bool> taken(n, false);
  for (std::size_t q = 0; q < n; ++q)
  {
    const std::size_t i = nearest(row_radius, radius[q]);
    // an angle just below 2 pi is column 0's
    const double t = angle[q] > 2 * M_PI - 0.25 * spacing ? angle[q] - 2 * M_PI : angle[q];
    const std::size_t j = nearest(column_angle, t);
    if (std::abs(radius[q] - row_radius[i]) > 0.25 * gap ||
        std::abs(t - column_angle[j]) > 0.25 * spacing)
      return false;
    const std::size_t p = i * columns + j;
    if (taken[p])
      return false;
    taken[p] = true;
    position_of_dof[q] = p;
  }
  grid = numerics::NodeGrid{static_cast<unsigned int>(rows), static_cast<unsigned int>(columns),
                            degree, true};
  return true;
}

namespace
{
/// The elimination position (1-based) of every dof in the nested dissection of `grid`, whose
/// node `position[dof]` each dof is.
std::vector<int> positions_in_nested_dissection(const numerics::NodeGrid &grid,
                                                const std::vector<unsigned int> &position)
{
  const std::vector<unsigned int> order = numerics::nested_dissection_order(grid);
  std::vector<unsigned int> dof_at(position.size());
  for (std::size_t dof = 0; dof < position.size(); ++dof)
    dof_at[position[dof]] = dof;
  std::vector<int> position_of_row(position.size());
  for (std::size_t p = 0; p < order.size(); ++p)
    position_of_row[dof_at[order[p]]] = static_cast<int>(p + 1);
  return position_of_row;
}

/// The grid's row and column of every dof.
void rows_and_columns(const numerics::NodeGrid &grid, const std::vector<unsigned int> &position,
                      std::vector<unsigned int> &row_of, std::vector<unsigned int> &column_of)
{
  row_of.resize(position.size());
  column_of.resize(position.size());
  for (std::size_t dof = 0; dof < position.size(); ++dof)
  {
    row_of[dof] = position[dof] / grid.columns;
    column_of[dof] = position[dof] % grid.columns;
  }
}
} // namespace

std::vector<int> polar_nested_dissection(const std::vector<Point<2>> &support,
                                         const unsigned int degree,
                                         const TrilinosWrappers::SparseMatrix &matrix)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  numerics::NodeGrid grid;
  std::vector<unsigned int> position;
  if (A.Comm().NumProc() != 1 || static_cast<std::size_t>(A.NumMyRows()) != support.size() ||
      !polar_node_grid(support, degree, grid, position))
    return {};
  // Every entry within one cell of the grid (rows and columns are dofs on one rank), with the
  // rows' and columns' indices held apart (2.6e7 entries at 1.05e6 Q2 dofs)
  std::vector<unsigned int> row_of, column_of;
  rows_and_columns(grid, position, row_of, column_of);
  std::vector<long> column_gid(A.NumMyCols());
  for (int c = 0; c < A.NumMyCols(); ++c)
    column_gid[c] = A.ColMap().GID64(c);
  for (int i = 0; i < A.NumMyRows(); ++i)
  {
    int entries;
    int *local_columns;
    if (A.Graph().ExtractMyRowView(i, entries, local_columns) != 0)
      return {};
    const long row = A.RowMap().GID64(i);
    if (row < 0 || row >= long(position.size()))
      return {};
    const long ia = row_of[row], ja = column_of[row];
    for (int k = 0; k < entries; ++k)
    {
      const long column = column_gid[local_columns[k]];
      if (column < 0 || column >= long(position.size()))
        return {};
      if (!numerics::within_one_cell(grid, ia, ja, row_of[column], column_of[column]))
        return {};
    }
  }
  return positions_in_nested_dissection(grid, position);
}

std::vector<int> polar_nested_dissection(const std::vector<Point<2>> &support,
                                         const unsigned int degree,
                                         const std::vector<unsigned int> &cell_dofs,
                                         const unsigned int dofs_per_cell)
{
  numerics::NodeGrid grid;
  std::vector<unsigned int> position;
  if (dofs_per_cell == 0 || cell_dofs.size() % dofs_per_cell != 0 ||
      !polar_node_grid(support, degree, grid, position))
    return {};
  std::vector<unsigned int> row_of, column_of;
  rows_and_columns(grid, position, row_of, column_of);
  // every two dofs of a cell within one cell of the grid (2.1e7 pairs at 1.05e6 Q2 dofs)
  for (std::size_t first = 0; first < cell_dofs.size(); first += dofs_per_cell)
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
    {
      const unsigned int a = cell_dofs[first + i];
      if (a >= position.size())
        return {};
      for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
      {
        const unsigned int b = cell_dofs[first + j];
        if (b >= position.size() ||
            !numerics::within_one_cell(grid, row_of[a], column_of[a], row_of[b], column_of[b]))
          return {};
      }
    }
  return positions_in_nested_dissection(grid, position);
}
} // namespace sealfe
