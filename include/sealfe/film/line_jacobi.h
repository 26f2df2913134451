// LineJacobi: block Jacobi over lines of dofs, each line block factorised exactly (banded LDL^T):
// the preconditioner the multigrid's Chebyshev smoother wraps, on the radial lines of the annulus.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

namespace sealfe
{
/// The locally owned dofs of a matrix grouped into lines (on the annulus: the dofs at one angle,
/// each line sorted by radius). Line k is the line positions start[k] .. start[k+1]; `order` is
/// the line position of each owned dof (by its index within the owned set); `at` the owned index
/// at each line position, empty where the dofs are numbered by lines (the position is the index:
/// the active dofs after FilmMultigrid::number_by_radial_lines).
struct RadialLines
{
  std::vector<unsigned int> order, start, at;
  unsigned int size() const { return order.size(); }
  /// The owned index at line position p.
  unsigned int index(const unsigned int p) const { return at.empty() ? p : at[p]; }
  /// Fills `at` from `order`: for dofs that keep a numbering other than by lines.
  void index_by_position();
};

/// Line Jacobi, x = B^-1 b with B the block diagonal of A over the lines (a banded Cholesky
/// factorisation LDL^T of each line block; the entries of A between two lines are left out).
/// The cells of the annulus are long in theta (up to ~45:1 at Ntheta/Nr = 1), so A couples a dof
/// far more strongly along r than along theta; a point smoother leaves the error that oscillates
/// in theta and is smooth in r, which the coarser levels cannot see (CG iterations 12 at
/// Ntheta/Nr = 32 but 93 at Ntheta/Nr = 1 with point Jacobi, measured). Solving each radial line
/// exactly removes that coupling from the smoother, the standard remedy for a strong coupling in
/// one mesh direction (Trottenberg, Oosterlee & Schueller 2001, ch. 5). Lines cut by a rank
/// boundary are solved in pieces (each rank's owned part). Where the dofs are not numbered by
/// lines (`at` not empty) the band and factors are kept by line position and each vector is
/// gathered into line order before the solve and scattered back after: the same operations, in
/// the same order, as on the same matrix numbered by lines.
class LineJacobi
{
public:
  using MatrixType = dealii::TrilinosWrappers::SparseMatrix;
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  /// Factorises the line blocks of `A` (square, its owned rows those of `lines`). `lines` is
  /// kept by reference until the next initialize().
  void initialize(const MatrixType &A, const RadialLines &lines);

  /// dst = B^-1 src.
  void vmult(VectorType &dst, const VectorType &src) const;

  /// The half bandwidth of the line blocks (the element degree on the annulus).
  unsigned int bandwidth() const { return band_width; }

private:
  /// x = B^-1 b on the lines first_line .. last_line - 1 (x may be b).
  void solve(double *x, const double *b, unsigned int first_line, unsigned int last_line) const;
  template <unsigned int B>
  void solve(double *x, const double *b, unsigned int first_line, unsigned int last_line) const;

  const RadialLines *lines = nullptr;
  unsigned int band_width = 0;
  std::vector<double> band;
  mutable std::vector<double> work; // the vector in line order (dofs not numbered by lines)
};

} // namespace sealfe
