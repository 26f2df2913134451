// LineJacobi (include/sealfe/film/line_jacobi.h), the multigrid's line smoother, on small
// symmetric matrices with lines of 2-12 dofs and couplings between the lines:
// - theory: one application is the exact solve of each line's block B (the couplings between
//   lines left out): for x given and b = B x, x is recovered to the forward error bound of a
//   Cholesky solve, kappa(B) (4 w + 8) u (band LDL^T of half bandwidth w: backward error
//   gamma_{w+2}, plus the rounding of b = B x; Higham 2002, 10.1), kappa(B) bounded by
//   Gershgorin's circles of the blocks;
// - gather/scatter: on the same matrix numbered otherwise (a permutation of the dofs, as deal.II
//   numbers a multigrid level) the result is the same permutation of the result on the matrix
//   numbered by lines, to the bit: the same band and the same operations in the same order.
// - interleaving: lines of one length are swept 4 at a time, side by side; each line's result is
//   the one of that line's block solved alone (a matrix of one line), to the bit.
// Half bandwidths 1-3 (the unrolled solves) and 4 (the generic one).
#include "../line_matrices.h"

#include <sealfe/film/line_jacobi.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
using sealfe::testing::Entries;
using sealfe::testing::make_entries;
using sealfe::testing::make_matrix;

/// Lines of these lengths (2 and 3: shorter than the band), numbered one after the other.
const std::vector<unsigned int> lengths = {2, 9, 7, 12, 3, 8};

RadialLines lines_in_order(const std::vector<unsigned int> &lengths = ::lengths)
{
  return sealfe::testing::lines_of_lengths(lengths);
}

bool same_line(const RadialLines &lines, const unsigned int i, const unsigned int j)
{
  const auto line = [&](const unsigned int p)
  { return std::upper_bound(lines.start.begin(), lines.start.end(), p) - lines.start.begin(); };
  return line(i) == line(j);
}
} // namespace

TEST(LineJacobi, SolvesEachLineBlockExactly)
{
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const RadialLines lines = lines_in_order();
  const unsigned int n = lines.size();
  std::vector<unsigned int> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  for (const unsigned int w : {1u, 2u, 3u, 4u})
  {
    const Entries a = make_entries(lines, w);
    TrilinosWrappers::SparseMatrix A;
    make_matrix(A, a, identity);
    LineJacobi jacobi;
    jacobi.initialize(A, lines);
    EXPECT_EQ(jacobi.bandwidth(), w);
    // kappa(B) <= max (a_ii + r_i) / min (a_ii - r_i), r_i the sum of |B_ij| off the diagonal
    std::vector<double> r(n, 0.0);
    for (const auto &[ij, v] : a)
      if (ij.first != ij.second && same_line(lines, ij.first, ij.second))
        r[ij.first] += std::abs(v);
    double top = 0, bottom = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < n; ++i)
    {
      top = std::max(top, a.at({i, i}) + r[i]);
      bottom = std::min(bottom, a.at({i, i}) - r[i]);
    }
    const double kappa = top / bottom, tolerance = kappa * (4 * w + 8) * u;
    // b = B x for a given x (B: the line blocks only; the entries between lines left out)
    std::vector<double> x(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = std::cos(0.37 * i + 0.1) + 0.5;
    const IndexSet all = complete_index_set(n);
    TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), y(b);
    for (const auto &[ij, v] : a)
      if (same_line(lines, ij.first, ij.second))
        b.begin()[ij.first] += v * x[ij.second];
    jacobi.vmult(y, b);
    double error = 0, norm = 0;
    for (unsigned int i = 0; i < n; ++i)
    {
      error = std::max(error, std::abs(y.begin()[i] - x[i]));
      norm = std::max(norm, std::abs(x[i]));
    }
    std::cout << "half bandwidth " << w << ": kappa(B) <= " << kappa << ", error " << error / norm
              << " (bound " << tolerance << ")\n";
    EXPECT_LE(error / norm, tolerance) << "half bandwidth " << w;
  }
}

TEST(LineJacobi, GatherIntoLineOrderIsThePermutedSolve)
{
  const RadialLines by_lines = lines_in_order();
  const unsigned int n = by_lines.size();
  // another numbering of the same dofs: number[p] is the dof at line position p
  std::vector<unsigned int> identity(n), number(n);
  std::iota(identity.begin(), identity.end(), 0u);
  number = identity;
  std::shuffle(number.begin(), number.end(), std::mt19937(5));
  const RadialLines permuted = sealfe::testing::permuted_lines(by_lines, number);
  for (unsigned int p = 0; p < n; ++p)
    ASSERT_EQ(permuted.index(p), number[p]);
  const IndexSet all = complete_index_set(n);
  for (const unsigned int w : {1u, 2u, 3u, 4u})
  {
    const Entries a = make_entries(by_lines, w);
    TrilinosWrappers::SparseMatrix A, P;
    make_matrix(A, a, identity);
    make_matrix(P, a, number);
    LineJacobi on_lines, on_permuted;
    on_lines.initialize(A, by_lines);
    on_permuted.initialize(P, permuted);
    TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(b), bp(b), xp(b);
    for (unsigned int p = 0; p < n; ++p)
    {
      b.begin()[p] = std::sin(0.61 * p + 0.2);
      bp.begin()[number[p]] = b.begin()[p];
    }
    on_lines.vmult(x, b);
    on_permuted.vmult(xp, bp);
    unsigned int differences = 0;
    for (unsigned int p = 0; p < n; ++p)
      differences += xp.begin()[number[p]] != x.begin()[p];
    EXPECT_EQ(differences, 0u) << "half bandwidth " << w;
  }
}

TEST(LineJacobi, InterleavedLinesAreSolvedAsAlone)
{
  // groups of 4 lines of one length (lines 0-3, 4-7, 10-13), lines left over one at a time (8;
  // 9, shorter than the band at w = 4)
  const RadialLines lines = lines_in_order({8, 8, 8, 8, 8, 8, 8, 8, 8, 3, 8, 8, 8, 8});
  const unsigned int n = lines.size(), n_lines = lines.start.size() - 1;
  std::vector<unsigned int> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  const IndexSet all = complete_index_set(n);
  for (const unsigned int w : {1u, 2u, 3u, 4u})
  {
    const Entries a = make_entries(lines, w);
    TrilinosWrappers::SparseMatrix A;
    make_matrix(A, a, identity);
    LineJacobi jacobi;
    jacobi.initialize(A, lines);
    TrilinosWrappers::MPI::Vector b(all, MPI_COMM_SELF), x(b);
    for (unsigned int p = 0; p < n; ++p)
      b.begin()[p] = std::sin(0.61 * p + 0.2);
    jacobi.vmult(x, b);
    unsigned int differences = 0;
    for (unsigned int k = 0; k < n_lines; ++k)
    {
      const unsigned int first = lines.start[k], m = lines.start[k + 1] - first;
      // line k's block alone: its entries shifted to 0 .. m-1
      Entries block;
      for (const auto &[ij, v] : a)
        if (ij.first >= first && ij.first < first + m && ij.second >= first &&
            ij.second < first + m)
          block[{ij.first - first, ij.second - first}] = v;
      RadialLines one_line;
      one_line.start = {0, m};
      one_line.order.resize(m);
      std::vector<unsigned int> local(m);
      std::iota(local.begin(), local.end(), 0u);
      TrilinosWrappers::SparseMatrix B;
      make_matrix(B, block, local);
      LineJacobi alone;
      alone.initialize(B, one_line);
      const IndexSet line_set = complete_index_set(m);
      TrilinosWrappers::MPI::Vector bk(line_set, MPI_COMM_SELF), xk(bk);
      for (unsigned int q = 0; q < m; ++q)
        bk.begin()[q] = b.begin()[first + q];
      alone.vmult(xk, bk);
      for (unsigned int q = 0; q < m; ++q)
        differences += xk.begin()[q] != x.begin()[first + q];
    }
    EXPECT_EQ(differences, 0u) << "half bandwidth " << w;
  }
}
