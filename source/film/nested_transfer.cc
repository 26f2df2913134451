#include <sealfe/film/nested_transfer.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/rtree.h>

#include <boost/geometry/index/rtree.hpp>

#include <limits>

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

bool values_at_points(const Mapping<2> &mapping, const DoFHandler<2> &dof_handler,
                      const std::vector<const TrilinosWrappers::MPI::Vector *> &fields,
                      const std::vector<Point<2>> &points, std::vector<std::vector<double>> &values)
{
  if (Utilities::MPI::n_mpi_processes(dof_handler.get_triangulation().get_communicator()) > 1)
    return false;
  using Cell = DoFHandler<2>::active_cell_iterator;
  // boxes from the mapping's support points, widened by a tenth of their size: a curved edge
  // bulges slightly past its support points
  std::vector<std::pair<BoundingBox<2>, Cell>> boxes;
  boxes.reserve(dof_handler.get_triangulation().n_active_cells());
  for (const auto &cell : dof_handler.active_cell_iterators())
  {
    BoundingBox<2> box = mapping.get_bounding_box(cell);
    const auto &[lo, hi] = box.get_boundary_points();
    box.extend(0.1 * std::max(hi[0] - lo[0], hi[1] - lo[1]));
    boxes.emplace_back(box, cell);
  }
  const auto tree = pack_rtree(boxes);
  namespace bgi = boost::geometry::index;
  const FiniteElement<2> &fe = dof_handler.get_fe();
  std::vector<std::vector<double>> out(fields.size(), std::vector<double>(points.size()));
  std::vector<Vector<double>> nodal(fields.size(), Vector<double>(fe.n_dofs_per_cell()));
  std::vector<std::pair<BoundingBox<2>, Cell>> candidates;
  Point<2> unit;
  for (std::size_t q = 0; q < points.size(); ++q)
  {
    candidates.clear();
    tree.query(bgi::intersects(points[q]), std::back_inserter(candidates));
    if (candidates.empty())
      // outside every box: the nearest boxes
      tree.query(bgi::nearest(points[q], 4), std::back_inserter(candidates));
    Cell best;
    double best_distance = std::numeric_limits<double>::max();
    for (const auto &[box, cell] : candidates)
    {
      Point<2> u;
      mapping.transform_points_real_to_unit_cell(cell, make_array_view(&points[q], &points[q] + 1),
                                                 make_array_view(&u, &u + 1));
      if (!std::isfinite(u[0]))
        continue; // the inverse mapping failed: the point is far from this cell
      const double d = GeometryInfo<2>::distance_to_unit_cell(u);
      if (d < best_distance)
      {
        best_distance = d;
        best = cell;
        unit = u;
      }
      if (d == 0)
        break;
    }
    if (best_distance == std::numeric_limits<double>::max())
      return false;
    unit = GeometryInfo<2>::project_to_unit_cell(unit);
    for (std::size_t f = 0; f < fields.size(); ++f)
    {
      best->get_dof_values(*fields[f], nodal[f]);
      double value = 0;
      for (unsigned int j = 0; j < fe.n_dofs_per_cell(); ++j)
        value += nodal[f][j] * fe.shape_value(j, unit);
      out[f][q] = value;
    }
  }
  values = std::move(out);
  return true;
}
} // namespace sealfe
