// PolarCellValues: the values FEValues gives on a cell of the built-in polar annulus, from one
// FEValues evaluation per radial row (every cell of a row is a rotation of the row's first cell).
#pragma once

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/std_cxx20/iota_view.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <map>
#include <optional>
#include <vector>

namespace sealfe
{
/// On the built-in annulus (vertices on circles, angles 2 pi j / N_theta with a shift that
/// depends on r only, the polar manifold everywhere) all cells of one radial row are the same cell
/// turned about the axis by a multiple of 2 pi / N_theta: their Jacobians, JxW and the shape
/// gradients turned back are the same. reinit() finds the row of a cell (by its vertex radii and
/// angular width), evaluates FEValues once on the first cell of each row, and gives the cell's
/// values by turning the row's points and gradients (a 2 x 2 rotation instead of a mapping and
/// gradient transformation per cell). A cell that is not such a rotation (checked on its four
/// vertices) is refused: the caller uses FEValues for it. Equal to FEValues to round-off
/// (tests/validation/polar_cell_values.cc).
class PolarCellValues
{
public:
  PolarCellValues(const dealii::Mapping<2> &mapping, const dealii::FiniteElement<2> &fe,
                  const dealii::Quadrature<2> &quadrature);

  /// The values of `cell`; false (values undefined) if it is not a rotation of its row's first
  /// cell about the origin.
  bool reinit(const dealii::Triangulation<2>::cell_iterator &cell);

  unsigned int n_quadrature_points() const { return n_q; }
  dealii::std_cxx20::ranges::iota_view<unsigned int, unsigned int> quadrature_point_indices() const
  {
    return {0U, n_q};
  }
  const dealii::FiniteElement<2> &get_fe() const { return *fe; }
  const dealii::Point<2> &quadrature_point(const unsigned int q) const { return points[q]; }
  /// |x_q| and the angle of x_q in (-pi, pi] (atan2), from the row's first cell (the radius is
  /// the same, the angle turned by the cell's): equal to norm() and atan2 of quadrature_point(q)
  /// to round-off, without a square root and an atan2 per point.
  double radius(const unsigned int q) const { return row->radii[q]; }
  double angle(const unsigned int q) const
  {
    const double theta = row->angles[q] + cell_angle;
    constexpr double pi = dealii::numbers::PI;
    return theta > pi ? theta - 2 * pi : (theta <= -pi ? theta + 2 * pi : theta);
  }
  double JxW(const unsigned int q) const { return row->JxW[q]; }
  double shape_value(const unsigned int i, const unsigned int q) const
  {
    return values[std::size_t(q) * n + i];
  }
  /// The gradient of shape function i at point q (turned on the first call after reinit).
  const dealii::Tensor<1, 2> &shape_grad(const unsigned int i, const unsigned int q) const
  {
    if (!grads_turned)
      turn_gradients();
    return grads[std::size_t(q) * n + i];
  }

  /// The values and gradients at the points of the finite element function whose values at this
  /// cell's dofs are `dof_values` (cell->get_dof_values): FEValues::get_function_values' and
  /// get_function_gradients' sums, over the shape functions in order at each point. The cell's
  /// nodal values, not a global vector, since reinit() takes the cell without its dofs.
  void get_function_values(const dealii::Vector<double> &dof_values,
                           std::vector<double> &values) const;
  void get_function_gradients(const dealii::Vector<double> &dof_values,
                              std::vector<dealii::Tensor<1, 2>> &gradients) const;

  /// The same in the frame of the row's first cell (the cell turned back by its angle): points,
  /// gradients, and a vector of this cell's frame turned into it. Products of two vectors are
  /// the same in either frame.
  const dealii::Point<2> &reference_point(const unsigned int q) const { return row->points[q]; }
  const dealii::Tensor<1, 2> &reference_shape_grad(const unsigned int i, const unsigned int q) const
  {
    return row->grads[std::size_t(q) * n + i];
  }
  dealii::Tensor<1, 2> to_reference(const dealii::Tensor<1, 2> &v) const
  {
    return dealii::Tensor<1, 2>({c * v[0] + s * v[1], -s * v[0] + c * v[1]});
  }
  /// (grad phi_i . grad phi_j) JxW at point q, [i n + j]: the same for every cell of the row
  /// (what an isotropic K needs).
  const double *gram(const unsigned int q) const { return &row->gram[std::size_t(q) * n * n]; }

  /// Cells given by rotation and rows evaluated by FEValues since construction.
  unsigned int n_turned() const { return turned; }
  unsigned int n_rows() const { return rows.size(); }

private:
  struct Row
  {
    std::array<dealii::Point<2>, 4> vertices;
    std::vector<dealii::Point<2>> points;
    std::vector<double> radii, angles; // of points
    std::vector<double> JxW;
    std::vector<dealii::Tensor<1, 2>> grads; // [q n + i]
    std::vector<double> gram;                // [(q n + i) n + j]
  };
  void turn_gradients() const;

  const dealii::Mapping<2> *mapping;
  const dealii::FiniteElement<2> *fe;
  dealii::Quadrature<2> quadrature;
  unsigned int n, n_q;
  std::vector<double> values; // [q n + i], the same on every cell (FE_Q)
  std::map<std::array<long long, 3>, Row> rows;
  /// The current cell's row, a pointer into `rows`. A copy (one per thread) has rows of its own
  /// and no current cell until its reinit(): the pointer is not copied.
  struct CurrentRow
  {
    const Row *row = nullptr;
    CurrentRow() = default;
    CurrentRow(const CurrentRow &) {}
    CurrentRow &operator=(const CurrentRow &)
    {
      row = nullptr;
      return *this;
    }
    CurrentRow &operator=(const Row *r)
    {
      row = r;
      return *this;
    }
    const Row *operator->() const { return row; }
  };
  CurrentRow row;
  double c = 1, s = 0;   // cos, sin of the angle from the row's first cell to this one
  double cell_angle = 0; // that angle (atan2(s, c))
  std::vector<dealii::Point<2>> points;
  mutable std::vector<dealii::Tensor<1, 2>> grads;
  mutable bool grads_turned = false;
  unsigned int turned = 0;
};

/// The locally owned active cells of `dof_handler` in their order; where `polar` is set, their
/// rows are found in that order too (reinit on each), so that the copies a threaded loop makes
/// afterwards, one per thread, turn the same first cell of each row.
std::vector<dealii::DoFHandler<2>::active_cell_iterator>
owned_cells_finding_rows(const dealii::DoFHandler<2> &dof_handler,
                         std::optional<PolarCellValues> &polar);
} // namespace sealfe
