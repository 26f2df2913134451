// The transient's film levels against each other on one window: level 1 (a table of FE loads made
// beforehand by `sealfe table`) against level 2 (an FE solve at each evaluation) on the same mesh.
// The bound is the table's own report of its interpolation error (held-out points at cell
// centres, summary.json of `sealfe table`), never a number from the transient.
#include "../sealfe_cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

using namespace sealfe::testing;

namespace
{
// Green 2002 Table 1 seal at 1500 rad/s, 100 / 500 kPa, fixed coning 1e-4 rad, full film, no
// contact; radial grading off so that the table's meshes (graded for each clearance) and level
// 2's (built once) are the same mesh: the levels then differ by the interpolation only
const std::string seal = R"(
subsection Geometry
  set Inner radius = 0.0355
  set Outer radius = 0.0408
  set Clearance    = 1e-6
  set Coning       = 1e-4
end
subsection Operating conditions
  set Viscosity = 1.2e-3
  set Inner pressure = 1e5
  set Outer pressure = 5e5
  set Rotor speed = 1500
end
subsection Cavitation
  set Model = none
end
subsection Discretization
  set Polynomial degree     = 2
  set Radial cells          = 4
  set Circumferential cells = 64
  set Radial grading        = false
end
)";

const std::string transient = R"(
subsection Thermal coning
  set Model = none
end
subsection Rotor runout
  set Tilt = 0
end
subsection Face contact
  set Model = none
end
subsection Ramps
  set Speed rest value = 1500
  set Speed steady value = 1500
  set Outer pressure rest value = 5e5
  set Outer pressure steady value = 5e5
  set Inner pressure rest value = 1e5
  set Inner pressure steady value = 1e5
end
)";

} // namespace

// An axial creep at the reference conditions from a clearance of 0.24 um (the equilibrium is at
// 0.21 um): at the start (same state) the film force and leakage of level 1 lie within the
// table's reported interpolation error of level 2's, and the creep of Z over 20 ms differs by no
// more than that force error through the squeeze damping allows (dZ <= t dF / D_zz).
TEST(TransientFilmLevels, TableWithinItsInterpolationErrorOfFiniteElement)
{
  const auto dir = fresh_directory("sealfe_transient_film_levels");
  const auto table_dir = dir / "table";
  std::filesystem::create_directories(table_dir);
  const auto table = run_sealfe(table_dir, "table", seal + R"(
subsection Coefficients
  set Method = perturbation
end
subsection Table
  set Rotor speed     =
  set Clearance       = 0.15e-6 : 0.31e-6 : 9
  set Tilt            = 0 : 4e-6 : 5
  set Held-out points = 2
end
)");
  ASSERT_EQ(table.status, 0) << table.err;
  const auto summary = nlohmann::json::parse(read_file(table_dir / "out" / "summary.json"));
  double force_error = 0, leakage_error = 0;
  for (const auto &h : summary.at("held_out_error"))
  {
    force_error = std::max(force_error, h.at("columns").at("force_z").get<double>());
    leakage_error = std::max(leakage_error, h.at("columns").at("leakage_inner").get<double>());
  }
  ASSERT_GT(force_error, 0);

  std::map<std::string, std::map<std::string, std::vector<double>>> runs;
  for (const std::string level : {"table", "finite element"})
  {
    const auto run_dir = dir / (level == "table" ? "level1" : "level2");
    std::filesystem::create_directories(run_dir);
    const auto r = run_sealfe(run_dir, "transient",
                              seal + transient + R"(
subsection Transient
  set Film level           = )" + level +
                                  R"(
  set Table file           = )" + (table_dir / "out" / "coefficients.csv").string() +
                                  R"(
  set Initial axial offset = -0.76
  set End time             = 0.02
  set Output interval      = 0.01
end
)");
    ASSERT_EQ(r.status, 0) << r.err;
    runs[level] = read_csv(read_file(run_dir / "out" / "transient.csv"));
  }
  const auto &l1 = runs["table"], &l2 = runs["finite element"];
  const auto &F1 = l1.at("film_force"), &F2 = l2.at("film_force");
  const auto &Q1 = l1.at("leakage_inner"), &Q2 = l2.at("leakage_inner");
  const auto &Z1 = l1.at("axial_offset"), &Z2 = l2.at("axial_offset");
  const auto &t = l2.at("time");
  std::cout << "film force at t = 0: level 1 " << F1[0] << " N, level 2 " << F2[0]
            << " N (table's reported error " << force_error << " relative); leakage " << Q1[0]
            << " vs " << Q2[0] << " m^3/s (" << leakage_error << "); Z at " << t.back()
            << " s: " << Z1.back() << " vs " << Z2.back() << " m" << std::endl;
  // the held-out points are two cell centres; the start is another: a factor 2 of margin
  EXPECT_LE(std::abs(F1[0] - F2[0]), 2 * force_error * std::abs(F2[0]));
  EXPECT_LE(std::abs(Q1[0] - Q2[0]), 2 * leakage_error * std::abs(Q2[0]));
  // squeeze damping of the narrow film at 0.24 um: D_zz = 2 pi r_m mu b^3 / h^3 ~ 3e9 N s/m;
  // 1e8 N s/m, well below it, keeps the bound conservative (the coning thickens the film)
  const double D_zz = 1e8;
  EXPECT_LE(std::abs(Z1.back() - Z2.back()),
            t.back() * 2 * force_error * std::abs(F2[0]) / D_zz + 1e-16);
}

// Level 2: a transient at constant conditions started 0.002 C0 off the balance settles on the
// operating point of `sealfe equilibrium` with the same finite-element film. The slow axial root
// is ~ -0.6 1/s here (film stiffness over squeeze damping): after 25 s the start has decayed to
// 0.002 e^-15 ~ 1e-9 C0, below the tolerance (the integrator's 1e-8 and the balance's root).
TEST(TransientFilmLevels, FiniteElementTransientSettlesOnTheEquilibrium)
{
  const auto dir = fresh_directory("sealfe_transient_level2_settles");
  const std::string level2 = "subsection Transient\n  set Film level = finite element\nend\n";
  const auto eq_dir = dir / "equilibrium";
  std::filesystem::create_directories(eq_dir);
  const auto eq = run_sealfe(eq_dir, "equilibrium", seal + transient + level2);
  ASSERT_EQ(eq.status, 0) << eq.err;
  const auto balance = nlohmann::json::parse(read_file(eq_dir / "out" / "summary.json"));
  const double C0 = 1e-6, z_eq = balance.at("axial_offset").get<double>();

  const auto tr_dir = dir / "transient";
  std::filesystem::create_directories(tr_dir);
  std::ostringstream settings;
  settings.precision(17);
  settings << "subsection Transient\n  set Film level = finite element\n"
           << "  set Initial axial offset = " << z_eq / C0 + 0.002 << "\n"
           << "  set End time = 25\n  set Output interval = 25\n"
           << "  set Relative tolerance = 1e-8\n  set Absolute tolerance = 1e-8\nend\n";
  const auto tr = run_sealfe(tr_dir, "transient", seal + transient + settings.str());
  ASSERT_EQ(tr.status, 0) << tr.err;
  const auto csv = read_csv(read_file(tr_dir / "out" / "transient.csv"));
  const double z_end = csv.at("axial_offset").back();
  std::cout << "level 2: Z(25 s) = " << z_end << " m, equilibrium " << z_eq << " m" << std::endl;
  EXPECT_NEAR(z_end / C0, z_eq / C0, 1e-6);
  // the rotor angle column is Int omega dt: omega t at the constant 1500 rad/s (37 500 rad at
  // 25 s; the CSV holds every double exactly, the ramp integral is exact for a constant speed)
  EXPECT_NEAR(csv.at("rotor_angle").back(), 1500.0 * 25, 1e-12 * 1500.0 * 25);
}
