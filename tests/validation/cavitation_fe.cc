// Cavitation in the finite-element solver (none, half-Sommerfeld, Reynolds, JFO):
//  - without cavitation all models give the full-film solution to solver tolerance;
//  - JFO conserves mass: inner + outer leakage = 0 to 1e-8 relative, and the flow through any
//    circle of the dam equals the leakage (to the accuracy of a direct flux integral);
//  - the JFO residuals and Jacobians from the assembled matrices give the loads and linearised
//    loads of the cell-by-cell assembly to the Newton tolerance, and the mass balance holds on
//    both; so does the low-rank
//    update of the global active-set rounds against a factorisation per round;
//  - the global P A and G equal deal.II's assembly of the cell matrices entry by entry, and the
//    Jacobian at the solution by their columns equals the cell loop's, with the same linearised
//    loads (round-off bounds);
//  - single-precision factors refined in double end on the double factors' solution;
//  - a level whose coarse level fails starts from the full film and ends on the same solution;
//  - JFO mesh convergence of force, moments and cavitated fraction (orders measured);
//  - hard cases converge (or stop with a clear message): tilt eps = 0.95 and 0.99, 1e4 rad/s at
//    10 kPa, waviness n = 1..12 up to 0.9 C0, and no supply (pi = po = p_cav) is refused.
#include <sealfe/film/jfo_solver.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include "../cavitating_wavy_seal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

using namespace sealfe;

using sealfe::testing::low_pressure;
using sealfe::testing::wavy_film;

namespace
{
FilmLoads solve(const FilmThickness &film, const OperatingConditions &conditions,
                const Cavitation model, const unsigned int nr = 8, const unsigned int nt = 128,
                const unsigned int degree = 2, ReynoldsSolver *keep = nullptr)
{
  ReynoldsSolver local(MPI_COMM_WORLD);
  ReynoldsSolver &s = keep ? *keep : local;
  s.cavitation.model = model;
  s.polynomial_degree = degree;
  s.mesh().radial_cells = nr;
  s.mesh().circumferential_cells = nt;
  return s.run(film, conditions);
}

/// The tilted Varney & Green seal of the speed benchmark: tilt eps = 0.5 (0.5 C0 at ro)
FilmThickness tilted_seal()
{
  FilmThickness film;
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  return film;
}

/// A JFO run to the Newton tolerance `tolerance` on `solver`, which must converge and balance
/// its leakages to 1e-8 (as JfoConservesMassThroughEveryCircle)
FilmLoads converged_jfo(const FilmThickness &film, const OperatingConditions &conditions,
                        const unsigned int nr, const unsigned int nt, const double tolerance,
                        ReynoldsSolver &solver)
{
  solver.cavitation.tolerance = tolerance;
  const FilmLoads l = solve(film, conditions, Cavitation::jfo, nr, nt, 2, &solver);
  EXPECT_LT(solver.nonlinear_residual(), tolerance);
  EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer), 1e-8 * std::abs(l.leakage_outer));
  return l;
}

/// Two runs that end on the same discrete JFO solution (a cavitating one): the loads agree to the
/// Newton tolerance
void expect_same_jfo_solution(const FilmLoads &a, const FilmLoads &b, const double tolerance,
                              const double outer_radius)
{
  ASSERT_GT(a.cavitated_fraction, 0.05);
  EXPECT_NEAR(a.cavitated_fraction, b.cavitated_fraction, tolerance);
  EXPECT_NEAR(a.force_z, b.force_z, tolerance * std::abs(a.force_z));
  EXPECT_NEAR(a.moment_x, b.moment_x, tolerance * std::abs(a.force_z) * outer_radius);
  EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tolerance * std::abs(a.leakage_outer));
}

} // namespace

TEST(CavitationFE, WithoutCavitationAllModelsAreTheFullFilm)
{
  // Default seal with a small tilt and the inner pressure raised: p > 0 everywhere.
  FilmThickness film;
  film.tilt = 0.05 * film.clearance / film.outer_radius;
  OperatingConditions conditions;
  conditions.inner_pressure = 2e5;
  const FilmLoads none = solve(film, conditions, Cavitation::none);
  ASSERT_GT(none.min_pressure, 0);
  for (const auto model : {Cavitation::half_sommerfeld, Cavitation::reynolds, Cavitation::jfo})
  {
    const FilmLoads c = solve(film, conditions, model);
    EXPECT_NEAR(c.force_z, none.force_z, 1e-10 * std::abs(none.force_z));
    EXPECT_NEAR(c.moment_x, none.moment_x, 1e-10 * std::abs(none.moment_x));
    EXPECT_NEAR(c.moment_y, none.moment_y, 1e-10 * std::abs(none.moment_x));
    EXPECT_NEAR(c.leakage_inner, none.leakage_inner, 1e-10 * std::abs(none.leakage_inner));
    EXPECT_EQ(c.cavitated_fraction, 0.0);
  }
}

TEST(CavitationFE, JfoConservesMassThroughEveryCircle)
{
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  ReynoldsSolver solver(MPI_COMM_WORLD);
  const FilmLoads jfo = solve(film, conditions, Cavitation::jfo, 8, 128, 2, &solver);
  std::cout << "jfo: cavitated fraction " << jfo.cavitated_fraction << ", Newton iterations "
            << solver.nonlinear_iterations() << " (+" << solver.coarse_nonlinear_iterations()
            << " on coarser meshes)\n";
  ASSERT_GT(jfo.cavitated_fraction, 0.05); // the case does cavitate
  const double Q = std::abs(jfo.leakage_outer);
  EXPECT_LT(std::abs(jfo.leakage_inner + jfo.leakage_outer), 1e-8 * Q);
  // The direct flux integral through interior circles agrees with the conservative leakage to
  // its own (mesh) accuracy; measured 1e-3..1e-2 here, so a 3% bound.
  for (const double f : {0.25, 0.5, 0.75})
  {
    const double rho = film.inner_radius + f * (film.outer_radius - film.inner_radius);
    const double flow = solver.volume_flow_through_circle(rho);
    std::cout << "flow through r = " << rho << ": " << flow << " vs leakage_outer "
              << jfo.leakage_outer << "\n";
    EXPECT_NEAR(flow / jfo.leakage_outer, 1.0, 0.03);
  }
  // Reynolds (Swift-Stieber) does not conserve mass at reformation: its imbalance is large.
  const FilmLoads rey = solve(film, conditions, Cavitation::reynolds);
  std::cout << "reynolds imbalance " << (rey.leakage_inner + rey.leakage_outer) / Q << "\n";
  EXPECT_GT(std::abs(rey.leakage_inner + rey.leakage_outer), 1e-3 * Q);
}

TEST(CavitationFE, JfoResidualsByMatrixProductsGiveTheCellAssemblysSolution)
{
  // The active-set rounds and line searches take the residual and right-hand side as products of
  // the assembled P A and G (JFOSolver::assemble_by_products), the active-set Jacobians as their
  // column selections and the Jacobian at the solution (the linearised loads) as their column
  // combinations; the same sums as the cell loop in another order. Both end on the same
  // cavitated set, where the JFO problem is linear, with a relative mass residual below the
  // Newton tolerance (Cavitation/Tolerance = 1e-10); so the loads agree to that tolerance and the
  // mass balance holds (1e-8, as above) on both. The linearised loads solve one linear system
  // whose matrices are the same up to round-off (bitwise where a_j + v_j > 0): they agree to the
  // same tolerance. The first run's Jacobian at the solution is the column combination
  // (JFOSolver::jacobian_by_columns: this case converges at the residual-only check after a
  // successful polish), the second's the cell loop's, so the linearised loads compare the two.
  // On several ranks (ctest cavitation_fe_on_2_ranks, _3_) the residuals, rounds and the column
  // combination take the same products from each rank's rows.
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  const double tolerance = 1e-10;
  FilmLoads l[2], lin[2];
  // the switch is a static: put back even if a solve throws (later tests take the default path)
  struct RestoreDefault
  {
    ~RestoreDefault() { JFOSolver::assemble_by_cells = false; }
  } restore;
  for (const bool by_cells : {false, true})
  {
    JFOSolver::assemble_by_cells = by_cells;
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solver.cavitation.tolerance = tolerance;
    const unsigned int by_columns_before = JFOSolver::jacobians_by_columns,
                       by_cells_before = JFOSolver::jacobians_by_cells,
                       one_pass_before = JFOSolver::solves_in_one_pass;
    l[by_cells] = solve(film, conditions, Cavitation::jfo, 16, 256, 2, &solver);
    // one Jacobian at the solution per solve (the coarse start levels have none)
    EXPECT_EQ(JFOSolver::jacobians_by_columns - by_columns_before, by_cells ? 0u : 1u);
    EXPECT_EQ(JFOSolver::jacobians_by_cells - by_cells_before, by_cells ? 1u : 0u);
    // one rank: the products' run read the finest level's cell matrices in one pass, holding
    // only those of the cells on the boundary (its flow scale, global P A and G and constant
    // terms made as it went); the cell loop's run held them all, and so does the distributed
    // level on several ranks
    const bool one_rank = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1;
    EXPECT_EQ(JFOSolver::solves_in_one_pass - one_pass_before, one_rank && !by_cells ? 1u : 0u);
    EXPECT_LT(solver.nonlinear_residual(), tolerance);
    const double Q = std::abs(l[by_cells].leakage_outer);
    EXPECT_LT(std::abs(l[by_cells].leakage_inner + l[by_cells].leakage_outer), 1e-8 * Q);
    // dF/dz and dM/d(tilt): a uniform gap change and a tilt about x
    lin[by_cells] = solver.linearized_loads(
        {[](double r, double t) { return 1e-7 + 1e-5 * r * std::sin(t); }, {}});
  }
  ASSERT_NE(lin[0].force_z, 0.0);
  EXPECT_NEAR(lin[0].force_z, lin[1].force_z, tolerance * std::abs(lin[1].force_z));
  EXPECT_NEAR(lin[0].moment_x, lin[1].moment_x,
              tolerance * std::abs(lin[1].force_z) * film.outer_radius);
  ASSERT_GT(l[0].cavitated_fraction, 0.05);
  EXPECT_NEAR(l[0].cavitated_fraction, l[1].cavitated_fraction, tolerance);
  EXPECT_NEAR(l[0].force_z, l[1].force_z, tolerance * std::abs(l[1].force_z));
  EXPECT_NEAR(l[0].moment_x, l[1].moment_x, tolerance * std::abs(l[1].force_z) * film.outer_radius);
  EXPECT_NEAR(l[0].leakage_outer, l[1].leakage_outer, tolerance * std::abs(l[1].leakage_outer));
}

TEST(CavitationFE, JfoGlobalMatricesAreTheAssemblyOfTheCellMatrices)
{
  // JFOSolver::prepare_global_matrices sums P A and G cell by cell straight into flat arrays in
  // the system matrix's storage order, with the constrained rows' diagonal rule of deal.II's
  // AffineConstraints::distribute_local_to_global (set_matrix_diagonals). Compared entry by entry
  // with deal.II's assembly of the same cell matrices into the Trilinos matrix. Round-off bound:
  // on quadrilaterals an entry (i, j) has a term from each cell holding both dofs, at most the 4
  // cells around a vertex; any two summation orders of k = 4 terms t_c differ by at most
  // 2 (k - 1) u sum |t_c| <= 6 u 4 max |t_c| = 12 eps max |t_c|, and a cell term is at most the
  // largest entry of its matrix (P A: the cell matrices are symmetric positive semidefinite, so
  // |A_c(i,j)| <= max A_c(i,i), and the diagonals sum terms of one sign; G: taken the same).
  // The code adds the same terms in the same order, so it claims more (equal to the bit): the
  // test prints how many entries differ at all. Degrees 1 and 2, a cavitating (wavy) case.
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  const double eps = std::numeric_limits<double>::epsilon();
  for (const unsigned int degree : {1u, 2u})
  {
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solve(film, conditions, Cavitation::jfo, 4, 64, degree, &solver);
    JFOSolver jfo(solver);
    const JFOSolver::GlobalMatricesAndAssembly m = jfo.global_matrices_and_assembly();
    // Dirichlet constraints only: there on one rank and on several (each rank's rows, summed
    // over the ranks by the system matrix; ctest cavitation_fe_on_2_ranks, _3_)
    ASSERT_FALSE(m.PA.empty()) << "degree " << degree;
    ASSERT_EQ(m.PA.size(), m.assembled_PA.size());
    ASSERT_EQ(m.G.size(), m.assembled_G.size());
    ASSERT_EQ(m.PA.size(), m.G.size());
    double largest_PA = 0, largest_G = 0;
    for (std::size_t e = 0; e < m.PA.size(); ++e)
    {
      largest_PA = std::max(largest_PA, std::abs(m.assembled_PA[e]));
      largest_G = std::max(largest_G, std::abs(m.assembled_G[e]));
    }
    const double bound_PA = 12 * eps * largest_PA, bound_G = 12 * eps * largest_G;
    std::size_t different_bits = 0, nonzero = 0;
    double worst_PA = 0, worst_G = 0;
    for (std::size_t e = 0; e < m.PA.size(); ++e)
    {
      worst_PA = std::max(worst_PA, std::abs(m.PA[e] - m.assembled_PA[e]) / bound_PA);
      worst_G = std::max(worst_G, std::abs(m.G[e] - m.assembled_G[e]) / bound_G);
      // bit patterns (a signed zero counts as a difference)
      different_bits += std::memcmp(&m.PA[e], &m.assembled_PA[e], sizeof(double)) != 0;
      different_bits += std::memcmp(&m.G[e], &m.assembled_G[e], sizeof(double)) != 0;
      nonzero += (m.assembled_PA[e] != 0) + (m.assembled_G[e] != 0);
    }
    std::cout << "degree " << degree << ": " << m.PA.size() << " entries each, " << nonzero
              << " nonzero in P A and G; worst difference / bound: P A " << worst_PA << ", G "
              << worst_G << "; " << different_bits << " entries differ in any bit\n";
    EXPECT_GT(largest_G, 0.0);       // a cavitating case: G is not all zero
    EXPECT_GT(nonzero, m.PA.size()); // not a comparison of zeros
    EXPECT_LE(worst_PA, 1.0) << "degree " << degree;
    EXPECT_LE(worst_G, 1.0) << "degree " << degree;
  }
}

TEST(CavitationFE, FlowScaleFromTheCellMatricesIsTheFullFilmAssembly)
{
  // The cavitation models no longer assemble the full film where they start from the coarse
  // level; the right-hand side they scale their mass residual by is made from their cell
  // matrices A and F (ReynoldsSolver::full_film_flow_scale) with the full-film assembly's
  // additions in its order: the same cell terms (film_matrices computes A and F alike with and
  // without the void terms), the cells without constrained dofs by position, the others through
  // the constraints. So every entry must be the same bits as assemble_system()'s (a signed zero
  // counts as a difference). Degrees 1 and 2, a cavitating (wavy) case; on 1, 2 and 3 ranks
  // (ctest cavitation_fe_on_2_ranks, _3_), where each rank compares its own rows.
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  for (const unsigned int degree : {1u, 2u})
  {
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solve(film, conditions, Cavitation::jfo, 4, 64, degree, &solver);
    JFOSolver jfo(solver);
    const auto [from_cells, assembled] = jfo.full_film_rhs_both_ways();
    ASSERT_EQ(from_cells.size(), assembled.size());
    std::size_t different_bits = 0, nonzero = 0;
    for (std::size_t i = 0; i < assembled.size(); ++i)
    {
      different_bits += std::memcmp(&from_cells[i], &assembled[i], sizeof(double)) != 0;
      nonzero += assembled[i] != 0;
    }
    EXPECT_GT(dealii::Utilities::MPI::sum(double(nonzero), MPI_COMM_WORLD),
              0.0); // not a comparison of zeros
    EXPECT_EQ(different_bits, 0u) << "degree " << degree << ": of " << assembled.size();
  }
}

TEST(CavitationFE, JfoJacobianByColumnsGivesTheCellLoopsLinearisedLoads)
{
  // This case converges at the residual-only check after a successful polish, so its Jacobian at
  // the solution, the one the linearised loads solve with, is the column combination of the
  // global P A and G (JFOSolver::jacobian_by_columns): the counter shows the path ran. At the same
  // solution the cell loop (assemble()) builds it again (JFOSolver::jacobian_at_solution).
  // Column j is P A(:, j) + e_j G(:, j) or G(:, j) + e_j P A(:, j) with |e_j| <= 1 (the ratio of
  // the complementarity derivatives, the smaller over the larger); the cell loop sums that per
  // cell. Both evaluate sums of at most 4 cell terms (the cells around a vertex) each bounded by
  // T = max |P A| + max |G| (the term bound of the test above), with a product and an addition
  // more: they differ by at most 2 x 6 u x 4 T = 24 eps T per entry (and not at all where
  // e_j = 0: x + 0 y = x). The linearised loads (a stiffness direction dh and a damping
  // direction dh/dt) solve one system with either matrix and the same right-hand side: equal to
  // the bit where no entry differs. The hook's by-columns Jacobian must give the loads of the
  // solve's own (the same operations).
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  const double eps = std::numeric_limits<double>::epsilon();
  ReynoldsSolver solver(MPI_COMM_WORLD);
  solver.cavitation.tolerance = 1e-10;
  const unsigned int by_columns_before = JFOSolver::jacobians_by_columns,
                     by_cells_before = JFOSolver::jacobians_by_cells;
  const FilmLoads loads = solve(film, conditions, Cavitation::jfo, 16, 256, 2, &solver);
  ASSERT_GT(loads.cavitated_fraction, 0.05);
  EXPECT_EQ(JFOSolver::jacobians_by_columns - by_columns_before, 1u);
  EXPECT_EQ(JFOSolver::jacobians_by_cells - by_cells_before, 0u);
  const auto tilt_x = [](double r, double t) { return 1e-7 + 1e-5 * r * std::sin(t); };
  const std::vector<FilmPerturbation> directions = {{tilt_x, {}}, {{}, tilt_x}};
  const std::vector<FilmLoads> of_solve = solver.linearized_loads(directions);

  JFOSolver jfo(solver);
  const JFOSolver::GlobalMatricesAndAssembly global = jfo.global_matrices_and_assembly();
  // (every rank leaves together: the calls below are collective)
  const auto on_every_rank = [](const bool here)
  { return dealii::Utilities::MPI::min(here ? 1 : 0, MPI_COMM_WORLD) == 1; };
  ASSERT_TRUE(on_every_rank(!global.PA.empty()));
  double T = 0;
  for (const auto *m : {&global.assembled_PA, &global.assembled_G})
    T += std::abs(*std::max_element(m->begin(), m->end(),
                                    [](double x, double y) { return std::abs(x) < std::abs(y); }));
  const std::vector<double> by_columns = jfo.jacobian_at_solution(true);
  ASSERT_TRUE(on_every_rank(!by_columns.empty()));
  const std::vector<FilmLoads> of_columns = solver.linearized_loads(directions);
  const std::vector<double> by_cells = jfo.jacobian_at_solution(false);
  ASSERT_TRUE(on_every_rank(by_cells.size() == by_columns.size()));
  const std::vector<FilmLoads> of_cells = solver.linearized_loads(directions);

  double worst = 0;
  std::size_t different = 0;
  for (std::size_t e = 0; e < by_cells.size(); ++e)
  {
    worst = std::max(worst, std::abs(by_columns[e] - by_cells[e]) / (24 * eps * T));
    different += by_columns[e] != by_cells[e];
  }
  std::cout << by_cells.size() << " Jacobian entries, " << different
            << " differ; worst difference / bound " << worst << "\n";
  EXPECT_LE(worst, 1.0);
  for (std::size_t d = 0; d < directions.size(); ++d)
  {
    const char *name = d == 0 ? "stiffness" : "damping";
    std::cout << name << ": dF/dh " << of_cells[d].force_z << " (cells), " << of_columns[d].force_z
              << " (columns), dMx/dh " << of_cells[d].moment_x << ", " << of_columns[d].moment_x
              << "\n";
    ASSERT_NE(of_cells[d].force_z, 0.0) << name;
    EXPECT_EQ(of_columns[d].force_z, of_solve[d].force_z) << name;
    EXPECT_EQ(of_columns[d].moment_x, of_solve[d].moment_x) << name;
    if (different == 0)
    {
      EXPECT_EQ(of_columns[d].force_z, of_cells[d].force_z) << name;
      EXPECT_EQ(of_columns[d].moment_x, of_cells[d].moment_x) << name;
      EXPECT_EQ(of_columns[d].moment_y, of_cells[d].moment_y) << name;
    }
  }
  EXPECT_EQ(different, 0u); // e_j = 0 at every node of this solution (a_j + v_j > 0)
}

TEST(CavitationFE, JfoLowRankUpdateGivesTheFactorisedRoundsSolution)
{
  // A global active-set round whose set differs from the last factorised one in at most
  // JFOSolver::low_rank_limit nodes solves by a Sherman-Morrison-Woodbury update of that
  // factorisation (sparse_direct.h, solve_column_update) instead of a new one. It solves the same
  // linear system to round-off (its backward error is checked), so the iteration takes the same
  // rounds (up to a node at the flip threshold, below) and ends on the same set, where the problem
  // is linear: the loads agree to the Newton tolerance, and the mass balance holds (1e-8, as above)
  // either way.
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  const double tolerance = 1e-10;
  FilmLoads l[2];
  unsigned int updates[2], rounds[2], factorizations[2];
  const unsigned int limit = JFOSolver::low_rank_limit;
  for (const bool with_update : {false, true})
  {
    JFOSolver::low_rank_limit = with_update ? limit : 0;
    ReynoldsSolver solver(MPI_COMM_WORLD);
    l[with_update] = converged_jfo(film, conditions, 16, 256, tolerance, solver);
    updates[with_update] = solver.low_rank_updates();
    rounds[with_update] = solver.active_set_rounds();
    factorizations[with_update] = solver.linear_solver_statistics().statistics().factorizations;
  }
  JFOSolver::low_rank_limit = limit;
  std::cout << "low-rank updates " << updates[1] << ", factorisations " << factorizations[0]
            << " -> " << factorizations[1] << ", active-set rounds " << rounds[1] << "\n";
  EXPECT_EQ(updates[0], 0u);
  EXPECT_GE(updates[1], 1u); // the confirming round at least
  // The update's answer equals the factorised one to round-off, so the sets agree except where
  // a node sits at the flip threshold (-1e-12), where round-off may flip it in one run and not
  // the other: that costs a round or two, so the counts may differ by that much
  const auto differ = [](const long a, const long b) { return std::abs(a - b); };
  EXPECT_LE(differ(rounds[0], rounds[1]), 2);
  EXPECT_LE(differ(factorizations[1] + updates[1], factorizations[0]), 2);
  expect_same_jfo_solution(l[0], l[1], tolerance, film.outer_radius);
}

TEST(CavitationFE, JfoWithSinglePrecisionFactorsIsTheDoubleSolution)
{
  // Above SparseDirect::single_precision_limit the Newton systems are factorised in single
  // precision and every solve (and low-rank update) refined in double to a double solve's
  // backward error, so the rounds solve the same linear systems to round-off and end on the same
  // set: the loads agree to the Newton tolerance and the mass balance holds (1e-8). The tilted
  // seal at 33 024 dofs (MUMPS) with the limit lowered below its size, against the limit above.
  FilmThickness film = tilted_seal();
  const OperatingConditions conditions;
  const double tolerance = 1e-10;
  const long long limit = SparseDirect::single_precision_limit;
  FilmLoads l[2];
  FilmLinearSolver::Statistics work[2];
  for (const bool single : {false, true})
  {
    SparseDirect::single_precision_limit = single ? 20000 : 1LL << 40;
    ReynoldsSolver solver(MPI_COMM_WORLD);
    l[single] = converged_jfo(film, conditions, 64, 128, tolerance, solver);
    work[single] = solver.linear_solver_statistics().statistics();
  }
  SparseDirect::single_precision_limit = limit;
  std::cout << "single precision: factorisations " << work[1].factorizations << " ("
            << work[1].single_precision_factorizations << " single), refinement steps "
            << work[1].refinement_steps << ", fallbacks " << work[1].refinement_fallbacks << "\n";
  EXPECT_EQ(work[0].single_precision_factorizations, 0u);
  EXPECT_EQ(work[0].refinement_steps, 0u);
  ASSERT_GE(work[1].factorizations, 1u);
  EXPECT_EQ(work[1].single_precision_factorizations, work[1].factorizations);
  EXPECT_GE(work[1].refinement_steps, work[1].solves); // every solve refines at least once
  EXPECT_EQ(work[1].refinement_fallbacks, 0u);
  expect_same_jfo_solution(l[0], l[1], tolerance, film.outer_radius);
}

TEST(CavitationFE, JfoBandStartGivesTheGlobalRoundsSolution)
{
  // A level started from the coarse one may begin with band rounds about the start's cavity
  // boundary instead of a global round (JFOSolver::polish). Only a global round without flips is
  // accepted either way, and on that set the problem is linear, so both end on the same solution:
  // the loads agree to the Newton tolerance and the mass balance holds (1e-8, as above). The
  // tilted Varney & Green seal (eps = 0.5, the speed benchmark's case; 33 024 dofs, MUMPS) takes
  // the band start on every level; the counts are printed (measured: 2 -> 1 factorisations).
  FilmThickness film = tilted_seal();
  const OperatingConditions conditions;
  const double tolerance = 1e-10;
  FilmLoads l[2];
  unsigned int rounds[2], band_rounds[2], factorizations[2], updates[2];
  bool failed[2];
  for (const bool band_start : {false, true})
  {
    JFOSolver::band_start = band_start;
    ReynoldsSolver solver(MPI_COMM_WORLD);
    l[band_start] = converged_jfo(film, conditions, 64, 128, tolerance, solver);
    rounds[band_start] = solver.active_set_rounds();
    band_rounds[band_start] = solver.band_rounds();
    factorizations[band_start] = solver.linear_solver_statistics().statistics().factorizations;
    updates[band_start] = solver.low_rank_updates();
    failed[band_start] = solver.band_start_failed();
  }
  JFOSolver::band_start = true;
  std::cout << "finest level: active-set rounds " << rounds[0] << " -> " << rounds[1]
            << ", factorisations " << factorizations[0] << " -> " << factorizations[1]
            << ", low-rank updates " << updates[0] << " -> " << updates[1] << "\n";
  EXPECT_TRUE(failed[0]);  // the hook turned it off
  EXPECT_FALSE(failed[1]); // taken, and the global round found the band rounds' set nearly right
  // taken on the finest level: band rounds before its first global round, which then needs no
  // more factorisations than the global start (a set nearer the solution's)
  EXPECT_GT(band_rounds[1], band_rounds[0]);
  EXPECT_LE(factorizations[1], factorizations[0]);
  expect_same_jfo_solution(l[0], l[1], tolerance, film.outer_radius);
}

TEST(CavitationFE, CoarseLevelsFreeTheirFactorisationsAndRunAgainAlike)
{
  // The JFO starts from the solution on the mesh twice as coarse (ReynoldsSolver::
  // coarse_level_state), whose solver is kept for the next run on the mesh; its factorisation is
  // freed once its solution is taken, before the finer level factorises. A second run on the same
  // solver then analyses the coarse patterns again and must end on the same discrete solution:
  // the loads to the Newton tolerance, the mass balance to 1e-8 (as above). The tilted Varney &
  // Green seal at 33 024 dofs (MUMPS on the finest level, KLU below).
  FilmThickness film = tilted_seal();
  const OperatingConditions conditions;
  const double tolerance = 1e-10;
  ReynoldsSolver solver(MPI_COMM_WORLD);
  const FilmLoads first = converged_jfo(film, conditions, 64, 128, tolerance, solver);
  const ReynoldsSolver *coarse = solver.coarse_level_solver();
  ASSERT_NE(coarse, nullptr) << "the run did not start from the coarse level";
  ASSERT_NE(coarse->coarse_level_solver(), nullptr) << "only one coarse level";
  // factorised during the run, holding no factorisation after it, on every coarse level
  for (const ReynoldsSolver *level = coarse; level; level = level->coarse_level_solver())
  {
    EXPECT_GT(level->linear_solver_statistics().statistics().factorizations, 0u);
    EXPECT_STREQ(level->linear_solver_statistics().direct_package(), "");
  }
  EXPECT_STRNE(solver.linear_solver_statistics().direct_package(), ""); // the finest keeps its own
  // the finest level (MUMPS) analysed in the nested dissection of its node grid
  // (polar_node_grid.h), the coarse levels' MUMPS sizes too (8 320 dofs and less: KLU)
  EXPECT_GE(solver.linear_solver_statistics().statistics().nested_dissection_analyses, 1u);
  const FilmLoads second = converged_jfo(film, conditions, 64, 128, tolerance, solver);
  EXPECT_EQ(solver.coarse_level_solver(), coarse); // the coarse level (and its mesh) reused
  for (const ReynoldsSolver *level = coarse; level; level = level->coarse_level_solver())
    EXPECT_STREQ(level->linear_solver_statistics().direct_package(), ""); // freed again
  expect_same_jfo_solution(first, second, tolerance, film.outer_radius);
}

TEST(CavitationFE, JfoStartsFromTheFullFilmWhereACoarseLevelFails)
{
  // A level whose coarse level fails starts from the full film instead (coarse_level_state,
  // JFOSolver::warm_start), also where that coarse level was solved while the level's mesh was
  // made on another thread (setup_while_coarse_levels_run: one rank, more than 200 cells). The
  // source hook adds nothing (h_t + 0) and throws at its first call, which the coarsest level
  // makes (the levels run coarsest first): its parent, of 16 x 32 cells, takes the full-film
  // start. Both runs end on the same discrete JFO solution: the loads to the Newton tolerance,
  // the mass balance to 1e-8 (as above). The tilted Varney & Green seal, 64 x 128 cells.
  FilmThickness film = tilted_seal();
  const OperatingConditions conditions;
  const double tolerance = 1e-10;
  FilmLoads l[2];
  unsigned int throws[2];
  for (const bool fail : {false, true})
  {
    std::atomic<unsigned int> calls{0}, thrown{0};
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solver.source = [&, fail](const dealii::Point<2> &)
    {
      if (fail && calls++ == 0)
      {
        ++thrown;
        throw std::runtime_error("the test's failing source");
      }
      return 0.0;
    };
    l[fail] = converged_jfo(film, conditions, 64, 128, tolerance, solver);
    throws[fail] = thrown;
    if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    {
      // three coarse levels at least, the coarsest of them the failed one
      const ReynoldsSolver *level = solver.coarse_level_solver();
      unsigned int levels = 0;
      for (; level; level = level->coarse_level_solver())
        ++levels;
      EXPECT_GE(levels, 3u);
    }
  }
  EXPECT_EQ(throws[0], 0u);
  EXPECT_EQ(throws[1], 1u);
  expect_same_jfo_solution(l[0], l[1], tolerance, film.outer_radius);
}

TEST(CavitationFE, JfoOnSeveralRanksWithSharedFactorisationsIsTheSameSolution)
{
  // On several ranks the direct factorisations can be shared over the ranks by a separator
  // (SparseDirect::substructured_limit, numerics::SubstructuredLU): the finest level's
  // distributed Jacobians, its band solves, and the coarse levels that every rank holds whole.
  // Exact algebra in another order: the run must end on the discrete solution of the run that
  // factorises each matrix whole (the loads to the Newton tolerance, the mass balance to 1e-8).
  // The tilted Varney & Green seal at 33 024 dofs (coarse levels of 8 320 and 2 112 dofs), with
  // the limit lowered to 2 000 unknowns so that every level takes the shared path.
  // (ctest cavitation_fe_on_2_ranks, _3_)
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) < 2)
    GTEST_SKIP() << "needs two ranks or more (ctest cavitation_fe_on_{2,3}_ranks)";
  FilmThickness film = tilted_seal();
  const OperatingConditions conditions;
  const double tolerance = 1e-10;
  const long long limit = SparseDirect::substructured_limit;
  struct RestoreLimit
  {
    long long value;
    ~RestoreLimit() { SparseDirect::substructured_limit = value; }
  } restore{limit};
  FilmLoads l[2];
  for (const bool share : {false, true})
  {
    SparseDirect::substructured_limit = share ? 2000 : std::numeric_limits<long long>::max();
    ReynoldsSolver solver(MPI_COMM_WORLD);
    l[share] = converged_jfo(film, conditions, 64, 128, tolerance, solver);
    // the global rounds' factorisations shared or not, on the finest level (distributed) and on
    // the first coarse level (whole on every rank)
    const ReynoldsSolver *coarse = solver.coarse_level_solver();
    ASSERT_NE(coarse, nullptr);
    for (const ReynoldsSolver *level : {static_cast<const ReynoldsSolver *>(&solver), coarse})
    {
      const FilmLinearSolver::Statistics &work = level->linear_solver_statistics().statistics();
      EXPECT_GT(work.factorizations, 0u);
      EXPECT_EQ(work.substructured_factorizations, share ? work.factorizations : 0u);
    }
  }
  expect_same_jfo_solution(l[0], l[1], tolerance, film.outer_radius);
}

TEST(CavitationFE, JfoMeshConvergence)
{
  // Three meshes, each twice as fine in r and theta; the observed order from successive
  // differences (the reference-based study is tests/long/cavitation_convergence.cc).
  const FilmThickness film = wavy_film();
  const OperatingConditions conditions = low_pressure();
  std::vector<FilmLoads> l;
  for (const unsigned int k : {1u, 2u, 4u})
    l.push_back(solve(film, conditions, Cavitation::jfo, 2 * k, 32 * k, 2));
  auto order = [&](const char *name, double FilmLoads::*m)
  {
    const double d0 = std::abs(l[0].*m - l[1].*m), d1 = std::abs(l[1].*m - l[2].*m);
    std::cout << name << ": " << l[0].*m << ", " << l[1].*m << ", " << l[2].*m
              << "; observed order " << std::log2(d0 / d1) << "\n";
    return std::log2(d0 / d1);
  };
  // The free boundary limits the asymptotic order to about 1 (the film fraction jumps at
  // reformation); force and cavitated fraction converge at least at that order on these meshes
  // (measured 3.0 and 1.5). The moment is reported only: on these meshes it is not yet
  // monotone (tests/long/cavitation_convergence.cc has the study against a fine reference).
  EXPECT_GT(order("force_z", &FilmLoads::force_z), 0.8);
  EXPECT_GT(order("cavitated_fraction", &FilmLoads::cavitated_fraction), 0.8);
  order("moment_x", &FilmLoads::moment_x);
}

struct HardCase
{
  const char *name;
  FilmThickness film;
  OperatingConditions conditions;
};

class CavitationHardCases : public ::testing::TestWithParam<int>
{
};

std::vector<HardCase> hard_cases()
{
  std::vector<HardCase> cases;
  for (const double eps : {0.95, 0.99})
  {
    HardCase c{eps == 0.95 ? "tilt eps 0.95" : "tilt eps 0.99", FilmThickness(),
               OperatingConditions()};
    c.film.coning = 0;
    c.film.tilt = eps * c.film.clearance / c.film.outer_radius;
    c.conditions.inner_pressure = 0;
    c.conditions.outer_pressure = 1e5;
    cases.push_back(c);
  }
  {
    HardCase c{"1e4 rad/s, 10 kPa", FilmThickness(), OperatingConditions()};
    c.film.tilt = 0.5 * c.film.clearance / c.film.outer_radius;
    c.conditions.rotor_speed = 1e4;
    c.conditions.inner_pressure = 0;
    c.conditions.outer_pressure = 1e4;
    cases.push_back(c);
  }
  for (const double n : {1.0, 2.0, 6.0, 12.0})
  {
    HardCase c{"waviness", wavy_film(0.9, n), low_pressure()};
    c.film.tilt = 0;
    cases.push_back(c);
  }
  return cases;
}

TEST_P(CavitationHardCases, ConvergesAndConservesMass)
{
  const HardCase c = hard_cases()[GetParam()];
  ReynoldsSolver solver(MPI_COMM_WORLD);
  dealii::Timer timer;
  const FilmLoads l = solve(c.film, c.conditions, Cavitation::jfo, 8, 128, 2, &solver);
  std::cout << c.name << " (waves " << c.film.wave_number << "): " << solver.nonlinear_iterations()
            << " Newton iterations (+" << solver.coarse_nonlinear_iterations()
            << " on coarser meshes), " << timer.wall_time() << " s, cavitated "
            << l.cavitated_fraction << ", force " << l.force_z << " N\n";
  EXPECT_TRUE(std::isfinite(l.force_z));
  EXPECT_GT(l.cavitated_fraction, 0.0);
  EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer),
            1e-8 * std::max(std::abs(l.leakage_inner), std::abs(l.leakage_outer)));
}

INSTANTIATE_TEST_SUITE_P(Jfo, CavitationHardCases, ::testing::Range(0, 7));

TEST(CavitationFE, NoSupplyIsRefusedClearly)
{
  FilmThickness film = wavy_film();
  OperatingConditions conditions;
  conditions.inner_pressure = conditions.outer_pressure = 0; // = p_cav
  try
  {
    solve(film, conditions, Cavitation::jfo);
    FAIL() << "expected an error";
  }
  catch (std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("not unique"), std::string::npos) << e.what();
  }
}
