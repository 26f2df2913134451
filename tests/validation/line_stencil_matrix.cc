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
// would leave u_s sum |A_ij| there, ~1e9 times the double term; the test would fail). For random
// x the float term is reached within a factor 10 (checked: the encoding is not exact by chance).
// Entries that do not fit (a coupling 4 lines or 4 positions away) put their lines in the
// remainder, in double: those rows meet the double term alone. On 2 ranks the rows are split in
// the middle of a line: the lines at the cut hold columns of the other rank (remainder), the
// others the stencil.
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
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
using Entries = std::map<std::pair<unsigned int, unsigned int>, double>;

const std::vector<unsigned int> lengths = {9, 7, 12, 8, 10, 5, 11, 9, 6, 12, 8, 10,
                                           7, 9, 11, 6, 12, 8, 10, 9, 5, 11, 7, 8};

std::vector<unsigned int> global_line_start()
{
  std::vector<unsigned int> start = {0};
  for (const unsigned int m : lengths)
    start.push_back(start.back() + m);
  return start;
}

/// The symmetric matrix of the header with couplings up to w lines and positions away, diagonally
/// dominant; `misfits`: couplings 4 lines and 4 positions away as well (lines 3 and 7, line 8).
Entries make_entries(const int w, const bool misfits)
{
  const auto start = global_line_start();
  const unsigned int n_lines = lengths.size();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(0.1, 1.0);
  Entries a;
  auto couple = [&](const unsigned int i, const unsigned int j)
  {
    const double v = -value(random) * M_PI / 3; // not a float
    a[{i, j}] = v;
    a[{j, i}] = v;
  };
  for (unsigned int k = 0; k < n_lines; ++k)
    for (unsigned int q = 0; q < lengths[k]; ++q)
      for (int b = 0; b <= w; ++b)
      {
        const unsigned int kb = (k + b) % n_lines;
        for (int d = -w; d <= w; ++d)
        {
          const int p = int(q) + d;
          if ((b == 0 && d <= 0) || p < 0 || p >= int(lengths[kb]) || value(random) < 0.3)
            continue;
          couple(start[k] + q, start[kb] + p);
        }
      }
  if (misfits)
  {
    couple(start[3] + 2, start[7] + 2); // 4 lines away
    couple(start[8] + 0, start[8] + 4); // 4 positions away
  }
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
  std::vector<unsigned int> local_line_start;
};

/// The rows split evenly over the ranks (in the middle of a line on 2 ranks); the owned part of
/// each global line is one local line.
void make_case(const Entries &entries, Case &c)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm),
                     rank = Utilities::MPI::this_mpi_process(comm);
  const auto start = global_line_start();
  const unsigned int n = start.back(), first = n * rank / n_ranks, last = n * (rank + 1) / n_ranks;
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
  for (unsigned int k = 0; k + 1 < start.size(); ++k)
  {
    const unsigned int b = std::max(first, start[k]), e = std::min(last, start[k + 1]);
    if (b < e)
      c.local_line_start.push_back(e - first);
  }
}

/// x_j known on every rank (a function of the global index j), so the bound needs no ghosts.
double x_at(const unsigned int j, const bool constant)
{
  return constant ? 0.7 : std::sin(1.3 * j + 0.4) + 0.25 * std::cos(0.37 * j * j);
}

/// The largest |Ã x - A x|_i over the bound of the header (float term and double term), for
/// constant or varying x; `stencil_rows_only`: rows held in the stencil (or in the remainder).
struct Result
{
  double ratio_to_bound = 0; // max |Ã x - A x| / bound
  double ratio_to_float = 0; // max |Ã x - A x| / u_s sum |A_ij| |x_j - x_i|
  unsigned int stencil_rows = 0;
};

Result check(const Entries &entries, const bool constant)
{
  Case c;
  make_case(entries, c);
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
  }
  r.ratio_to_bound = Utilities::MPI::max(r.ratio_to_bound, MPI_COMM_WORLD);
  r.ratio_to_float = Utilities::MPI::max(r.ratio_to_float, MPI_COMM_WORLD);
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
    const Result r = check(make_entries(w, false), false);
    EXPECT_LE(r.ratio_to_bound, 1.0);
    EXPECT_GE(r.ratio_to_float, 0.1); // the values are rounded: a float term reached
    const unsigned int n = global_line_start().back();
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
    const Result r = check(make_entries(w, false), true);
    EXPECT_LE(r.ratio_to_bound, 1.0) << w; // the double term alone: a constant's product is A's
  }
}

TEST(LineStencilMatrix, EntriesThatDoNotFitKeepTheirLinesInDouble)
{
  const Entries entries = make_entries(2, true);
  const Result r = check(entries, false);
  EXPECT_LE(r.ratio_to_bound, 1.0);
  if (n_ranks() == 1)
  {
    // lines 3 and 7 (4 lines apart) and line 8 (4 positions apart) in the remainder
    const unsigned int n = global_line_start().back();
    EXPECT_EQ(r.stencil_rows, n - lengths[3] - lengths[7] - lengths[8]);
  }
  const Result constant = check(entries, true);
  EXPECT_LE(constant.ratio_to_bound, 1.0);
}
