// The dofs of the built-in annulus as the nodes of its polar grid, and their nested-dissection
// elimination order for the sparse direct factorisations of the film's matrices.
#pragma once

#include <sealfe/numerics/nested_dissection.h>

#include <deal.II/base/point.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <vector>

namespace sealfe
{
/// The grid position (numerics::NodeGrid, rows radial and columns angular, a ring) of every dof
/// of a degree-`degree` space on a polar tensor mesh, from the dofs' support points `support` (by
/// dof index, all dofs on one rank): the rows are the radii of the nodes on the ray theta = 0,
/// the columns the angles of the nodes on the inner circle; every node must lie within a quarter
/// of the spacings of a row's radius and a column's angle, each position taken once. False
/// where the points are not such a grid: a gmsh mesh, angles shifted from row to row (spiral
/// alignment), surface-aligned meshes whose columns are not the same in every row.
bool polar_node_grid(const std::vector<dealii::Point<2>> &support, unsigned int degree,
                     numerics::NodeGrid &grid, std::vector<unsigned int> &position_of_dof);

/// The elimination position (1-based, SparseDirect::set_elimination_order) of every row of
/// `matrix` (one rank, rows = dofs) in the nested dissection of the polar node grid
/// (numerics::nested_dissection_order); empty where the dofs are not a polar grid or an entry of
/// the matrix couples two nodes that no cell holds (the separators would not separate: the
/// factorisation would still be right, only denser), so that MUMPS's AMD orders instead.
std::vector<int> polar_nested_dissection(const std::vector<dealii::Point<2>> &support,
                                         unsigned int degree,
                                         const dealii::TrilinosWrappers::SparseMatrix &matrix);

/// The same order for the pattern of a matrix assembled over cells whose dofs are `cell_dofs`
/// (`dofs_per_cell` numbers per cell, CellSparsity::active_cell_dofs), before that matrix is
/// made: empty where the dofs are not a polar grid or two dofs of a cell are not within one
/// cell of it. Reads no matrix and makes no MPI call (ReynoldsSolver makes it on a thread while
/// the coarse levels run).
std::vector<int> polar_nested_dissection(const std::vector<dealii::Point<2>> &support,
                                         unsigned int degree,
                                         const std::vector<unsigned int> &cell_dofs,
                                         unsigned int dofs_per_cell);
} // namespace sealfe
