// The film's kernels split over threads (deal.II's MultithreadInfo; one rank of a 2-core machine
// has two): the multigrid smoother's single-precision products (LineStencilMatrix), its line
// solves (LineJacobi, numbered by lines and gathered into line order) and the CG's and coarse
// levels' products (numerics::threaded_product), on a symmetric matrix of 480 lines of 7-9
// dofs (4 224 rows: every kernel's range is split into several grains: 16 lines, 2048 rows).
// - Each line or row is written by one thread with the operations of the serial loop, so the
//   results on one and on two threads are the same to the bit.
// - threaded_product is y_i = sum_j A_ij x_j summed in the order of the row's entries (the same
//   bits as that loop written out here), and agrees with Epetra's Multiply to the rounding of
//   two sums of m terms: |y - y_Epetra|_i <= 2 gamma_m sum_j |A_ij| |x_j| (Higham 2002, 3.1).
// - On one thread it is the same loop, unsplit: the same bits as on two.
// - A whole full-film run (the assembly's batches of cells computed on the threads and added in
//   the order of the cells, the multigrid, the CG): the loads on one and on two threads are the
//   same to the bit, on a mesh of 2 048 cells (two batches of 1 024); so are the cavitation
//   models' (JFO, Reynolds), whose cell matrices are made in batches on the threads too, and
//   whose loads are summed in chunks of 64 cells on the threads (32 chunks here). (OpenBLAS stays
//   on one thread, the test main's: its threaded sums differ at round-off.)
// - The batches (numerics::compute_in_batches_add_in_order) hand every item to `add` once, in
//   order; an exception thrown while a batch computes reaches the caller, after the batches
//   before it were added and before its own is (deal.II 9.4's Task<void>::join does not rethrow:
//   a batch's exception had been lost, its results left as they were).
#include "../line_matrices.h"

#include <sealfe/film/film_settings.h>
#include <sealfe/film/line_jacobi.h>
#include <sealfe/film/line_stencil_matrix.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/numerics/ordered_batches.h>
#include <sealfe/numerics/threaded_product.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
using sealfe::testing::Entries;
using sealfe::testing::make_entries;
using sealfe::testing::make_matrix;
using VectorType = TrilinosWrappers::MPI::Vector;

/// 480 lines of 9 dofs, every fifth of 7 (lines that differ: positions near the end of a line
/// have no partner on the next).
RadialLines lines_in_order()
{
  std::vector<unsigned int> lengths;
  for (unsigned int k = 0; k < 480; ++k)
    lengths.push_back(k % 5 == 4 ? 7 : 9);
  return sealfe::testing::lines_of_lengths(lengths);
}

std::vector<double> values_of(const VectorType &v)
{
  return {v.begin(), v.end()};
}

/// Restores deal.II's thread limit of the test main (one thread) when a test ends.
struct ThreadLimit
{
  explicit ThreadLimit(const unsigned int n) { MultithreadInfo::set_thread_limit(n); }
  ~ThreadLimit() { MultithreadInfo::set_thread_limit(1); }
};

/// The Varney & Green seal tilted to eps = 0.5 (benchmarks/reynolds_speed/case.prm), Q2 on
/// 16 x 128 cells: 2 048 cells, two batches of 1 024 (32 load chunks of 64).
FilmSettings tilted_seal()
{
  FilmSettings settings;
  settings.geometry.tilt = 0.5 * settings.geometry.clearance / settings.geometry.outer_radius;
  settings.polynomial_degree = 2;
  settings.mesh.radial_cells = 16;
  settings.mesh.circumferential_cells = 128;
  settings.estimate_error = false;
  return settings;
}

/// The loads of a run of `settings` on `threads` threads.
FilmLoads loads_on(const FilmSettings &settings, const unsigned int threads)
{
  const ThreadLimit limit(threads);
  ReynoldsSolver solver(settings, MPI_COMM_WORLD);
  return solver.run();
}

/// Whether deal.II gives this process two threads when asked (else one and two threads are
/// the same run).
bool two_threads_allowed()
{
  const ThreadLimit limit(2);
  return MultithreadInfo::n_threads() >= 2;
}

/// Force, moments and leakages to the bit.
void expect_same_loads(const FilmLoads &one, const FilmLoads &two)
{
  EXPECT_EQ(one.force_z, two.force_z);
  EXPECT_EQ(one.moment_x, two.moment_x);
  EXPECT_EQ(one.moment_y, two.moment_y);
  EXPECT_EQ(one.leakage_inner, two.leakage_inner);
  EXPECT_EQ(one.leakage_outer, two.leakage_outer);
}
} // namespace

TEST(ThreadedKernels, SameBitsOnOneAndTwoThreads)
{
  const RadialLines by_lines = lines_in_order();
  const unsigned int n = by_lines.size();
  std::vector<unsigned int> identity(n), number(n);
  std::iota(identity.begin(), identity.end(), 0u);
  // another numbering of the same dofs, as deal.II numbers a coarse level: number[p] is the dof
  // at line position p
  number = identity;
  std::shuffle(number.begin(), number.end(), std::mt19937(11));
  const RadialLines permuted = sealfe::testing::permuted_lines(by_lines, number);

  const Entries a = make_entries(by_lines, 2);
  TrilinosWrappers::SparseMatrix A, P;
  make_matrix(A, a, identity);
  make_matrix(P, a, number);
  LineStencilMatrix stencil;
  stencil.initialize(A, by_lines.start);
  ASSERT_EQ(stencil.n_stencil_rows(), n); // every line in the stencil, none in the remainder
  LineJacobi on_lines, on_permuted;
  on_lines.initialize(A, by_lines);
  on_permuted.initialize(P, permuted);

  const IndexSet all = complete_index_set(n);
  VectorType x(all, MPI_COMM_SELF);
  for (unsigned int i = 0; i < n; ++i)
    x.begin()[i] = std::sin(0.61 * i + 0.2) + 0.3 * std::cos(2.9 * i);
  auto run = [&](const unsigned int threads)
  {
    const ThreadLimit limit(threads);
    std::vector<std::vector<double>> results;
    VectorType y(x);
    stencil.vmult(y, x);
    results.push_back(values_of(y));
    on_lines.vmult(y, x);
    results.push_back(values_of(y));
    on_permuted.vmult(y, x);
    results.push_back(values_of(y));
    return results;
  };
  const auto one = run(1);
  const auto two = run(2);
  if (!two_threads_allowed())
    GTEST_SKIP() << "deal.II allows one thread here: nothing to compare";
  const char *names[] = {"LineStencilMatrix::vmult", "LineJacobi::vmult (lines)",
                         "LineJacobi::vmult (gathered)"};
  for (unsigned int r = 0; r < one.size(); ++r)
  {
    unsigned int differences = 0;
    for (unsigned int i = 0; i < n; ++i)
      differences += one[r][i] != two[r][i];
    EXPECT_EQ(differences, 0u) << names[r];
  }
}

TEST(ThreadedKernels, ProductIsTheRowSumsInTheirOrder)
{
  const RadialLines lines = lines_in_order();
  const unsigned int n = lines.size();
  std::vector<unsigned int> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  TrilinosWrappers::SparseMatrix A;
  make_matrix(A, make_entries(lines, 2), identity);
  const Epetra_CrsMatrix &E = A.trilinos_matrix();

  const IndexSet all = complete_index_set(n);
  VectorType x(all, MPI_COMM_SELF), y(x), y_epetra(x);
  for (unsigned int i = 0; i < n; ++i)
    x.begin()[i] = std::sin(0.61 * i + 0.2) + 0.3 * std::cos(2.9 * i);

  VectorType y_one(x);
  {
    const ThreadLimit limit(1);
    ASSERT_TRUE(numerics::threaded_product(E, x.begin(), y_one.begin()));
  }
  const ThreadLimit limit(2);
  ASSERT_TRUE(numerics::threaded_product(E, x.begin(), y.begin()));
  ASSERT_EQ(E.Multiply(false, x.trilinos_vector(), y_epetra.trilinos_vector()), 0);

  const double u = std::numeric_limits<double>::epsilon() / 2;
  unsigned int not_in_order = 0, beyond_bound = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    int count;
    double *values;
    int *columns;
    E.ExtractMyRowView(int(i), count, values, columns);
    double sum = 0, absolute = 0;
    for (int e = 0; e < count; ++e)
    {
      sum += values[e] * x.begin()[columns[e]];
      absolute += std::abs(values[e] * x.begin()[columns[e]]);
    }
    not_in_order += y.begin()[i] != sum || y_one.begin()[i] != sum;
    const double gamma = count * u / (1 - count * u);
    beyond_bound += std::abs(y.begin()[i] - y_epetra.begin()[i]) > 2 * gamma * absolute;
  }
  EXPECT_EQ(not_in_order, 0u);
  EXPECT_EQ(beyond_bound, 0u);
}

TEST(ThreadedKernels, FullFilmLoadsSameBitsOnOneAndTwoThreads)
{
  // CG + geometric multigrid
  FilmSettings settings = tilted_seal();
  settings.linear_solver = FilmSettings::LinearSolver::cg_gmg;
  const FilmLoads one = loads_on(settings, 1), two = loads_on(settings, 2);
  if (!two_threads_allowed())
    GTEST_SKIP() << "deal.II allows one thread here: nothing to compare";
  expect_same_loads(one, two);
  EXPECT_EQ(one.friction_torque, two.friction_torque);
  EXPECT_EQ(one.max_pressure, two.max_pressure);
}

TEST(ThreadedKernels, CavitationLoadsSameBitsOnOneAndTwoThreads)
{
  // The cavitation models' cell matrices (ReynoldsSolver::for_each_cell_film_matrices: batches
  // computed on the threads, summed into the global matrices in the order of the cells): the same
  // tilted seal with a cavity on the side where the faces open, JFO and Reynolds (Swift-Stieber),
  // coarse levels included
  FilmSettings settings = tilted_seal();
  for (const Cavitation model : {Cavitation::jfo, Cavitation::reynolds})
  {
    settings.cavitation.model = model;
    const FilmLoads one = loads_on(settings, 1), two = loads_on(settings, 2);
    if (!two_threads_allowed())
      GTEST_SKIP() << "deal.II allows one thread here: nothing to compare";
    EXPECT_GT(one.cavitated_fraction, 0.05); // a cavity: the nonlinear paths run
    expect_same_loads(one, two);
    EXPECT_EQ(one.cavitated_fraction, two.cavitated_fraction);
  }
}

TEST(ThreadedKernels, BatchesAddEveryItemInOrderAndPassOnAnException)
{
  // 5 000 items in batches of 1 024 (five batches), each item's result its own index
  const std::size_t n_items = 5000, batch_size = 1024;
  for (const bool fail : {false, true})
  {
    std::array<std::vector<std::size_t>, 2> batches;
    for (auto &batch : batches)
      batch.assign(batch_size, 0);
    std::vector<std::size_t> added;
    auto compute = [fail](std::vector<std::size_t> &batch, const std::size_t first_item,
                          const std::size_t begin, const std::size_t end)
    {
      for (std::size_t c = begin; c < end; ++c)
      {
        if (fail && first_item + c == 3000)
          throw std::runtime_error("item 3000");
        batch[c] = first_item + c;
      }
    };
    auto add =
        [&added](const std::vector<std::size_t> &batch, const std::size_t, const std::size_t count)
    { added.insert(added.end(), batch.begin(), batch.begin() + count); };
    std::string message;
    try
    {
      numerics::compute_in_batches_add_in_order(n_items, batch_size, batches, 32, compute, add);
    }
    catch (const std::exception &e)
    {
      message = e.what();
    }
    // without the exception every item once, in order; with it, the two batches before the
    // third (items 2 048-3 071, which holds item 3 000) and nothing after
    EXPECT_EQ(message, fail ? "item 3000" : "");
    ASSERT_EQ(added.size(), fail ? 2 * batch_size : n_items);
    for (std::size_t k = 0; k < added.size(); ++k)
      ASSERT_EQ(added[k], k);
  }
}
