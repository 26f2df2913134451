// The Reynolds (Swift-Stieber) cavitation model, p >= p_cav by the primal-dual active-set method
// (ReynoldsCavitationSolver), on the tilted Varney & Green seal (benchmarks/reynolds_speed):
//  - the solution satisfies the discrete complementarity conditions, to the bounds its stopping
//    test implies;
//  - the start from the mesh twice as coarse (mesh sequencing) and the old start from the clipped
//    full film end on the same solution: the same cavitated set and the same loads to the
//    stopping tolerance (the discrete problem is a linear complementarity problem with a
//    symmetric positive definite matrix, whose solution is unique);
//  - the steps by low-rank updates of an earlier factorisation (one rank) end on the solution of
//    the steps that factorise every time, with the same linearised loads.
#include <sealfe/film/jfo_solver.h>
#include <sealfe/film/reynolds_cavitation_solver.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace sealfe;

namespace
{
// The benchmark's tilted seal: eps = gamma ro / C0 = 0.5, 4 bar sealed, 1000 rad/s.
FilmThickness tilted_seal()
{
  FilmThickness film;
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  return film;
}

FilmLoads solve_reynolds(ReynoldsSolver &solver, const bool sequenced, const unsigned int nr,
                         const unsigned int nt)
{
  // put the switch back even if the solve throws (later tests take the default)
  struct Restore
  {
    ~Restore() { ReynoldsCavitationSolver::sequenced_start = true; }
  } restore;
  ReynoldsCavitationSolver::sequenced_start = sequenced;
  solver.cavitation.model = Cavitation::reynolds;
  solver.polynomial_degree = 2;
  solver.mesh().radial_cells = nr;
  solver.mesh().circumferential_cells = nt;
  return solver.run(tilted_seal(), OperatingConditions());
}
} // namespace

TEST(ReynoldsCavitation, SolutionSatisfiesTheComplementarityConditions)
{
  // The iteration stops when the cavitated set repeats and the relative residual (the mass
  // residuals R_i = (A p - F)_i of the free nodes and u_i of the cavitated ones, over the flow
  // scale |F|) is below tol; the set is {i : u_i - R_i / J_ii <= 0} with J_ii = P A_ii > 0.
  // So at the solution, with the residual recomputed from the stored pressure:
  //   free nodes:      |R_i| <= tol |F|, and u_i > R_i / J_ii >= -tol |F| / J_ii;
  //   cavitated nodes: |u_i| <= tol |F| (p = p_cav), and R_i >= J_ii u_i >= -J_ii tol |F|
  //                    (the film there would take up liquid: no outflow to hold p at p_cav).
  // (The hook gives R_i and J_ii over |F|.)
  // The recomputation from p = p_cav + P u adds round-off of p only: 1e-12 relative to the
  // largest |A_ij p_j| terms, far below tol = 1e-10 on this mesh, so the bounds are stated with
  // a factor 2 over the stopping tolerance.
  ReynoldsSolver solver(MPI_COMM_WORLD);
  const FilmLoads loads = solve_reynolds(solver, true, 16, 64);
  const double tol = solver.cavitation.tolerance;
  const auto c = ReynoldsCavitationSolver::complementarity_at_solution(solver);
  ASSERT_FALSE(c.u.empty());
  unsigned int cavitated = 0;
  for (std::size_t k = 0; k < c.u.size(); ++k)
  {
    const double bound = 2 * tol; // relative to |F|
    if (c.cavitated[k])
    {
      ++cavitated;
      EXPECT_LE(std::abs(c.u[k]), bound * c.flow_scale) << "cavitated node " << k;
      EXPECT_GE(c.residual[k], -bound * c.jacobian_diagonal[k] * c.flow_scale)
          << "cavitated node " << k;
    }
    else
    {
      EXPECT_LE(std::abs(c.residual[k]), bound) << "free node " << k;
      EXPECT_GE(c.u[k], -bound / c.jacobian_diagonal[k]) << "free node " << k;
    }
  }
  std::cout << "cavitated nodes " << cavitated << " of " << c.u.size() << ", cavitated fraction "
            << loads.cavitated_fraction << ", iterations " << solver.nonlinear_iterations() << " (+"
            << solver.coarse_nonlinear_iterations() << " on coarser meshes)\n";
  EXPECT_GT(cavitated, 0u); // the tilted seal does cavitate
  EXPECT_GT(loads.cavitated_fraction, 0.05);
}

TEST(ReynoldsCavitation, SequencedStartGivesTheFullFilmStartsSolution)
{
  // The discrete problem is the LCP  u >= 0, R(u) = P A u + (A p_cav - F) >= 0, u^T R = 0 with
  // A the stiffness matrix of the pressure flow on the free dofs: symmetric positive definite,
  // so the LCP has exactly one solution (Cottle, Pang & Stone 1992, Thm. 3.3.7), whatever the
  // start of the active-set iteration. Both starts therefore end on the same cavitated set (a
  // node could differ only where u_i = R_i = 0 to round-off: none here, checked by the set
  // equality) and on the same linear system, whose solutions differ by the stopping residual:
  // relative mass residual below tol = 1e-10 each. The loads are integrals of p, whose
  // sensitivity to a residual of relative size tol is of that size (the adjoint of an integral
  // of an elliptic solution is smooth): stated 10 tol.
  ReynoldsSolver old_start(MPI_COMM_WORLD), sequenced(MPI_COMM_WORLD);
  const FilmLoads a = solve_reynolds(old_start, false, 16, 64);
  const FilmLoads b = solve_reynolds(sequenced, true, 16, 64);
  const double tol = old_start.cavitation.tolerance;
  std::cout << "iterations: full-film start " << old_start.nonlinear_iterations() << ", sequenced "
            << sequenced.nonlinear_iterations() << " (+" << sequenced.coarse_nonlinear_iterations()
            << " on coarser meshes)\n";
  ASSERT_NE(sequenced.coarse_level_solver(), nullptr); // it did start from the coarse mesh
  EXPECT_EQ(old_start.coarse_nonlinear_iterations(), 0u);
  const auto ca = ReynoldsCavitationSolver::complementarity_at_solution(old_start);
  const auto cb = ReynoldsCavitationSolver::complementarity_at_solution(sequenced);
  EXPECT_EQ(ca.cavitated, cb.cavitated);
  for (auto member : {&FilmLoads::force_z, &FilmLoads::moment_x, &FilmLoads::moment_y,
                      &FilmLoads::leakage_inner, &FilmLoads::leakage_outer})
    EXPECT_NEAR(a.*member, b.*member, 10 * tol * std::abs(a.*member));
  EXPECT_EQ(a.cavitated_fraction, b.cavitated_fraction);
}

TEST(ReynoldsCavitation, LowRankStepsGiveTheFactorisedStepsSolution)
{
  // On one rank each step solves the column form, and a step whose set differs from the last
  // factorised one in few nodes is a low-rank update of that factorisation
  // (ReynoldsCavitationSolver::column_form_step); the row form factorises every step (the hook
  // column_form = false, as on several ranks). Both iterations solve the same LCP (unique
  // solution, as above), so they end on the same cavitated set, and their loads differ by the
  // stopping residuals (10 tol relative, as above). The linearised loads solve with the
  // Jacobian at the solution: the row form's from its last step's factorisation, the column
  // form's made again and factorised at the first solve; the same matrix, so they differ by the
  // solutions' residuals too. Two meshes: below 2e4 unknowns (KLU: the update by a block solve)
  // and above (MUMPS: by selected entries of the inverse). The updates must have been taken, or
  // the test compares a path with itself.
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    GTEST_SKIP() << "the low-rank steps are one rank's";
  const auto tilt_x = [](double r, double t) { return 1e-7 + 1e-5 * r * std::sin(t); };
  const std::vector<FilmPerturbation> directions = {{tilt_x, {}}, {{}, tilt_x}};
  for (const auto &[nr, nt] : {std::pair{16u, 64u}, std::pair{64u, 128u}})
  {
    struct Restore
    {
      ~Restore() { ReynoldsCavitationSolver::column_form = true; }
    } restore;
    ReynoldsSolver updated(MPI_COMM_WORLD), factorised(MPI_COMM_WORLD);
    const FilmLoads a = solve_reynolds(updated, true, nr, nt);
    const std::vector<FilmLoads> da = updated.linearized_loads(directions);
    ReynoldsCavitationSolver::column_form = false; // every step factorises its row form
    const FilmLoads b = solve_reynolds(factorised, true, nr, nt);
    const std::vector<FilmLoads> db = factorised.linearized_loads(directions);
    std::cout << nr << " x " << nt << " cells, " << updated.n_dofs()
              << " dofs: " << updated.low_rank_updates() << " low-rank steps of "
              << updated.nonlinear_iterations() << ", against " << factorised.low_rank_updates()
              << "\n";
    EXPECT_GT(updated.low_rank_updates(), 0u);
    EXPECT_EQ(factorised.low_rank_updates(), 0u);
    EXPECT_EQ(updated.nonlinear_iterations(), factorised.nonlinear_iterations());
    const double tol = updated.cavitation.tolerance;
    EXPECT_EQ(ReynoldsCavitationSolver::complementarity_at_solution(updated).cavitated,
              ReynoldsCavitationSolver::complementarity_at_solution(factorised).cavitated);
    for (auto member : {&FilmLoads::force_z, &FilmLoads::leakage_inner, &FilmLoads::leakage_outer})
      EXPECT_NEAR(a.*member, b.*member, 10 * tol * std::abs(a.*member));
    // the moments against |force_z| r_o: a residual of relative size tol moves p by that share,
    // and a moment by at most that share of |force_z| times the outer radius
    const double ro = tilted_seal().outer_radius;
    for (auto member : {&FilmLoads::moment_x, &FilmLoads::moment_y})
      EXPECT_NEAR(a.*member, b.*member, 10 * tol * std::abs(a.force_z) * ro);
    for (std::size_t d = 0; d < directions.size(); ++d)
    {
      EXPECT_NEAR(da[d].force_z, db[d].force_z, 10 * tol * std::abs(da[d].force_z))
          << "direction " << d;
      for (auto member : {&FilmLoads::moment_x, &FilmLoads::moment_y})
        EXPECT_NEAR(da[d].*member, db[d].*member, 10 * tol * std::abs(da[d].force_z) * ro)
            << "direction " << d;
    }
  }
}
