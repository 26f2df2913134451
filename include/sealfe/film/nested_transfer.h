// Values of finite element functions of a mesh at the nodes of the same mesh refined once more
// (the JFO coarse start on a mesh file with global refinements), found through the parent cells
// instead of a point search.
#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace sealfe
{
/// For the dofs `dofs` of `fine` (owned, with support points), the values of each of `fields`
/// (ghosted vectors on `coarse`) at their support points. `fine` must be `coarse`'s mesh refined
/// globally once more, from the same coarse grid, on one process: each fine cell's parent is then
/// an active cell of `coarse` with the same level and index, and a fine node's reference
/// coordinates in it are those of its child (exact up to the curvature the manifold gives the
/// children: O(h^2) of a cell, a start for Newton only). Returns false, with nothing filled, if
/// the meshes are not nested that way (the caller then searches the points).
bool values_from_parent_cells(
    const dealii::DoFHandler<2> &fine, const dealii::DoFHandler<2> &coarse,
    const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &fields,
    const std::vector<dealii::types::global_dof_index> &dofs,
    std::vector<std::vector<double>> &values);
} // namespace sealfe
