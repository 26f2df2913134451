#include <sealfe/film/polar_node_grid.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cmath>
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
  // the radial rows: as many as nodes on the ray theta = 0 (the angle of the mesh's column 0)
  std::size_t rows = 0;
  for (const Point<2> &x : support)
    rows += x[0] > 0 && std::abs(x[1]) <= 1e-12 * x[0];
  if (rows < 2 || n % rows != 0)
    return false;
  const std::size_t columns = n / rows;
  if (columns % degree != 0 || columns < 2 * degree)
    return false;
  std::vector<double> radius(n), angle(n);
  for (std::size_t q = 0; q < n; ++q)
  {
    radius[q] = support[q].norm();
    // in [0, 2 pi), an angle within round-off below 2 pi counted as 0 (the ray's nodes)
    const double t = std::atan2(support[q][1], support[q][0]);
    angle[q] = t < -1e-12 ? t + 2 * M_PI : std::max(t, 0.0);
  }
  std::vector<unsigned int> by_radius(n);
  std::iota(by_radius.begin(), by_radius.end(), 0u);
  std::sort(by_radius.begin(), by_radius.end(),
            [&](unsigned int a, unsigned int b) { return radius[a] < radius[b]; });
  position_of_dof.assign(n, 0);
  for (std::size_t i = 0; i < rows; ++i)
  {
    const auto first = by_radius.begin() + i * columns, last = first + columns;
    // a row is a circle: its radii spread far less than the gap to the next row
    const double spread = radius[*(last - 1)] - radius[*first];
    if (i + 1 < rows && !(radius[*last] - radius[*(last - 1)] > 10 * spread))
      return false;
    std::sort(first, last, [&](unsigned int a, unsigned int b) { return angle[a] < angle[b]; });
    for (std::size_t j = 0; j < columns; ++j)
      position_of_dof[first[j]] = i * columns + j;
  }
  grid = numerics::NodeGrid{static_cast<unsigned int>(rows), static_cast<unsigned int>(columns),
                            degree, true};
  return true;
}

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
  // every entry within one cell of the grid (rows and columns are dofs on one rank)
  for (int i = 0; i < A.NumMyRows(); ++i)
  {
    int entries;
    int *columns;
    if (A.Graph().ExtractMyRowView(i, entries, columns) != 0)
      return {};
    const auto row = static_cast<std::size_t>(A.RowMap().GID64(i));
    for (int k = 0; k < entries; ++k)
    {
      const auto column = static_cast<std::size_t>(A.ColMap().GID64(columns[k]));
      if (row >= position.size() || column >= position.size() ||
          !numerics::within_one_cell(grid, position[row], position[column]))
        return {};
    }
  }
  const std::vector<unsigned int> order = numerics::nested_dissection_order(grid);
  std::vector<unsigned int> dof_at(position.size());
  for (std::size_t dof = 0; dof < position.size(); ++dof)
    dof_at[position[dof]] = dof;
  std::vector<int> position_of_row(position.size());
  for (std::size_t p = 0; p < order.size(); ++p)
    position_of_row[dof_at[order[p]]] = static_cast<int>(p + 1);
  return position_of_row;
}
} // namespace sealfe
