// SparseDirect and the band solve of the JFO active-set polish (sparse_direct.h) on a
// nonsymmetric upwind convection-diffusion matrix: a refactorisation with the kept ordering
// solves the new matrix, and solve_on_subset solves exactly the principal subsystem A_SS x_S = b_S
// and leaves the rest of x alone (linear algebra: residuals at round-off).
#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;
using namespace dealii;

namespace
{
constexpr unsigned int n = 200;

/// -u'' + c u' on a uniform 1D grid, upwind convection (c > 0): tridiagonal, nonsymmetric.
void fill(TrilinosWrappers::SparseMatrix &A, const double c)
{
  for (unsigned int i = 0; i < n; ++i)
  {
    A.set(i, i, 2.0 + c);
    if (i > 0)
      A.set(i, i - 1, -1.0 - c);
    if (i + 1 < n)
      A.set(i, i + 1, -1.0);
  }
  A.compress(VectorOperation::insert);
}

void make(TrilinosWrappers::SparseMatrix &A)
{
  DynamicSparsityPattern pattern(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(i + 1, n - 1); ++j)
      pattern.add(i, j);
  const IndexSet all = complete_index_set(n);
  A.reinit(all, all, pattern, MPI_COMM_SELF);
}

double residual(const TrilinosWrappers::SparseMatrix &A, const TrilinosWrappers::MPI::Vector &x,
                const TrilinosWrappers::MPI::Vector &b)
{
  TrilinosWrappers::MPI::Vector r(b);
  A.vmult(r, x);
  r -= b;
  return r.linfty_norm() / b.linfty_norm();
}
} // namespace

TEST(SparseDirect, RefactorisationWithTheKeptOrderingSolvesTheNewMatrix)
{
  TrilinosWrappers::SparseMatrix A;
  make(A);
  const IndexSet all = complete_index_set(n);
  TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(all, MPI_COMM_SELF);
  for (unsigned int i = 0; i < n; ++i)
    b[i] = std::sin(0.1 * i) + 1;
  SparseDirect lu;
  for (const double c : {0.0, 5.0, 50.0})
  {
    fill(A, c);
    lu.factorize(A);
    lu.solve(b, x);
    EXPECT_LT(residual(A, x, b), 1e-12) << "c = " << c;
  }
  EXPECT_EQ(lu.numeric_only(), 2u); // the 2nd and 3rd reused the ordering
}

TEST(SparseDirect, SubsetSolveSolvesThePrincipalSubsystemOnly)
{
  TrilinosWrappers::SparseMatrix A;
  make(A);
  fill(A, 10.0);
  const IndexSet all = complete_index_set(n);
  TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(all, MPI_COMM_SELF);
  for (unsigned int i = 0; i < n; ++i)
  {
    b[i] = std::cos(0.05 * i);
    x[i] = -7; // untouched outside the subset
  }
  std::vector<bool> seed(n, false);
  seed[100] = true;
  // 3 layers of the tridiagonal graph: dofs 97 .. 103
  const std::vector<bool> subset = grow_in_graph(A, seed, 3);
  for (unsigned int i = 0; i < n; ++i)
    EXPECT_EQ(subset[i], i >= 97 && i <= 103) << i;
  solve_on_subset(A, subset, b, x);
  for (unsigned int i = 97; i <= 103; ++i)
  {
    // row i of A_SS x_S = b_S
    double row = 0;
    for (unsigned int j = std::max(i - 1, 97u); j <= std::min(i + 1, 103u); ++j)
      row += A.el(i, j) * x[j];
    EXPECT_NEAR(row, b[i], 1e-13 * std::abs(b[i]) + 1e-14) << i;
  }
  for (unsigned int i = 0; i < n; ++i)
    if (!subset[i])
      EXPECT_EQ(x[i], -7.0) << i;

  // the whole set: the solution of A x = b
  solve_on_subset(A, std::vector<bool>(n, true), b, x);
  EXPECT_LT(residual(A, x, b), 1e-12);
}
