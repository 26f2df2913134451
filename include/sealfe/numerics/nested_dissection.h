// Nested dissection of a structured grid of nodes: an elimination order for the sparse direct
// factorisations of finite-element matrices on a tensor-product mesh (the built-in annulus).
#pragma once

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

namespace sealfe::numerics
{
/// The nodes of a tensor-product mesh of cells of degree `stride`: `rows` x `columns` nodes,
/// node (i, j) at position i * columns + j. Cell boundaries are the rows and columns that are
/// multiples of `stride`, so two nodes of one cell have i within one interval [m s, (m + 1) s]
/// and j within one such interval. `periodic_columns`: the columns close into a ring (the
/// annulus's angle), the last interval being [columns - s, columns] with column `columns` = 0.
struct NodeGrid
{
  unsigned int rows = 0, columns = 0, stride = 1;
  bool periodic_columns = false;
};

/// The grid's positions in a nested-dissection elimination order (George 1973): a line of nodes
/// on a cell boundary across the longer side of a region separates it, the two halves come first
/// (each ordered the same way) and the line last; regions of at most `leaf_nodes` nodes, or that
/// no cell boundary splits, in row order. A ring is first cut at column 0. On an n x n grid of
/// a 9-point stencil the factor has O(n^2 log n) entries and costs O(n^3) operations, against
/// O(n^3) and O(n^4) for a band order (tests/validation/nested_dissection.cc); on the annulus's
/// Jacobians it needs 13-40 % fewer operations than MUMPS's AMD (doc/performance.md, Session
/// 38).
std::vector<unsigned int> nested_dissection_order(const NodeGrid &grid,
                                                  unsigned int leaf_nodes = 16);

/// Whether the positions a and b can belong to one cell (both coordinates within one interval
/// between cell boundaries): what every entry of the matrix must satisfy for the separators of
/// nested_dissection_order to separate.
bool within_one_cell(const NodeGrid &grid, unsigned int a, unsigned int b);

/// within_one_cell of the nodes (row_a, column_a) and (row_b, column_b): for callers that hold
/// the coordinates (polar_nested_dissection checks every entry of a matrix with it), inline.
inline bool within_one_cell(const NodeGrid &grid, const long row_a, const long column_a,
                            const long row_b, const long column_b)
{
  // no cell boundary strictly between the two coordinates, and at most one cell apart
  const long stride = grid.stride, columns = grid.columns;
  auto one_interval = [stride](long lo, long hi)
  {
    if (lo > hi)
      std::swap(lo, hi);
    return hi - lo <= stride && (lo / stride + 1) * stride >= hi;
  };
  if (!one_interval(row_a, row_b))
    return false;
  if (grid.periodic_columns && std::abs(column_a - column_b) > columns / 2)
    // across column 0 of the ring: the smaller one a turn further
    return one_interval(std::max(column_a, column_b), std::min(column_a, column_b) + columns);
  return one_interval(column_a, column_b);
}
} // namespace sealfe::numerics
