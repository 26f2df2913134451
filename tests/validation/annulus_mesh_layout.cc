// Validation of the built-in annulus mesh: it is built from a coarse polar grid refined globally
// (few p4est trees), and must be the mesh asked for, nr x nt cells with vertices exactly on the
// graded radial nodes and on the angles 2 pi j / nt (the definition of the built-in mesh), with
// `Global refinements` halving every cell of that mesh (new radii the means of the old ones).
#include <sealfe/film/annulus_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

using namespace sealfe;

namespace
{
constexpr double ri = 0.0355, ro = 0.0408;

AnnulusMesh graded_mesh(const unsigned int nr, const unsigned int nt, const unsigned int refs)
{
  AnnulusMesh m;
  m.radial_cells = nr;
  m.circumferential_cells = nt;
  m.global_refinements = refs;
  m.grading_clearance = 1e-6; // C0
  m.grading_coning = 1e-3;    // beta: h0 grows by a factor 6.3 across the dam
  return m;
}

/// Checks that every vertex of `tria` is at one of `radii` and at an angle 2 pi j / nt, and (one
/// rank) that every (radius, angle) pair occurs: the vertex set of the polar grid radii x angles.
void expect_polar_grid(const dealii::parallel::distributed::Triangulation<2> &tria,
                       const std::vector<double> &radii, const unsigned int nt)
{
  std::map<std::pair<unsigned int, long>, unsigned int> seen;
  double worst_r = 0, worst_t = 0;
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
    {
      const dealii::Point<2> x = cell->vertex(v);
      const double r = x.norm();
      unsigned int i = 0;
      for (unsigned int k = 1; k < radii.size(); ++k)
        if (std::abs(radii[k] - r) < std::abs(radii[i] - r))
          i = k;
      double t = std::atan2(x[1], x[0]);
      if (t < 0)
        t += 2 * M_PI;
      const long j = std::lround(t * nt / (2 * M_PI)) % long(nt);
      worst_r = std::max(worst_r, std::abs(r - radii[i]) / ro);
      const double dt = std::remainder(t - 2 * M_PI * j / nt, 2 * M_PI);
      worst_t = std::max(worst_t, std::abs(dt));
      ++seen[{i, j}];
    }
  // vertex coordinates are r cos(t), r sin(t) of the exact values: round-off only
  EXPECT_LT(worst_r, 1e-15);
  EXPECT_LT(worst_t, 1e-14);
  // (each rank holds only its part of the fine cells)
  if (dealii::Utilities::MPI::n_mpi_processes(tria.get_communicator()) == 1)
  {
    EXPECT_EQ(seen.size(), radii.size() * nt);
  }
}
} // namespace

TEST(AnnulusMeshLayout, RefinedCoarseGridIsTheGradedMeshAskedFor)
{
  // 8 x 128 (the default mesh) and 16 x 32: built from 1 x 16 and 8 x 16 coarse grids
  for (const auto [nr, nt] : {std::pair{8u, 128u}, std::pair{16u, 32u}, std::pair{7u, 20u}})
  {
    const AnnulusMesh m = graded_mesh(nr, nt, 0);
    dealii::parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
    m.create(tria, ri, ro);
    EXPECT_EQ(tria.n_global_active_cells(), nr * nt);
    const std::vector<double> radii = m.radial_nodes(nr, ri, ro);
    // the grading is not uniform (else this test would not see a wrong interpolation)
    EXPECT_GT(std::abs((radii[nr] - radii[nr - 1]) / (radii[1] - radii[0]) - 1), 0.5);
    expect_polar_grid(tria, radii, nt);
  }
}

TEST(AnnulusMeshLayout, GlobalRefinementsHalveTheGradedCells)
{
  // 4 x 32 refined twice: 16 x 128 cells; radii: the 5 graded nodes of 4 cells, each interval
  // cut into 4 equal parts (polar-manifold midpoints)
  const AnnulusMesh m = graded_mesh(4, 32, 2);
  dealii::parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  m.create(tria, ri, ro);
  EXPECT_EQ(tria.n_global_active_cells(), 16u * 128u);
  const std::vector<double> nodes = m.radial_nodes(4, ri, ro);
  std::vector<double> radii;
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int s = 0; s < 4; ++s)
      radii.push_back(nodes[i] + (nodes[i + 1] - nodes[i]) * s / 4.0);
  radii.push_back(ro);
  expect_polar_grid(tria, radii, 128);
}

TEST(AnnulusMeshLayout, CoarseningHalvesTheCellsAskedFor)
{
  // the error estimate's coarse mesh: 8 x 128 coarsened once is the graded 4 x 64 mesh
  const AnnulusMesh m = graded_mesh(8, 128, 0);
  dealii::parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  m.create(tria, ri, ro, 1);
  EXPECT_EQ(tria.n_global_active_cells(), 4u * 64u);
  expect_polar_grid(tria, m.radial_nodes(4, ri, ro), 64);
}
