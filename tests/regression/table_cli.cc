// `sealfe coefficients` and `sealfe table` through the command line: the summary.json contract,
// the CSV layout (header with units, one row per point), a failing point reported in its row
// while the rest of the table is kept, the same file on 1 and 2 MPI ranks, and the held-out error
// of an FE table falling with grid refinement. Bad input: tests/input/table_cli_input.cc.
#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/coefficients/table_sweep.h>
#include <sealfe/numerics/number_lists.h>

#include "../sealfe_cli.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace sealfe;

namespace
{
using Result = sealfe::testing::CliResult;
using sealfe::testing::read_file;
using sealfe::testing::run_sealfe;

fs::path work_dir(const std::string &name)
{
  return sealfe::testing::fresh_directory("sealfe_table_cli_" + name);
}

/// A mesh small enough for many points per second.
const std::string small_mesh = "subsection Discretization\n  set Radial cells = 4\n"
                               "  set Circumferential cells = 32\nend\n";

std::vector<std::string> lines(const std::string &text)
{
  std::vector<std::string> l;
  std::istringstream s(text);
  for (std::string line; std::getline(s, line);)
    l.push_back(line);
  return l;
}

bool have_mpirun()
{
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
}

/// This test is itself an MPI process (singleton): its OMPI_/PMIX_ variables must not reach the
/// mpirun it starts, or that mpirun takes itself for a child of this job.
const std::string mpirun_env =
    "for v in $(env | cut -d= -f1 | grep -E '^(OMPI_|PMIX_|OPAL_)'); do unset $v; done; "
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
    "OMPI_MCA_rmaps_base_oversubscribe=1 ";
} // namespace

TEST(CoefficientsCli, SummaryHasStiffnessDampingAndTheirErrors)
{
  // Twice as fine as small_mesh: the estimate assumes the H1 rate, |L_h - L_2h| / (2^k - 1)
  // (the same formula as the loads'), which on 4 x 32 cells is 1.3-1.7e-2 of the entries.
  const std::string mesh = "subsection Discretization\n  set Radial cells = 8\n"
                           "  set Circumferential cells = 64\nend\n";
  const fs::path d = work_dir("coefficients");
  const Result r = run_sealfe(d, "coefficients", mesh);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto s = nlohmann::json::parse(read_file(d / "out" / "summary.json"));
  for (const char *key : {"stiffness", "damping"})
  {
    ASSERT_EQ(s[key].size(), 3u);
    for (const auto &row : s[key])
      EXPECT_EQ(row.size(), 3u);
    ASSERT_EQ(s["error_estimate"][key].size(), 3u);
    // The estimate is small against the (dominant) direct entries.
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_LT(s["error_estimate"][key][i][i].get<double>(),
                1e-2 * std::abs(s[key][i][i].get<double>()));
  }
  for (const char *key : {"force_z", "moment_x", "leakage_outer", "dofs", "coefficient_method",
                          "linearization", "narrow_seal_reference", "coefficient_cost_ratio"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_EQ(s["film_model_level"], 2);
  EXPECT_EQ(s["coefficient_method"], "perturbation");
  // The linear solver's work: one solve of the operating point (2176 unknowns: factorised), and
  // six linearised solves with its factorisation (none of their own).
  EXPECT_EQ(s["linear_solver"]["method"], "direct");
  EXPECT_EQ(s["linear_solver"]["solves"], 1);
  EXPECT_EQ(s["linear_solver"]["factorizations"], 1);
  EXPECT_EQ(s["coefficient_linear_solver"]["method"], "direct");
  EXPECT_EQ(s["coefficient_linear_solver"]["solves"], 6);
  EXPECT_EQ(s["coefficient_linear_solver"]["factorizations"], 0);

  // The finite-difference check from the command line gives the same matrices.
  const fs::path d2 = work_dir("coefficients_fd");
  const Result r2 = run_sealfe(d2, "coefficients",
                               mesh + "subsection Coefficients\n  set Method = finite difference\n"
                                      "end\n");
  ASSERT_EQ(r2.status, 0) << r2.err;
  const auto s2 = nlohmann::json::parse(read_file(d2 / "out" / "summary.json"));
  // central differences: 12 perturbed full-film solves, one factorisation and solve each
  EXPECT_EQ(s2["coefficient_linear_solver"]["solves"], 12);
  EXPECT_EQ(s2["coefficient_linear_solver"]["factorizations"], 12);
  EXPECT_EQ(s2["linear_solver"]["solves"], 1);
  for (const char *key : {"stiffness", "damping"})
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_NEAR(s2[key][i][i].get<double>(), s[key][i][i].get<double>(),
                  1e-5 * std::abs(s[key][i][i].get<double>()));
}

TEST(TableCli, OneRowPerPointAndAFailingPointKeepsTheRest)
{
  // Tilts of 0, 1e-5 and 5e-5 rad at two speeds: 5e-5 rad touches down (5e-5 * 0.0408 m > C0)
  // and so does the held-out point between 1e-5 and 5e-5.
  const fs::path d = work_dir("failing");
  const Result r = run_sealfe(d, "table",
                              small_mesh + "subsection Table\n  set Rotor speed = 500, 1500\n"
                                           "  set Clearance =\n  set Tilt = 0, 1e-5, 5e-5\n"
                                           "  set Held-out points = 1\nend\n");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(read_file(d / "out" / "coefficients.csv"));
  ASSERT_EQ(rows.size(), 1u + 6u + 1u); // header, 6 grid points, 1 held-out
  EXPECT_EQ(rows[0], coefficient_table_format::header(true));
  EXPECT_NE(rows[0].find("rotor_speed [rad/s]"), std::string::npos);
  EXPECT_NE(rows[0].find("K_tx_ty [N m/rad]"), std::string::npos);
  EXPECT_NE(rows[0].find("D_z_z [N s/m]"), std::string::npos);
  unsigned int failed = 0;
  for (unsigned int i = 1; i < rows.size(); ++i)
  {
    const bool touches = rows[i].find(",5e-05,") != std::string::npos ||
                         rows[i].find(",check,") != std::string::npos;
    if (touches)
    {
      ++failed;
      EXPECT_NE(rows[i].find(",failed: "), std::string::npos) << rows[i];
      EXPECT_NE(rows[i].find("touches down"), std::string::npos) << rows[i];
    }
    else
      EXPECT_EQ(rows[i].substr(rows[i].size() - 3), ",ok") << rows[i];
  }
  EXPECT_EQ(failed, 3u);
  EXPECT_NE(r.err.find("FAILED"), std::string::npos);
  EXPECT_NE(r.err.find("point 3/7"), std::string::npos) << r.err;
  const auto s = nlohmann::json::parse(read_file(d / "out" / "summary.json"));
  EXPECT_EQ(s["failed_points"], 3);
  EXPECT_EQ(s["grid_points"], 6);
  // The table reads back; interpolation between the good tilts works.
  const CoefficientTable table((d / "out" / "coefficients.csv").string(),
                               CoefficientTable::Interpolation::linear);
  EXPECT_EQ(table.n_failed_points(), 2u);
  FilmThickness film;
  OperatingConditions conditions;
  film.tilt = 0.5e-5;
  conditions.rotor_speed = 1000;
  EXPECT_GT(table.coefficients(film, conditions).tilt_direct_damping(), 0);
}

TEST(TableCli, TwoRanksWriteTheSameFile)
{
  if (!have_mpirun())
    GTEST_SKIP() << "mpirun not found";
  const std::string body = small_mesh + "subsection Table\n  set Rotor speed = 0 : 3000 : 4\n"
                                        "  set Clearance = 1e-6, 1.5e-6\nend\n";
  const fs::path d1 = work_dir("np1"), d2 = work_dir("np2");
  const Result r1 = run_sealfe(d1, "table", body, mpirun_env + "mpirun -np 1 ");
  const Result r2 = run_sealfe(d2, "table", body, mpirun_env + "mpirun -np 2 ");
  ASSERT_EQ(r1.status, 0) << r1.err;
  ASSERT_EQ(r2.status, 0) << r2.err;
  EXPECT_EQ(read_file(d1 / "out" / "coefficients.csv"), read_file(d2 / "out" / "coefficients.csv"));
  EXPECT_NE(r2.err.find("[rank 1]"), std::string::npos) << r2.err;
  const auto s = nlohmann::json::parse(read_file(d2 / "out" / "summary.json"));
  EXPECT_EQ(s["mpi_ranks"], 2);
}

TEST(TableCli, HeldOutErrorOfAnFETableFallsAtTheInterpolantsOrder)
{
  // Clearance axes of 3, 5 and 9 nodes over 0.8..1.6 um, held-out points at the centres of cells
  // spread over the axis: multilinear interpolation error h^2 f''/8 at a cell centre, so the
  // largest held-out error falls 4x per halving of h.
  std::vector<double> errors;
  for (const unsigned int n : {3u, 5u, 9u})
  {
    const fs::path d = work_dir("refine" + std::to_string(n));
    const Result r = run_sealfe(
        d, "table",
        small_mesh +
            "subsection Discretization\n  set Error estimate = false\n"
            "end\nsubsection Table\n  set Rotor speed =\n"
            "  set Clearance = 0.8e-6 : 1.6e-6 : " +
            std::to_string(n) + "\n  set Held-out points = 8\n  set Interpolation = linear\nend\n");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = nlohmann::json::parse(read_file(d / "out" / "summary.json"));
    errors.push_back(s["max_held_out_error"]["stiffness"].get<double>());
  }
  for (unsigned int i = 1; i < errors.size(); ++i)
  {
    const double rate = std::log2(errors[i - 1] / errors[i]);
    std::cout << "held-out stiffness error " << errors[i] << ", observed order " << rate << "\n";
    EXPECT_NEAR(rate, 2.0, 0.3);
  }
}

TEST(TableSweep, ListsAndRanges)
{
  EXPECT_EQ(numerics::parse_number_list("3, 1, 2", "X"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(numerics::parse_number_list("0 : 4000 : 5", "X"),
            (std::vector<double>{0, 1000, 2000, 3000, 4000}));
  EXPECT_EQ(numerics::parse_number_list("  ", "X"), std::vector<double>{});
  EXPECT_EQ(numerics::parse_number_list("7:7:1", "X"), std::vector<double>{7});
  EXPECT_THROW(numerics::parse_number_list("1, 1", "X"), std::runtime_error);
  EXPECT_THROW(numerics::parse_number_list("1:2:0", "X"), std::runtime_error);
  OperatingPoint base;
  const SweepPlan plan = SweepPlan::make(
      base, {{"rotor_speed", {0, 1000, 2000}}, {"clearance", {1e-6, 2e-6}}, {"tilt", {}}}, 2);
  EXPECT_EQ(plan.n_grid, 6u);
  ASSERT_EQ(plan.points.size(), 8u);
  EXPECT_EQ(plan.points[1].clearance, 2e-6); // last axis fastest
  EXPECT_EQ(plan.points[6].rotor_speed, 500);
  EXPECT_EQ(plan.points[7].rotor_speed, 1500);
  EXPECT_EQ(plan.points[7].clearance, 1.5e-6);
}
