#include <sealfe/numerics/nested_dissection.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace sealfe::numerics
{
namespace
{
/// A cell boundary (multiple of `stride`) strictly inside [first + 1, last - 2] nearest to the
/// middle of [first, last), so that both sides keep nodes; -1 where there is none.
long boundary_near_middle(const long first, const long last, const long stride)
{
  const long middle = first + (last - first) / 2, near = middle / stride * stride;
  long best = -1;
  for (long c = near - stride; c <= near + stride; c += stride)
    if (c >= first + 1 && c <= last - 2 &&
        (best < 0 || std::abs(c - middle) < std::abs(best - middle)))
      best = c;
  return best;
}

struct Dissection
{
  const NodeGrid &grid;
  unsigned int leaf_nodes;
  std::vector<unsigned int> &order;

  void add_row_range(const unsigned int i, const unsigned int j0, const unsigned int j1)
  {
    for (unsigned int j = j0; j < j1; ++j)
      order.push_back(i * grid.columns + j);
  }

  /// Orders the nodes [i0, i1) x [j0, j1).
  void region(const unsigned int i0, const unsigned int i1, const unsigned int j0,
              const unsigned int j1)
  {
    if (i0 >= i1 || j0 >= j1)
      return;
    const long rows = i1 - i0, columns = j1 - j0;
    if (rows * columns > long(leaf_nodes))
    {
      // across the longer side first; the other where the longer has no cell boundary inside
      for (const bool cut_columns : {columns >= rows, columns < rows})
      {
        const long c = cut_columns ? boundary_near_middle(j0, j1, grid.stride)
                                   : boundary_near_middle(i0, i1, grid.stride);
        if (c < 0)
          continue;
        if (cut_columns)
        {
          region(i0, i1, j0, c);
          region(i0, i1, c + 1, j1);
          for (unsigned int i = i0; i < i1; ++i)
            order.push_back(i * grid.columns + c);
        }
        else
        {
          region(i0, c, j0, j1);
          region(c + 1, i1, j0, j1);
          add_row_range(c, j0, j1);
        }
        return;
      }
    }
    for (unsigned int i = i0; i < i1; ++i)
      add_row_range(i, j0, j1);
  }
};
} // namespace

std::vector<unsigned int> nested_dissection_order(const NodeGrid &grid,
                                                  const unsigned int leaf_nodes)
{
  if (grid.stride == 0 || (grid.periodic_columns && grid.columns % grid.stride != 0))
    throw std::invalid_argument("nested_dissection_order: the columns of a ring are not whole "
                                "cells");
  std::vector<unsigned int> order;
  order.reserve(std::size_t(grid.rows) * grid.columns);
  Dissection dissection{grid, leaf_nodes, order};
  if (grid.periodic_columns)
  {
    // column 0 closes the ring: the rest is a strip whose both ends touch it
    dissection.region(0, grid.rows, 1, grid.columns);
    for (unsigned int i = 0; i < grid.rows; ++i)
      order.push_back(i * grid.columns);
  }
  else
    dissection.region(0, grid.rows, 0, grid.columns);
  return order;
}

bool within_one_cell(const NodeGrid &grid, const unsigned int a, const unsigned int b)
{
  return within_one_cell(grid, a / grid.columns, a % grid.columns, b / grid.columns,
                         b % grid.columns);
}
} // namespace sealfe::numerics
