// LineStencilMatrix (include/sealfe/film/line_stencil_matrix.h), the multigrid smoother's
// single-precision products on the finest level, against the Trilinos matrix it encodes: a
// symmetric matrix numbered by 24 lines of 5-12 dofs (lengths that differ, so positions near a
// line's ends have no partner on the next line), each dof coupled to the dofs within w positions
// on its own line and on the lines up to w away (w = 2, 3: Q2 and Q3 on the annulus), the last
// lines coupled round to the first.
//
// Bound, from the rounding alone. Ã_ij = fl32(A_ij) = A_ij (1 + delta), |delta| <= u_s = 2^-24,
// and Ã_ii = A_ii - sum_j (Ã_ij - A_ij), so (Ã x - A x)_i = sum_{j != i} (Ã_ij - A_ij)(x_j - x_i)
// exactly, and |.| <= u_s sum_{j != i} |A_ij| |x_j - x_i|. Both products are then formed in
// double, each a sum of at most m + 2 terms (m entries in the row, the diagonal's correction
// summed over the row): a further gamma_{m+2} sum_j |A_ij| |x_j| each, and the correction's sum
// gamma_m |x_i| sum_j |A_ij| (Higham 2002, 3.1). So
//   |Ã x - A x|_i <= u_s sum_{j != i} |A_ij| |x_j - x_i| + 4 (m + 2) u sum_j |A_ij| (|x_j| +
//   |x_i|).
// For a constant x the first term vanishes: the row sums are A's (a plain rounding of the values
// would leave up to u_s sum |A_ij| |x| there, u_s / (8 (m + 2) u) = 2^29 / (8 (m + 2)) ~ 1e6
// times the double term for m = 25-49; the test would fail). For random
// x the float term is reached within a factor 10 (checked: the encoding is not exact by chance).
// Entries that do not fit (a coupling 4 lines or 4 positions away) put their lines in the
// remainder, in double: those rows meet the double term alone. On 2 ranks the rows are split in
// the middle of a line: the lines at the cut hold columns of the other rank (remainder), the
// others the stencil. Which lines are held in the stencil is checked rank by rank against the
// rule of the header (every nonzero entry of the line's rows owned and within 3 lines and 3
// positions, the lines taken as a ring), on rings of 2-5 lines too (where line k + a and
// k + a - n are one line), with lines of no dofs, explicit zeros far away, and a remainder on
// one rank only (the remainder matrix is made collectively).
#include <sealfe/film/line_stencil_matrix.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
using Entries = std::map<std::pair<unsigned int, unsigned int>, double>;

/// The dofs numbered line after line (global line k: `lengths[k]` dofs); `split_line`: on 2
/// ranks, the first line of rank 1 (-1: the rows split evenly, in the middle of a line);
/// `empty_before`: local lines of no dofs inserted before these local line numbers on every rank
/// (a number may repeat; one past the rank's last line or more: at the end).
struct Layout
{
  std::vector<unsigned int> lengths;
  int split_line = -1;
  std::vector<unsigned int> empty_before;

  std::vector<unsigned int> line_start() const
  {
    std::vector<unsigned int> start = {0};
    for (const unsigned int m : lengths)
      start.push_back(start.back() + m);
    return start;
  }
  unsigned int size() const { return line_start().back(); }
};

const Layout ring24 = {
    {9, 7, 12, 8, 10, 5, 11, 9, 6, 12, 8, 10, 7, 9, 11, 6, 12, 8, 10, 9, 5, 11, 7, 8}};

/// A coupling that does not fit (4 lines or 4 positions away): global line and position of both.
struct Misfit
{
  unsigned int line_i, position_i, line_j, position_j;
};

/// The symmetric matrix of the header with couplings up to w lines and positions away, diagonally
/// dominant. `block_lines` > 0: lines coupled only within consecutive blocks of that many lines
/// (no ring); 0: over all lines, the last round to the first. `misfits`: couplings added.
Entries make_entries(const Layout &layout, const int w, const unsigned int block_lines = 0,
                     const std::vector<Misfit> &misfits = {})
{
  const auto start = layout.line_start();
  const unsigned int n_lines = layout.lengths.size();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(0.1, 1.0);
  Entries a;
  auto couple = [&](const unsigned int i, const unsigned int j)
  {
    const double v = -value(random) * M_PI / 3; // not a float
    if (i == j)
      return; // a ring shorter than the couplings: line k + b is line k
    a[{i, j}] = v;
    a[{j, i}] = v;
  };
  for (unsigned int k = 0; k < n_lines; ++k)
    for (unsigned int q = 0; q < layout.lengths[k]; ++q)
      for (int b = 0; b <= w; ++b)
      {
        if (block_lines > 0 && (k % block_lines) + b >= block_lines)
          continue;
        const unsigned int kb = (k + b) % n_lines;
        for (int d = -w; d <= w; ++d)
        {
          const int p = int(q) + d;
          if ((b == 0 && d <= 0) || p < 0 || p >= int(layout.lengths[kb]) || value(random) < 0.3)
            continue;
          couple(start[k] + q, start[kb] + p);
        }
      }
  for (const Misfit &m : misfits)
    couple(start[m.line_i] + m.position_i, start[m.line_j] + m.position_j);
  std::map<unsigned int, double> row_sum;
  for (const auto &[ij, v] : a)
    row_sum[ij.first] += std::abs(v);
  for (unsigned int i = 0; i < start.back(); ++i)
    a[{i, i}] = row_sum[i] + value(random);
  return a;
}

struct Case
{
  TrilinosWrappers::SparseMatrix A;
  IndexSet owned;
  unsigned int first = 0; // the first owned row
  std::vector<unsigned int> local_line_start;
};

/// The rows split over the ranks (`layout.split_line` or evenly); the owned part of each global
/// line is one local line, with the empty lines of the layout inserted.
void make_case(const Entries &entries, const Layout &layout, Case &c)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm),
                     rank = Utilities::MPI::this_mpi_process(comm);
  const auto start = layout.line_start();
  const unsigned int n = start.back();
  unsigned int first = n * rank / n_ranks, last = n * (rank + 1) / n_ranks;
  if (layout.split_line >= 0 && n_ranks == 2)
  {
    first = rank == 0 ? 0 : start[layout.split_line];
    last = rank == 0 ? start[layout.split_line] : n;
  }
  c.first = first;
  c.owned = IndexSet(n);
  c.owned.add_range(first, last);
  TrilinosWrappers::SparsityPattern pattern(c.owned, comm);
  for (const auto &[ij, v] : entries)
    if (c.owned.is_element(ij.first))
      pattern.add(ij.first, ij.second);
  pattern.compress();
  c.A.reinit(pattern);
  for (const auto &[ij, v] : entries)
    if (c.owned.is_element(ij.first))
      c.A.set(ij.first, ij.second, v);
  c.A.compress(VectorOperation::insert);
  c.local_line_start = {0};
  unsigned int local_line = 0;
  auto insert_empty_lines = [&](const bool at_end)
  {
    for (const unsigned int l : layout.empty_before)
      if (l == local_line || (at_end && l > local_line))
        c.local_line_start.push_back(c.local_line_start.back());
  };
  for (unsigned int k = 0; k + 1 < start.size(); ++k)
  {
    const unsigned int b = std::max(first, start[k]), e = std::min(last, start[k + 1]);
    if (b < e)
    {
      insert_empty_lines(false);
      c.local_line_start.push_back(e - first);
      ++local_line;
    }
  }
  insert_empty_lines(true);
}

/// x_j known on every rank (a function of the global index j), so the bound needs no ghosts.
double x_at(const unsigned int j, const bool constant)
{
  return constant ? 0.7 : std::sin(1.3 * j + 0.4) + 0.25 * std::cos(0.37 * j * j);
}

/// Whether each owned row's line should be held in the stencil, by the rule of the header, from
/// the entries and the local lines alone: every nonzero entry A_ij, j != i, of the line's rows
/// owned, on a local line within 3 of the row's round the ring of local lines and within 3
/// positions of it.
std::vector<bool> stencil_rows_by_the_rule(const Entries &entries, const Case &c)
{
  const std::vector<unsigned int> &start = c.local_line_start;
  const unsigned int n_lines = start.size() - 1, n_owned = start.back();
  auto line_of = [&](const unsigned int local) // the non-empty line holding a local index
  { return unsigned(std::upper_bound(start.begin(), start.end(), local) - start.begin()) - 1; };
  std::vector<bool> line_fits(n_lines, true);
  for (const auto &[ij, v] : entries)
  {
    const auto [i, j] = ij;
    if (!c.owned.is_element(i) || i == j || v == 0)
      continue;
    const unsigned int ki = line_of(i - c.first);
    bool fits = false;
    if (c.owned.is_element(j))
    {
      const unsigned int kj = line_of(j - c.first);
      const int d = int(j - c.first - start[kj]) - int(i - c.first - start[ki]);
      for (int a = -3; a <= 3 && !fits; ++a)
        fits = (int(ki) + a + 4 * int(n_lines)) % int(n_lines) == int(kj) && std::abs(d) <= 3;
    }
    if (!fits)
      line_fits[ki] = false;
  }
  std::vector<bool> in_stencil(n_owned);
  for (unsigned int r = 0; r < n_owned; ++r)
    in_stencil[r] = line_fits[line_of(r)];
  return in_stencil;
}

/// |Ã x - A x|_i against the bound of the header (float term and double term), for constant or
/// varying x, and the owned rows held in the stencil against the rule.
struct Result
{
  double ratio_to_bound = 0; // max |Ã x - A x| / bound
  double ratio_to_float = 0; // max |Ã x - A x| / u_s sum |A_ij| |x_j - x_i|
  unsigned int stencil_rows = 0;
  unsigned int local_stencil_rows = 0, local_stencil_rows_by_the_rule = 0;
  std::vector<double> product;     // Ã x on the owned rows
  std::vector<double> double_term; // the bound's double term on the owned rows
  std::vector<bool> in_stencil;    // by the rule
};

Result check(const Entries &entries, const Layout &layout, const bool constant)
{
  Case c;
  make_case(entries, layout, c);
  LineStencilMatrix stencil;
  stencil.initialize(c.A, c.local_line_start);
  TrilinosWrappers::MPI::Vector x(c.owned, MPI_COMM_WORLD), exact(x), approximate(x);
  for (const auto j : c.owned)
    x[j] = x_at(j, constant);
  x.compress(VectorOperation::insert);
  c.A.vmult(exact, x);
  stencil.vmult(approximate, x);
  const double u = std::numeric_limits<double>::epsilon() / 2, us = std::ldexp(1.0, -24);
  std::map<unsigned int, std::vector<std::pair<unsigned int, double>>> rows;
  for (const auto &[ij, v] : entries)
    rows[ij.first].emplace_back(ij.second, v);
  Result r;
  r.in_stencil = stencil_rows_by_the_rule(entries, c);
  for (const auto i : c.owned)
  {
    double float_term = 0, double_term = 0;
    const double xi = x_at(i, constant);
    for (const auto &[j, v] : rows[i])
    {
      if (j != i)
        float_term += us * std::abs(v) * std::abs(x_at(j, constant) - xi);
      double_term += std::abs(v) * (std::abs(x_at(j, constant)) + std::abs(xi));
    }
    double_term *= 4 * (rows[i].size() + 2) * u;
    const double difference = std::abs(approximate[i] - exact[i]);
    r.ratio_to_bound = std::max(r.ratio_to_bound, difference / (float_term + double_term));
    if (float_term > 0)
      r.ratio_to_float = std::max(r.ratio_to_float, difference / float_term);
    r.product.push_back(approximate[i]);
    r.double_term.push_back(double_term);
    r.local_stencil_rows_by_the_rule += r.in_stencil[i - c.first];
  }
  r.ratio_to_bound = Utilities::MPI::max(r.ratio_to_bound, MPI_COMM_WORLD);
  r.ratio_to_float = Utilities::MPI::max(r.ratio_to_float, MPI_COMM_WORLD);
  r.local_stencil_rows = stencil.n_stencil_rows();
  r.stencil_rows = Utilities::MPI::sum(stencil.n_stencil_rows(), MPI_COMM_WORLD);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    std::cout << "  |Ã x - A x| / bound <= " << r.ratio_to_bound
              << ", / float term <= " << r.ratio_to_float << ", " << r.stencil_rows
              << " rows in the stencil\n";
  return r;
}

unsigned int n_ranks()
{
  return Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
}
} // namespace

TEST(LineStencilMatrix, ProductWithinTheRoundingOfItsValues)
{
  for (const int w : {2, 3})
  {
    SCOPED_TRACE("couplings up to " + std::to_string(w) + " lines and positions away");
    const Result r = check(make_entries(ring24, w), ring24, false);
    EXPECT_LE(r.ratio_to_bound, 1.0);
    EXPECT_GE(r.ratio_to_float, 0.1); // the values are rounded: a float term reached
    EXPECT_EQ(r.local_stencil_rows, r.local_stencil_rows_by_the_rule);
    const unsigned int n = ring24.size();
    if (n_ranks() == 1)
      EXPECT_EQ(r.stencil_rows, n); // every row fits, the lines round the ring included
    else
      EXPECT_LT(r.stencil_rows, n); // the cut lines see the other rank's columns: remainder
    EXPECT_GT(r.stencil_rows, 0u);
  }
}

TEST(LineStencilMatrix, RowSumsAreTheMatrixs)
{
  for (const int w : {2, 3})
  {
    const Result r = check(make_entries(ring24, w), ring24, true);
    EXPECT_LE(r.ratio_to_bound, 1.0) << w; // the double term alone: a constant's product is A's
  }
}

TEST(LineStencilMatrix, EntriesThatDoNotFitKeepTheirLinesInDouble)
{
  // lines 3 and 7 (4 lines apart) and line 8 (4 positions apart)
  const Entries entries = make_entries(ring24, 2, 0, {{3, 2, 7, 2}, {8, 0, 8, 4}});
  const Result r = check(entries, ring24, false);
  EXPECT_LE(r.ratio_to_bound, 1.0);
  EXPECT_EQ(r.local_stencil_rows, r.local_stencil_rows_by_the_rule);
  if (n_ranks() == 1)
  {
    const auto &m = ring24.lengths;
    EXPECT_EQ(r.stencil_rows, ring24.size() - m[3] - m[7] - m[8]);
  }
  const Result constant = check(entries, ring24, true);
  EXPECT_LE(constant.ratio_to_bound, 1.0);
}

// Rings of 2-5 lines, couplings up to w lines away: line k + a and line k + a - n are one line,
// and the product reads it for each slot it is reached by; every row fits (one rank).
TEST(LineStencilMatrix, RingsOfFewLines)
{
  const std::vector<std::pair<Layout, int>> rings = {
      {{{9, 7}}, 2}, {{{9, 7, 12}}, 3}, {{{9, 7, 12, 8}}, 2}, {{{9, 7, 12, 8, 10}}, 3}};
  for (const auto &[layout, w] : rings)
  {
    SCOPED_TRACE(std::to_string(layout.lengths.size()) + " lines, couplings up to " +
                 std::to_string(w) + " away");
    const Entries entries = make_entries(layout, w);
    for (const bool constant : {false, true})
    {
      const Result r = check(entries, layout, constant);
      EXPECT_LE(r.ratio_to_bound, 1.0);
      EXPECT_EQ(r.local_stencil_rows, r.local_stencil_rows_by_the_rule);
      if (n_ranks() == 1)
      {
        EXPECT_EQ(r.stencil_rows, layout.size());
      }
    }
  }
}

// Two blocks of 4 lines, not coupled to each other, rank 0 holding the first and rank 1 the
// second: a misfit on line 1 puts a remainder on rank 0 only (made collectively: a rank without
// one must still take part).
TEST(LineStencilMatrix, RemainderOnOneRankOnly)
{
  Layout layout = {{9, 7, 12, 8, 10, 5, 11, 9}};
  layout.split_line = 4;
  const Entries entries = make_entries(layout, 2, 4, {{1, 0, 1, 4}});
  const Result r = check(entries, layout, false);
  EXPECT_LE(r.ratio_to_bound, 1.0);
  EXPECT_EQ(r.local_stencil_rows, r.local_stencil_rows_by_the_rule);
  if (n_ranks() == 1)
  {
    EXPECT_EQ(r.stencil_rows, 71u - 7u);
  }
  else if (n_ranks() == 2)
  {
    EXPECT_EQ(r.local_stencil_rows, Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0
                                        ? 36u - 7u
                                        : 35u); // every line of rank 1 fits
  }
}

// Explicit zeros in the pattern, 8 lines and 10 positions away, play no part: the lines stay in
// the stencil and the product is the one without them, to the bit (rows in the remainder: within
// the double term, their sums may be ordered otherwise). Lines of no dofs count as lines of the
// ring: inserted between two coupled lines they move them apart (w = 3: 4 lines, remainder).
TEST(LineStencilMatrix, ZeroEntriesAndEmptyLinesChangeNothingButTheRule)
{
  for (const int w : {2, 3})
  {
    SCOPED_TRACE("couplings up to " + std::to_string(w) + " lines and positions away");
    const Entries plain = make_entries(ring24, w);
    Entries with_zeros = plain;
    const auto start = ring24.line_start();
    for (const auto &[i, j] : std::vector<std::pair<unsigned int, unsigned int>>{
             {start[2] + 1, start[10] + 1}, {start[14] + 0, start[14] + 10}})
    {
      with_zeros[{i, j}] = 0.0;
      with_zeros[{j, i}] = 0.0;
    }
    const Result a = check(plain, ring24, false), b = check(with_zeros, ring24, false);
    EXPECT_EQ(b.local_stencil_rows, a.local_stencil_rows);
    EXPECT_EQ(b.local_stencil_rows, b.local_stencil_rows_by_the_rule);
    ASSERT_EQ(a.product.size(), b.product.size());
    unsigned int differences = 0;
    for (unsigned int r = 0; r < a.product.size(); ++r)
      if (a.in_stencil[r])
        differences += a.product[r] != b.product[r];
      else
        EXPECT_LE(std::abs(a.product[r] - b.product[r]), 2 * a.double_term[r]);
    EXPECT_EQ(differences, 0u);

    // one empty line in a gap moves the lines across it 1 further apart: w = 2 still fits
    // (couplings 2 lines away cross one gap at most), w = 3 does not (3 + 1); the two layouts are
    // one ring (before line 0 and after the last: one gap), inserted the two ways
    for (const std::vector<unsigned int> &empty :
         {std::vector<unsigned int>{0, 3, 5}, std::vector<unsigned int>{3, 5, 1000}})
    {
      Layout with_empty_lines = ring24;
      with_empty_lines.empty_before = empty;
      const Result e = check(plain, with_empty_lines, false);
      EXPECT_LE(e.ratio_to_bound, 1.0);
      EXPECT_EQ(e.local_stencil_rows, e.local_stencil_rows_by_the_rule);
      if (n_ranks() == 1)
      {
        if (w == 2)
          EXPECT_EQ(e.stencil_rows, ring24.size());
        else
          EXPECT_LT(e.stencil_rows, ring24.size());
      }
    }
  }
}
