// ActiveSetKrylov (jfo_krylov.h), the block-triangular GMRES of the JFO active-set probe, on an
// m x m grid whose left half (F) has Laplacian rows and whose right half (C) has upwind
// transport rows. Linear algebra only: (1) when the matrix itself is block lower (upper)
// triangular the lower (upper) preconditioner with exact block solves is its inverse, so
// right-preconditioned GMRES ends after one iteration at round-off; (2) with approximate block
// solves (AMG, ILU, ILUT) on the coupled matrix GMRES stops at the requested true residual
// (right preconditioning: its residual is that of the unpreconditioned system).
#include <sealfe/film/jfo_krylov.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
constexpr unsigned int m = 24, n = m * m;

unsigned int node(const unsigned int i, const unsigned int j)
{
  return j * m + i;
}
bool in_full_film(const unsigned int k)
{
  return k % m < m / 2;
}

/// F rows: 5-point Laplacian (Dirichlet outside the grid), with or without their entries in C
/// columns; C rows: upwind transport in +x, 1.5 on the diagonal (diagonally dominant), -1 on
/// the left neighbour, with or without that entry when the neighbour is in F.
void make(TrilinosWrappers::SparseMatrix &A, const bool F_to_C, const bool C_to_F)
{
  DynamicSparsityPattern pattern(n, n);
  std::vector<std::vector<std::pair<unsigned int, double>>> rows(n);
  for (unsigned int j = 0; j < m; ++j)
    for (unsigned int i = 0; i < m; ++i)
    {
      const unsigned int k = node(i, j);
      if (in_full_film(k))
      {
        rows[k].push_back({k, 4.0});
        const int di[] = {-1, 1, 0, 0}, dj[] = {0, 0, -1, 1};
        for (unsigned int e = 0; e < 4; ++e)
        {
          const int ii = static_cast<int>(i) + di[e], jj = static_cast<int>(j) + dj[e];
          if (ii < 0 || jj < 0 || ii >= static_cast<int>(m) || jj >= static_cast<int>(m))
            continue;
          const unsigned int l = node(ii, jj);
          if (in_full_film(l) || F_to_C)
            rows[k].push_back({l, -1.0});
        }
      }
      else
      {
        rows[k].push_back({k, 1.5});
        if (i > 0 && (!in_full_film(node(i - 1, j)) || C_to_F))
          rows[k].push_back({node(i - 1, j), -1.0});
      }
    }
  for (unsigned int k = 0; k < n; ++k)
    for (const auto &[l, value] : rows[k])
      pattern.add(k, l);
  const IndexSet all = complete_index_set(n);
  A.reinit(all, all, pattern, MPI_COMM_SELF);
  for (unsigned int k = 0; k < n; ++k)
    for (const auto &[l, value] : rows[k])
      A.set(k, l, value);
  A.compress(VectorOperation::insert);
}

struct Problem
{
  TrilinosWrappers::SparseMatrix A;
  TrilinosWrappers::MPI::Vector b;
  std::vector<char> full_film;
  std::vector<double> x, y;
  Problem(const bool F_to_C, const bool C_to_F)
  {
    make(A, F_to_C, C_to_F);
    b.reinit(complete_index_set(n), MPI_COMM_SELF);
    full_film.resize(n);
    x.resize(n);
    y.resize(n);
    for (unsigned int k = 0; k < n; ++k)
    {
      b[k] = 1.0 + std::sin(0.37 * k);
      full_film[k] = in_full_film(k);
      x[k] = (k % m) / double(m);
      y[k] = (k / m) / double(m);
    }
  }
  double relative_residual(const TrilinosWrappers::MPI::Vector &w) const
  {
    TrilinosWrappers::MPI::Vector r(b);
    A.vmult(r, w);
    r -= b;
    return r.l2_norm() / b.l2_norm();
  }
};
} // namespace

TEST(ActiveSetKrylov, ExactBlockSolvesInvertABlockTriangularMatrixInOneIteration)
{
  for (const bool lower : {true, false})
  {
    // lower: no F-row entries in C columns, so J is its own block lower triangle; upper: the
    // other way round
    Problem p(!lower, lower);
    ActiveSetKrylov::Options options;
    options.full_film = ActiveSetKrylov::FullFilmSolver::direct;
    options.transport = ActiveSetKrylov::TransportSolver::direct;
    options.lower = lower;
    options.degree = 1;
    ActiveSetKrylov krylov;
    krylov.setup(p.A, p.full_film, p.x, p.y, options);
    EXPECT_EQ(krylov.n_full_film(), n / 2);
    EXPECT_EQ(krylov.n_cavitated(), n / 2);
    TrilinosWrappers::MPI::Vector w(p.b);
    w = 0;
    // target 1e-12 |b|: met by one exact application (round-off ~ n u cond, cond ~ 1e3 here)
    const unsigned int iterations = krylov.solve(p.b, w, 1e-12 * p.b.l2_norm(), 10);
    EXPECT_EQ(iterations, 1u) << (lower ? "lower" : "upper");
    EXPECT_LT(p.relative_residual(w), 1e-12) << (lower ? "lower" : "upper");
  }
}

TEST(ActiveSetKrylov, ApproximateBlockSolvesReachTheRequestedTrueResidual)
{
  Problem p(true, true); // coupled both ways: the triangle is only a preconditioner
  for (const auto transport :
       {ActiveSetKrylov::TransportSolver::ilu, ActiveSetKrylov::TransportSolver::ilut})
    for (const bool lower : {true, false})
    {
      ActiveSetKrylov::Options options;
      options.transport = transport;
      options.lower = lower;
      options.degree = 1;
      ActiveSetKrylov krylov;
      krylov.setup(p.A, p.full_film, p.x, p.y, options);
      for (const double tolerance : {1e-6, 1e-10})
      {
        TrilinosWrappers::MPI::Vector w(p.b);
        w = 0;
        const unsigned int iterations = krylov.solve(p.b, w, tolerance * p.b.l2_norm(), 300);
        ASSERT_NE(iterations, std::numeric_limits<unsigned int>::max());
        EXPECT_GT(iterations, 1u); // the coupling is not in the preconditioner
        // GMRES's residual estimate equals the true residual up to round-off (u cond |b|)
        EXPECT_LT(p.relative_residual(w), tolerance * (1 + 1e-3) + 1e-13)
            << "tolerance " << tolerance << (lower ? " lower" : " upper");
      }
    }
}
