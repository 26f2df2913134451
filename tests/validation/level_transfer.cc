// LevelTransfer (the multigrid prolongation FilmMultigrid uses) builds the matrices of deal.II's
// MGTransferPrebuilt by its own cell loop: the finite-element embedding of each level into the
// next, with the columns of the coarse level's boundary dofs zeroed. Both must give the same
// prolongation and restriction, level by level, on a graded annulus refined from its coarse
// grid (three levels), degrees 1-3; and on the finest level, whose rows LevelTransfer numbers by
// the active dofs (the system's numbering), the same values at the same support points.
//
// Tolerance, from round-off alone. A prolonged entry is sum_j P_ij x_j over the n dofs of the
// parent cell; the two paths may add in another order and take P_ij from another child cell
// (the embedding matrices are computed in floating point, a few units of round-off u apart), so
// they differ by at most (2 n + 4) u sum_j |P_ij| |x_j| <= (2 n + 4) u Lambda |x|_inf, where
// Lambda = sum_j |P_ij| is the Lebesgue constant of the equispaced Lagrange interpolation at the
// children's nodes: <= 1.25^2 (Q2), < 1.7^2 (Q3), 1 (Q1); 3 bounds all of them. A restricted
// entry sums P_ij y_i over the m <= 4 (2k + 1)^2 fine rows whose cells touch the coarse dof,
// |P_ij| <= Lambda_1 <= 1.7 in 1D squared (< 3): at most (2 m + 4) u 3 m |y|_inf. The vectors
// are random in [-1/2, 1/2]. A missing or extra entry (a wrong embedding or boundary column)
// differs by O(1) and fails.
#include "../graded_annulus.h"
#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/level_transfer.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>
#include <deal.II/multigrid/mg_transfer.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
using VectorType = TrilinosWrappers::MPI::Vector;

/// Random entries in [-1/2, 1/2] (xorshift64; the seed differs per rank and per call).
void fill_random(VectorType &x, std::uint64_t seed)
{
  seed += 1000003ull * Utilities::MPI::this_mpi_process(x.get_mpi_communicator());
  for (auto it = x.begin(); it != x.end(); ++it)
  {
    seed ^= seed << 13;
    seed ^= seed >> 7;
    seed ^= seed << 17;
    *it = double(seed >> 11) / double(1ull << 53) - 0.5;
  }
  x.compress(VectorOperation::insert);
}

/// Largest |a - b| over the ranks.
double max_difference(const VectorType &a, const VectorType &b)
{
  VectorType d(a);
  d -= b;
  return d.linfty_norm();
}

constexpr double u = std::numeric_limits<double>::epsilon() / 2;
constexpr double lebesgue = 3; // bounds sum_j |P_ij| and |P_ij| for degrees 1-3 (see above)

class LevelTransferTest : public ::testing::TestWithParam<unsigned int>
{
};
} // namespace

TEST_P(LevelTransferTest, EqualsMGTransferPrebuiltOnEveryLevel)
{
  const unsigned int degree = GetParam();
  const MPI_Comm comm = MPI_COMM_WORLD;
  test::GradedAnnulusDoFs annulus(comm, degree);
  const auto &tria = annulus.annulus.tria;
  ASSERT_EQ(tria.n_global_levels(), 3u);
  const FE_Q<2> &fe = annulus.fe;
  const DoFHandler<2> &dof_handler = annulus.dof_handler;
  const MGConstrainedDoFs &constrained = annulus.level_boundary;
  MGTransferPrebuilt<VectorType> reference(constrained);
  reference.build(dof_handler);

  const unsigned int n = fe.n_dofs_per_cell(), fine = tria.n_global_levels() - 1;
  const unsigned int m_rows = 4 * (2 * degree + 1) * (2 * degree + 1);
  const double prolong_bound = (2 * n + 4) * u * lebesgue * 0.5;
  const double restrict_bound = (2 * m_rows + 4) * u * lebesgue * m_rows * 0.5;
  auto level_vector = [&](const unsigned int l)
  { return VectorType(dof_handler.locally_owned_mg_dofs(l), comm); };

  // Level numbering on every level (the transfer of FilmMultigrid's fallback branch).
  {
    LevelTransfer transfer;
    ASSERT_TRUE(transfer.build(dof_handler, constrained, false, dof_handler.get_communicator()));
    for (unsigned int l = 1; l <= fine; ++l)
    {
      VectorType coarse = level_vector(l - 1), fine_vector = level_vector(l);
      fill_random(coarse, 17 * l + degree);
      VectorType mine = level_vector(l), theirs = level_vector(l);
      transfer.prolongate_and_add(l, mine, coarse);
      reference.prolongate(l, theirs, coarse);
      EXPECT_GT(theirs.linfty_norm(), 0.1) << "level " << l;
      EXPECT_LE(max_difference(mine, theirs), prolong_bound) << "prolongation to level " << l;

      fill_random(fine_vector, 31 * l + degree);
      VectorType mine_r = level_vector(l - 1), theirs_r = level_vector(l - 1);
      transfer.restrict_and_add(l, mine_r, fine_vector);
      reference.restrict_and_add(l, theirs_r, fine_vector);
      EXPECT_GT(theirs_r.linfty_norm(), 0.1) << "level " << l;
      EXPECT_LE(max_difference(mine_r, theirs_r), restrict_bound) << "restriction from level " << l;
    }
  }

  // Finest level in the active numbering (FilmMultigrid's system branch): the same values at
  // the same dofs, matched cell by cell (every finest-level cell is active).
  {
    LevelTransfer transfer;
    ASSERT_TRUE(transfer.build(dof_handler, constrained, true, dof_handler.get_communicator()));
    const IndexSet &owned_active = dof_handler.locally_owned_dofs();
    const IndexSet &owned_level = dof_handler.locally_owned_mg_dofs(fine);
    std::vector<types::global_dof_index> active(n), level(n);
    std::vector<std::pair<types::global_dof_index, types::global_dof_index>> pairs;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        ASSERT_EQ(unsigned(cell->level()), fine);
        cell->get_dof_indices(active);
        cell->get_mg_dof_indices(level);
        for (unsigned int i = 0; i < n; ++i)
          if (owned_active.is_element(active[i]) && owned_level.is_element(level[i]))
            pairs.emplace_back(active[i], level[i]);
      }

    VectorType coarse = level_vector(fine - 1);
    fill_random(coarse, 101 + degree);
    VectorType mine(owned_active, comm), theirs = level_vector(fine);
    transfer.prolongate_and_add(fine, mine, coarse);
    reference.prolongate(fine, theirs, coarse);
    double difference = 0;
    for (const auto &[a, l] : pairs)
      difference = std::max(difference, std::abs(mine[a] - theirs[l]));
    EXPECT_LE(Utilities::MPI::max(difference, comm), prolong_bound);

    // restriction of the same fine field, given in either numbering
    VectorType fine_active(owned_active, comm), fine_level = level_vector(fine);
    fill_random(fine_active, 202 + degree);
    for (const auto &[a, l] : pairs)
      fine_level[l] = fine_active[a];
    fine_level.compress(VectorOperation::insert);
    // every owned level dof must have its active twin here (always on one rank; on several the
    // two ownerships could differ at partition edges, and this part would test nothing)
    std::vector<bool> seen(owned_level.n_elements(), false);
    for (const auto &pair : pairs)
      seen[owned_level.index_within_set(pair.second)] = true;
    const bool covered = std::find(seen.begin(), seen.end(), false) == seen.end();
    if (Utilities::MPI::min(covered ? 1 : 0, comm) == 0)
      GTEST_SKIP() << "level and active ownership differ on this partition";
    VectorType mine_r = level_vector(fine - 1), theirs_r = level_vector(fine - 1);
    transfer.restrict_and_add(fine, mine_r, fine_active);
    reference.restrict_and_add(fine, theirs_r, fine_level);
    EXPECT_GT(theirs_r.linfty_norm(), 0.1);
    EXPECT_LE(max_difference(mine_r, theirs_r), restrict_bound);
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, LevelTransferTest, ::testing::Values(1u, 2u, 3u));
