// LineStencilMatrix: a matrix whose dofs are numbered by radial lines, held as a stencil over the
// neighbouring lines with single-precision values: the multigrid smoother's products on the
// finest level at about half the memory traffic of the Trilinos matrix.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace sealfe
{
/// y = Ã x for a square Trilinos matrix A whose owned dofs are numbered by lines (line k: the
/// owned indices start[k] .. start[k+1]; FilmMultigrid::number_by_radial_lines). Ã is A with its
/// off-diagonal entries rounded to single precision and each diagonal entry moved by the rounding
/// errors of its row, so that Ã and A have the same row sums (the products of a constant agree:
/// the smooth error the coarse levels correct is the one the rounding would otherwise spoil);
/// the arithmetic is double.
///
/// Why: a product with A on the finest level of the multigrid reads 12 bytes per entry (value and
/// column index), ~16 entries per row for Q2 on quadrilaterals; on the annulus every entry of a
/// row at (line k, position q) couples to a dof at (line k + a, position q + d) with |a|, |d| <=
/// the element degree, so the column follows from (a, d) and each entry costs the 4 bytes of its
/// value. The smoother wants only an approximation of A (its products enter a Chebyshev
/// polynomial that the coarse levels correct), the CG iterations keep the Trilinos matrix.
///
/// The encoding is algebraic and checked entry by entry: an entry A_ij of row i on line k is
/// held at (a, d) only if j is owned and j = start[(k + a) mod n_lines] + (i - start[k]) + d with
/// |a|, |d| <= 3; so the product reads exactly the x_j the entry multiplies, whatever the mesh.
/// The lines with an entry that does not fit (columns on another rank, a mesh not numbered by
/// lines) keep their rows in a Trilinos remainder matrix in double, applied after the stencil.
class LineStencilMatrix
{
public:
  using MatrixType = dealii::TrilinosWrappers::SparseMatrix;
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  /// Encodes A (its rows of lines that do not fit copied into the remainder; A is not kept).
  void initialize(const MatrixType &A, const std::vector<unsigned int> &line_start);

  /// dst = Ã src.
  void vmult(VectorType &dst, const VectorType &src) const;

  /// The global size (deal.II's PreconditionChebyshev asks).
  dealii::types::global_dof_index m() const { return n_rows; }
  dealii::types::global_dof_index n() const { return n_rows; }

  /// The owned rows held in the stencil (the rest in the remainder).
  unsigned int n_stencil_rows() const { return stencil_rows; }

private:
  /// The largest line and position offset held (the element degree, up to Q3).
  static constexpr int max_reach = 3;

  template <int A>
  void line_product(unsigned int k, const double *x, double *y) const;

  std::vector<unsigned int> start;
  /// Per line: the half width A of the neighbouring lines it couples to (0..max_reach), or -1:
  /// the line is in the remainder; the half width R of its position offsets; the offset of its
  /// values.
  std::vector<std::int8_t> line_reach, position_reach;
  std::vector<std::size_t> value_offset;
  /// Slot by slot within each line: (2 A + 1) x (2 R + 1) slots (the neighbouring line k + a,
  /// a = -A .. A, and the offset d = -R .. R of the position on it), each the line's rows in
  /// order; the diagonal's slot holds 0 and is skipped (diagonal below).
  std::vector<float> values;
  std::vector<double> diagonal;
  unsigned int stencil_rows = 0;
  dealii::types::global_dof_index n_rows = 0;
  std::unique_ptr<Epetra_CrsMatrix> remainder;
  mutable VectorType remainder_product;
};

} // namespace sealfe
