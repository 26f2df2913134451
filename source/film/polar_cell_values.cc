#include <sealfe/film/polar_cell_values.h>

#include <deal.II/fe/fe_values.h>

#include <cmath>
#include <limits>

namespace sealfe
{
using namespace dealii;

PolarCellValues::PolarCellValues(const Mapping<2> &mapping_in, const FiniteElement<2> &fe_in,
                                 const Quadrature<2> &quadrature_in)
    : mapping(&mapping_in), fe(&fe_in), quadrature(quadrature_in), n(fe_in.n_dofs_per_cell()),
      n_q(quadrature_in.size()), points(n_q), grads(std::size_t(n) * n_q)
{
}

bool PolarCellValues::reinit(const Triangulation<2>::cell_iterator &cell)
{
  std::array<Point<2>, 4> v;
  for (unsigned int k = 0; k < 4; ++k)
    v[k] = cell->vertex(k);
  const double r0 = v[0].norm(), r1 = v[1].norm(), r2 = v[2].norm();
  if (!(r0 > 0) || !(r2 > 0))
    return false;
  // The row: inner and outer radius, in units of 2^-36 m (1.5e-11 m: far below the spacing of
  // rows, far above the round-off of a radius), and angular width (sine of the angle between
  // vertices 0 and 2) in units of 2^-36. A value that straddles a rounding step only gives the
  // row a second first cell.
  const double scale = std::ldexp(1.0, 36); // per metre
  const double width = (v[0][0] * v[2][1] - v[0][1] * v[2][0]) / (r0 * r2);
  const std::array<long long, 3> key = {
      {std::llround(r0 * scale), std::llround(r1 * scale), std::llround(width * scale)}};
  auto it = rows.find(key);
  if (it == rows.end())
  {
    Row fresh;
    fresh.vertices = v;
    FEValues<2> fe_values(*mapping, *fe, quadrature,
                          update_values | update_gradients | update_quadrature_points |
                              update_JxW_values);
    fe_values.reinit(cell);
    fresh.points = fe_values.get_quadrature_points();
    fresh.JxW = fe_values.get_JxW_values();
    for (const Point<2> &x : fresh.points)
    {
      fresh.radii.push_back(x.norm());
      fresh.angles.push_back(std::atan2(x[1], x[0]));
    }
    fresh.grads.resize(std::size_t(n) * n_q);
    fresh.gram.resize(std::size_t(n) * n * n_q);
    if (values.empty())
    {
      values.resize(std::size_t(n) * n_q);
      for (unsigned int q = 0; q < n_q; ++q)
        for (unsigned int i = 0; i < n; ++i)
          values[std::size_t(q) * n + i] = fe_values.shape_value(i, q);
    }
    for (unsigned int q = 0; q < n_q; ++q)
    {
      for (unsigned int i = 0; i < n; ++i)
        fresh.grads[std::size_t(q) * n + i] = fe_values.shape_grad(i, q);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          fresh.gram[(std::size_t(q) * n + i) * n + j] =
              (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q)) * fe_values.JxW(q);
    }
    it = rows.emplace(key, std::move(fresh)).first;
  }
  row = &it->second;
  // The angle from the row's first cell: cos and sin from vertex 0 of both (same radius).
  const Point<2> &a = row->vertices[0];
  const double dot = a[0] * v[0][0] + a[1] * v[0][1], cross = a[0] * v[0][1] - a[1] * v[0][0];
  const double norm = std::sqrt(dot * dot + cross * cross);
  c = dot / norm;
  s = cross / norm;
  // Refuse a cell whose vertices are not those of the first cell turned by that angle (to
  // 64 u r: the round-off of the mesh's vertices and of the rotation, a few u r each).
  const double tolerance = 64 * std::numeric_limits<double>::epsilon() * std::max(r0, r1);
  for (unsigned int k = 0; k < 4; ++k)
  {
    const Point<2> &w = row->vertices[k];
    if (std::abs(c * w[0] - s * w[1] - v[k][0]) > tolerance ||
        std::abs(s * w[0] + c * w[1] - v[k][1]) > tolerance)
      return false;
  }
  if (c != 1 || s != 0)
    ++turned;
  cell_angle = std::atan2(s, c);
  for (unsigned int q = 0; q < n_q; ++q)
  {
    const Point<2> &x = row->points[q];
    points[q] = Point<2>(c * x[0] - s * x[1], s * x[0] + c * x[1]);
  }
  grads_turned = false;
  return true;
}

void PolarCellValues::get_function_values(const Vector<double> &dof_values,
                                          std::vector<double> &values) const
{
  AssertDimension(dof_values.size(), n);
  values.resize(n_q);
  for (unsigned int q = 0; q < n_q; ++q)
  {
    values[q] = 0;
    for (unsigned int i = 0; i < n; ++i)
      values[q] += dof_values(i) * shape_value(i, q);
  }
}

void PolarCellValues::get_function_gradients(const Vector<double> &dof_values,
                                             std::vector<Tensor<1, 2>> &gradients) const
{
  AssertDimension(dof_values.size(), n);
  gradients.resize(n_q);
  for (unsigned int q = 0; q < n_q; ++q)
  {
    gradients[q] = Tensor<1, 2>();
    for (unsigned int i = 0; i < n; ++i)
      gradients[q] += dof_values(i) * shape_grad(i, q);
  }
}

void PolarCellValues::turn_gradients() const
{
  for (std::size_t k = 0; k < grads.size(); ++k)
  {
    const Tensor<1, 2> &g = row->grads[k];
    grads[k][0] = c * g[0] - s * g[1];
    grads[k][1] = s * g[0] + c * g[1];
  }
  grads_turned = true;
}

std::vector<DoFHandler<2>::active_cell_iterator>
owned_cells_finding_rows(const DoFHandler<2> &dof_handler, std::optional<PolarCellValues> &polar)
{
  std::vector<DoFHandler<2>::active_cell_iterator> cells;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cells.push_back(cell);
      if (polar)
        polar->reinit(cell);
    }
  return cells;
}
} // namespace sealfe
