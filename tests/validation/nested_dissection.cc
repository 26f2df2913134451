// The nested-dissection order of a grid of nodes (numerics::nested_dissection_order) against the
// theory of George (1973), "Nested dissection of a regular finite element mesh", SIAM J. Numer.
// Anal. 10: on the n x n nodes of a mesh of bilinear elements (each node coupled to the 8 around
// it, stride 1) the Cholesky factor has 31/4 n^2 log2 n + O(n^2) entries below the diagonal and
// costs 829/84 n^3 + O(n^2 log n) multiplications; a band (row-by-row) order costs O(n^4).
// Counted here by a symbolic factorisation (elimination tree, column structures merged): for
// n = 2^p - 1 the dissection halves exactly, as in George's, so counts at n = 31 ... 255 fitted
// with the next terms of the expansions give George's leading coefficients, the two-term fits
// miss them by what an n log2 n remainder predicts, and the band order's cost grows with order
// 4. A ring (periodic columns) and cells of degree 2 and 3 give permutations whose separators
// separate: the factor of the ring's pattern has no entry that the dissection should have kept
// apart.
#include <sealfe/numerics/nested_dissection.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <utility>
#include <vector>

using namespace sealfe::numerics;

namespace
{
/// Entries below the diagonal of the Cholesky factor and multiplications, sum over columns
/// of c (c + 3) / 2 (George's count), of the symmetric pattern where every two positions of one
/// cell are coupled, eliminated in `order`.
struct Fill
{
  double entries = 0, multiplications = 0;
};

Fill symbolic_cholesky(const NodeGrid &grid, const std::vector<unsigned int> &order)
{
  const std::size_t N = std::size_t(grid.rows) * grid.columns;
  std::vector<unsigned int> step(N);
  for (std::size_t k = 0; k < N; ++k)
    step[order[k]] = k;
  // the neighbours of every node eliminated later, as steps
  const int reach = int(grid.stride);
  std::vector<std::vector<unsigned int>> structure(N);
  std::vector<long> parent(N, -1);
  std::vector<std::vector<unsigned int>> children(N);
  Fill fill;
  for (std::size_t k = 0; k < N; ++k)
  {
    const unsigned int a = order[k];
    const int i = a / grid.columns, j = a % grid.columns;
    std::vector<unsigned int> column;
    for (int di = -reach; di <= reach; ++di)
      for (int dj = -reach; dj <= reach; ++dj)
      {
        const int ii = i + di;
        int jj = j + dj;
        if (ii < 0 || ii >= int(grid.rows))
          continue;
        if (grid.periodic_columns)
          jj = (jj + int(grid.columns)) % int(grid.columns);
        else if (jj < 0 || jj >= int(grid.columns))
          continue;
        const unsigned int b = ii * grid.columns + jj;
        if (within_one_cell(grid, a, b) && step[b] > k)
          column.push_back(step[b]);
      }
    for (const unsigned int c : children[k])
      for (const unsigned int s : structure[c])
        if (s > k)
          column.push_back(s);
    std::sort(column.begin(), column.end());
    column.erase(std::unique(column.begin(), column.end()), column.end());
    for (const unsigned int c : children[k])
      std::vector<unsigned int>().swap(structure[c]);
    const double c = column.size();
    fill.entries += c;
    fill.multiplications += c * (c + 3) / 2;
    if (!column.empty())
      children[column.front()].push_back(k);
    structure[k] = std::move(column);
  }
  return fill;
}

std::vector<unsigned int> row_order(const NodeGrid &grid)
{
  std::vector<unsigned int> order(std::size_t(grid.rows) * grid.columns);
  for (std::size_t k = 0; k < order.size(); ++k)
    order[k] = k;
  return order;
}

bool is_permutation(const std::vector<unsigned int> &order, const std::size_t N)
{
  std::vector<bool> seen(N, false);
  for (const unsigned int p : order)
  {
    if (p >= N || seen[p])
      return false;
    seen[p] = true;
  }
  return order.size() == N;
}

/// x solving the 3 x 3 system M x = y (Gaussian elimination with partial pivoting)
std::array<double, 3> solve3(std::array<std::array<double, 4>, 3> M)
{
  for (int i = 0; i < 3; ++i)
  {
    int p = i;
    for (int r = i + 1; r < 3; ++r)
      if (std::abs(M[r][i]) > std::abs(M[p][i]))
        p = r;
    std::swap(M[i], M[p]);
    for (int r = 0; r < 3; ++r)
      if (r != i)
      {
        const double f = M[r][i] / M[i][i];
        for (int c = i; c < 4; ++c)
          M[r][c] -= f * M[i][c];
      }
  }
  return {{M[0][3] / M[0][0], M[1][3] / M[1][1], M[2][3] / M[2][2]}};
}
} // namespace

TEST(NestedDissection, BilinearMeshFollowsGeorgesLeadingTerms)
{
  // n = 2^p - 1 nodes a side, so that every region halves exactly as in George's dissection
  const std::array<unsigned int, 4> sizes = {{31, 63, 127, 255}};
  std::array<Fill, 4> fill;
  for (std::size_t s = 0; s < sizes.size(); ++s)
  {
    const unsigned int n = sizes[s];
    const NodeGrid grid{n, n, 1, false};
    const auto order = nested_dissection_order(grid);
    ASSERT_TRUE(is_permutation(order, std::size_t(n) * n));
    fill[s] = symbolic_cholesky(grid, order);
    std::cout << "n = " << n << ": entries " << fill[s].entries << ", multiplications "
              << fill[s].multiplications << "\n";
  }
  const auto lg = [](const double n) { return std::log2(n); };
  // George's expansions with the next term of each: entries = a n^2 log2 n + b n^2 + c n log2 n
  // (the separators' borders) and multiplications = a n^3 + b n^2 log2 n + c n^2, fitted exactly
  // to three sizes. The terms left out (O(n) entries, a factor log2 n below the last one kept;
  // O(n log2 n) multiplications, a factor n / log2 n below it) move the fitted a by their size
  // relative to a's term, n log2 n times smaller for the entries (0.05 % at n = 255) and more for
  // the multiplications, magnified by the fit's differences over the sizes' log2 spacing of 1
  // (about the fitted b and c over a, 3): under 1 % from n = 63 on, and less on larger sizes (16
  // nodes a leaf instead of George's single nodes only changes b: a leaf of the same shape at
  // every size is O(n^2) entries and O(n^2) operations).
  std::array<double, 2> entries_lead{}, multiplications_lead{};
  for (int t = 0; t < 2; ++t)
  {
    std::array<std::array<double, 4>, 3> E{}, M{};
    for (int i = 0; i < 3; ++i)
    {
      const double n = sizes[t + i];
      E[i] = {{lg(n), 1.0, lg(n) / n, fill[t + i].entries / (n * n)}};
      M[i] = {{1.0, lg(n) / n, 1.0 / n, fill[t + i].multiplications / (n * n * n)}};
    }
    entries_lead[t] = solve3(E)[0];
    multiplications_lead[t] = solve3(M)[0];
    std::cout << "fit to n = " << sizes[t] << ", " << sizes[t + 1] << ", " << sizes[t + 2]
              << ": entries " << entries_lead[t] << " n^2 log2 n (31/4 = 7.75), multiplications "
              << multiplications_lead[t] << " n^3 (829/84 = " << 829.0 / 84 << ")\n";
  }
  EXPECT_NEAR(entries_lead[1] / (31.0 / 4), 1.0, 0.01);
  EXPECT_NEAR(multiplications_lead[1] / (829.0 / 84), 1.0, 0.01);
  // and closer to George's value on the larger sizes
  EXPECT_LT(std::abs(entries_lead[1] / (31.0 / 4) - 1), std::abs(entries_lead[0] / (31.0 / 4) - 1));

  // The n log2 n remainder, seen on its own: a two-term fit a n^2 log2 n + b n^2 to sizes n and
  // m = 2n + 1 misses 31/4 by c (log2 m / m - log2 n / n) / (log2 m - log2 n) / (31/4), so the
  // misses of two successive pairs stand in the ratio that expression gives whatever c is (about
  // (1 + 1 / log2 n) / 2). The O(n) term left out changes the ratio by about its share of the
  // remainder, 1 / log2 n of it times the ratio's own size (0.6 / 7 = 0.09 at n = 127, less the
  // part the two pairs share): within 0.05.
  const auto two_term_miss = [&](const int s)
  {
    const double n = sizes[s], m = sizes[s + 1];
    const double lead =
        (fill[s + 1].entries / (m * m) - fill[s].entries / (n * n)) / (lg(m) - lg(n));
    const double predicted = (lg(m) / m - lg(n) / n) / (lg(m) - lg(n));
    return std::pair{lead / (31.0 / 4) - 1, predicted};
  };
  // (pairs 63, 127 and 127, 255)
  const auto [miss_small, shape_small] = two_term_miss(1);
  const auto [miss_large, shape_large] = two_term_miss(2);
  std::cout << "two-term misses " << miss_small << ", " << miss_large << ": ratio "
            << miss_large / miss_small << " (n log2 n remainder: " << shape_large / shape_small
            << ")\n";
  EXPECT_NEAR(miss_large / miss_small, shape_large / shape_small, 0.05);
  const double order_multiplications =
      std::log(fill[3].multiplications / fill[2].multiplications) / std::log(255.0 / 127.0);
  std::cout << "observed order of the multiplications " << order_multiplications << "\n";
  EXPECT_NEAR(order_multiplications, 3.0, 0.15);
}

TEST(NestedDissection, BandOrderCostsAnOrderMore)
{
  Fill band[2];
  const unsigned int sizes[2] = {31, 63};
  for (int s = 0; s < 2; ++s)
  {
    const NodeGrid grid{sizes[s], sizes[s], 1, false};
    band[s] = symbolic_cholesky(grid, row_order(grid));
  }
  const double order =
      std::log(band[1].multiplications / band[0].multiplications) / std::log(63.0 / 31.0);
  EXPECT_NEAR(order, 4.0, 0.2);
  const NodeGrid grid{63, 63, 1, false};
  EXPECT_LT(symbolic_cholesky(grid, nested_dissection_order(grid)).multiplications,
            band[1].multiplications / 3);
}

TEST(NestedDissection, RingsOfHigherDegreeCellsArePermutedAndSeparated)
{
  for (const NodeGrid grid : {NodeGrid{33, 128, 2, true}, NodeGrid{31, 96, 3, true},
                              NodeGrid{9, 16, 2, false}, NodeGrid{3, 4, 2, true}})
  {
    const auto order = nested_dissection_order(grid);
    const std::size_t N = std::size_t(grid.rows) * grid.columns;
    ASSERT_TRUE(is_permutation(order, N)) << grid.rows << " x " << grid.columns;
    // A separator that did not separate would leave the two halves coupled through the
    // elimination: the factor would fill up towards the band order's. The dissection's factor
    // of a ring must stay well below the band order's (a ring's band order wraps: its factor
    // holds the first columns in every row, order n^2 columns x rows).
    if (N > 1000)
    {
      EXPECT_LT(symbolic_cholesky(grid, order).entries,
                0.5 * symbolic_cholesky(grid, row_order(grid)).entries)
          << grid.rows << " x " << grid.columns;
    }
  }
  // positions of one cell, and not: stride 2, ring of 8 columns
  const NodeGrid ring{5, 8, 2, true};
  EXPECT_TRUE(within_one_cell(ring, 0 * 8 + 7, 2 * 8 + 0)); // across column 0, one cell
  EXPECT_TRUE(within_one_cell(ring, 1 * 8 + 6, 0 * 8 + 0));
  EXPECT_FALSE(within_one_cell(ring, 1 * 8 + 5, 1 * 8 + 7)); // column 6 lies between
  EXPECT_FALSE(within_one_cell(ring, 1 * 8 + 1, 3 * 8 + 1)); // row 2 lies between
  EXPECT_TRUE(within_one_cell(ring, 2 * 8 + 2, 4 * 8 + 4));
  EXPECT_THROW(nested_dissection_order(NodeGrid{5, 9, 2, true}), std::invalid_argument);
}
