// The dofs of the built-in annulus as the nodes of its polar grid (polar_node_grid.h): on the
// graded annulus (8 x 64 cells) of degree 1-3 every dof gets its own position on the
// (k N_r + 1) x k N_theta grid, at its row's radius and at its column's angle, the same in every
// row (the mapping of degree k on the polar manifold maps the cell's support points, equally
// spaced for k <= 2 and Gauss-Lobatto points from k = 3, along the circles); every entry of the
// finite-element matrix couples two nodes of one cell, so polar_nested_dissection gives a
// permutation, and the cells' dofs alone give the same one (the order made before the matrix).
// Points that are not such a grid are refused: a node turned by 0.3 of a column, a node moved
// 0.3 of the way to the next row; so is a matrix with an entry between two nodes that no cell
// holds, and a cell holding two such nodes.
#include "../graded_annulus.h"

#include <sealfe/film/cell_sparsity.h>
#include <sealfe/film/polar_node_grid.h>

#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
std::vector<Point<2>> support_points(const DoFHandler<2> &dof_handler, const Mapping<2> &mapping)
{
  const FiniteElement<2> &fe = dof_handler.get_fe();
  std::vector<Point<2>> support(dof_handler.n_dofs());
  FEValues<2> fe_values(mapping, fe, Quadrature<2>(fe.get_unit_support_points()),
                        update_quadrature_points);
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  for (const auto &cell : dof_handler.active_cell_iterators())
  {
    fe_values.reinit(cell);
    cell->get_dof_indices(dofs);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      support[dofs[i]] = fe_values.quadrature_point(i);
  }
  return support;
}
} // namespace

TEST(PolarNodeGrid, DofsOfTheAnnulusAreItsNodeGrid)
{
  for (const unsigned int degree : {1u, 2u, 3u})
  {
    test::GradedAnnulusDoFs dofs(MPI_COMM_SELF, degree);
    const MappingQ<2> mapping(degree);
    const std::vector<Point<2>> support = support_points(dofs.dof_handler, mapping);
    numerics::NodeGrid grid;
    std::vector<unsigned int> position;
    ASSERT_TRUE(polar_node_grid(support, degree, grid, position)) << "degree " << degree;
    EXPECT_EQ(grid.rows, degree * 8 + 1);
    EXPECT_EQ(grid.columns, degree * 64);
    EXPECT_TRUE(grid.periodic_columns);
    std::vector<bool> taken(support.size(), false);
    std::vector<std::size_t> column_node(grid.columns, support.size());
    for (std::size_t dof = 0; dof < support.size(); ++dof)
      if (position[dof] < grid.columns)
        column_node[position[dof]] = dof;
    for (const std::size_t dof : column_node)
      ASSERT_LT(dof, support.size());
    double worst_angle = 0;
    for (std::size_t dof = 0; dof < support.size(); ++dof)
    {
      ASSERT_LT(position[dof], support.size());
      EXPECT_FALSE(taken[position[dof]]);
      taken[position[dof]] = true;
      // the angle of the node of the same column on the inner circle (row 0)
      const std::size_t inner = column_node[position[dof] % grid.columns];
      const double angle = std::atan2(support[dof][1], support[dof][0]),
                   expected = std::atan2(support[inner][1], support[inner][0]);
      worst_angle = std::max(worst_angle, std::abs(std::remainder(angle - expected, 2 * M_PI)));
    }
    EXPECT_LT(worst_angle, 1e-12);

    // the matrix of the cells' couplings: every entry inside one cell
    DynamicSparsityPattern pattern(dofs.dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dofs.dof_handler, pattern);
    TrilinosWrappers::SparseMatrix matrix;
    matrix.reinit(complete_index_set(support.size()), complete_index_set(support.size()), pattern,
                  MPI_COMM_SELF);
    const std::vector<int> order = polar_nested_dissection(support, degree, matrix);
    ASSERT_EQ(order.size(), support.size()) << "degree " << degree;
    std::vector<bool> eliminated(order.size(), false);
    for (const int p : order)
    {
      ASSERT_GE(p, 1);
      ASSERT_LE(std::size_t(p), order.size());
      EXPECT_FALSE(eliminated[p - 1]);
      eliminated[p - 1] = true;
    }
    // the same order from the cells' dofs (the pattern's couplings), before any matrix
    const std::vector<unsigned int> cell_dofs = CellSparsity::active_cell_dofs(dofs.dof_handler);
    const unsigned int per_cell = dofs.dof_handler.get_fe().n_dofs_per_cell();
    EXPECT_EQ(polar_nested_dissection(support, degree, cell_dofs, per_cell), order);

    // Points that are not the grid, each refused by the quarter-spacing checks (the counts of
    // rows and columns kept): a node of a middle row turned by 0.3 of its column's spacing, or
    // moved 0.3 of the way to the next row (the local spacing is at least the smallest, whose
    // quarter is the bound)
    const unsigned int middle = grid.rows / 2, column = grid.columns / 3;
    const auto node_at = [&](const unsigned int i, const unsigned int j)
    {
      for (std::size_t dof = 0; dof < position.size(); ++dof)
        if (position[dof] == i * grid.columns + j)
          return dof;
      return position.size();
    };
    const std::size_t dof = node_at(middle, column), next_column = node_at(middle, column + 1),
                      next_row = node_at(middle + 1, column);
    ASSERT_LT(std::max({dof, next_column, next_row}), support.size());
    const double dtheta = std::atan2(support[next_column][1], support[next_column][0]) -
                          std::atan2(support[dof][1], support[dof][0]),
                 dr = support[next_row].norm() - support[dof].norm();
    ASSERT_GT(dtheta, 0);
    ASSERT_GT(dr, 0);
    std::vector<Point<2>> turned = support, moved = support;
    const double c = std::cos(0.3 * dtheta), s = std::sin(0.3 * dtheta);
    turned[dof] = Point<2>(c * support[dof][0] - s * support[dof][1],
                           s * support[dof][0] + c * support[dof][1]);
    moved[dof] *= (support[dof].norm() + 0.3 * dr) / support[dof].norm();
    numerics::NodeGrid refused;
    std::vector<unsigned int> refused_position;
    EXPECT_FALSE(polar_node_grid(turned, degree, refused, refused_position)) << "degree " << degree;
    EXPECT_TRUE(polar_nested_dissection(turned, degree, matrix).empty());
    EXPECT_TRUE(polar_nested_dissection(turned, degree, cell_dofs, per_cell).empty());
    EXPECT_FALSE(polar_node_grid(moved, degree, refused, refused_position)) << "degree " << degree;

    // A matrix entry between two nodes that no cell holds (a middle node and the node half a
    // turn away): the separators would not separate, so no order is given
    DynamicSparsityPattern coupled(dofs.dof_handler.n_dofs()); // (a copy must be empty)
    DoFTools::make_sparsity_pattern(dofs.dof_handler, coupled);
    const std::size_t opposite = node_at(middle, (column + grid.columns / 2) % grid.columns);
    ASSERT_LT(opposite, support.size());
    coupled.add(dof, opposite);
    TrilinosWrappers::SparseMatrix coupled_matrix;
    coupled_matrix.reinit(complete_index_set(support.size()), complete_index_set(support.size()),
                          coupled, MPI_COMM_SELF);
    EXPECT_TRUE(polar_nested_dissection(support, degree, coupled_matrix).empty());
    // and a cell whose dofs hold both (the last dof of a cell of the middle node replaced)
    std::vector<unsigned int> far_cell = cell_dofs;
    const std::size_t k = std::find(far_cell.begin(), far_cell.end(), dof) - far_cell.begin();
    ASSERT_LT(k, far_cell.size());
    far_cell[(k / per_cell) * per_cell + (k % per_cell == per_cell - 1 ? 0 : per_cell - 1)] =
        opposite;
    EXPECT_TRUE(polar_nested_dissection(support, degree, far_cell, per_cell).empty());
  }
}
