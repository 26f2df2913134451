// Values of finite element functions of a mesh at the nodes of another mesh (the JFO coarse
// start): through the parent cells when the other mesh is this one refined once more, else by a
// point search over the cells' bounding boxes (one rank).
#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
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

/// The values of each of `fields` (ghosted vectors on `dof_handler`) at `points`, on one process
/// and any mesh (e.g. a regenerated coarser gmsh mesh): each point's cell is found among the
/// cells whose bounding box holds it (an R-tree), by the mapping's inverse. A point that falls in
/// no cell (the polygonal boundaries of two meshes differ by O(h^2)) takes the nearest cell's
/// value at the unit-cell point closest to it. deal.II 9.4's point search (RemotePointEvaluation)
/// scans all cells for every point its vertex-based guess misses: 25 s for 1e5 points on a gmsh
/// mesh (doc/textures.md). Returns false on several processes.
bool values_at_points(const dealii::Mapping<2> &mapping, const dealii::DoFHandler<2> &dof_handler,
                      const std::vector<const dealii::TrilinosWrappers::MPI::Vector *> &fields,
                      const std::vector<dealii::Point<2>> &points,
                      std::vector<std::vector<double>> &values);
} // namespace sealfe
