#include <sealfe/film/nested_transfer.h>

#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <unordered_map>

namespace sealfe
{
using namespace dealii;

bool values_from_parent_cells(const DoFHandler<2> &fine, const DoFHandler<2> &coarse,
                              const std::vector<const TrilinosWrappers::MPI::Vector *> &fields,
                              const std::vector<types::global_dof_index> &dofs,
                              std::vector<std::vector<double>> &values)
{
  const Triangulation<2> &fine_tria = fine.get_triangulation(),
                         &coarse_tria = coarse.get_triangulation();
  if (Utilities::MPI::n_mpi_processes(fine_tria.get_communicator()) > 1 ||
      fine_tria.n_levels() != coarse_tria.n_levels() + 1 || fine_tria.n_levels() < 2 ||
      fine.get_fe().n_dofs_per_cell() != coarse.get_fe().n_dofs_per_cell() ||
      !fine.get_fe().has_support_points())
    return false;
  const FiniteElement<2> &fe = fine.get_fe();
  const std::vector<Point<2>> &unit = fe.get_unit_support_points();
  std::unordered_map<types::global_dof_index, std::size_t> wanted;
  for (std::size_t k = 0; k < dofs.size(); ++k)
    wanted[dofs[k]] = k;
  std::vector<std::vector<double>> out(fields.size(), std::vector<double>(dofs.size()));
  std::vector<bool> filled(dofs.size(), false);
  std::vector<types::global_dof_index> fine_dofs(fe.n_dofs_per_cell());
  std::vector<Vector<double>> coarse_values(fields.size(), Vector<double>(fe.n_dofs_per_cell()));
  const double tolerance = 1e-10 * GridTools::diameter(coarse_tria);
  for (const auto &cell : fine.active_cell_iterators())
  {
    if (cell->level() != int(fine_tria.n_levels()) - 1 || cell->level() == 0)
      return false;
    const auto parent = cell->parent();
    const typename DoFHandler<2>::cell_iterator other(&coarse_tria, parent->level(),
                                                      parent->index(), &coarse);
    if (!other->is_active())
      return false;
    for (const unsigned int v : parent->vertex_indices())
      if (parent->vertex(v).distance(other->vertex(v)) > tolerance)
        return false;
    cell->get_dof_indices(fine_dofs);
    bool needed = false;
    for (const auto g : fine_dofs)
    {
      const auto it = wanted.find(g);
      needed = needed || (it != wanted.end() && !filled[it->second]);
    }
    if (!needed)
      continue;
    for (std::size_t f = 0; f < fields.size(); ++f)
      other->get_dof_values(*fields[f], coarse_values[f]);
    // child c of an isotropically refined quad covers [c % 2, c % 2 + 1] x [c / 2, c / 2 + 1] / 2
    const unsigned int child = parent->child_iterator_to_index(cell);
    const Point<2> corner(0.5 * (child % 2), 0.5 * (child / 2));
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
    {
      const auto it = wanted.find(fine_dofs[i]);
      if (it == wanted.end() || filled[it->second])
        continue;
      const Point<2> x = corner + 0.5 * unit[i];
      for (std::size_t f = 0; f < fields.size(); ++f)
      {
        double value = 0;
        for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
          value += coarse_values[f][j] * fe.shape_value(j, x);
        out[f][it->second] = value;
      }
      filled[it->second] = true;
    }
  }
  for (const bool f : filled)
    if (!f)
      return false;
  values = std::move(out);
  return true;
}
} // namespace sealfe
