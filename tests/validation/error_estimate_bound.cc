// The error estimate bounds the discretisation error or says that it cannot (issue 14, item 4).
// The three-mesh rule (grid_convergence.h: observed order, Roache's grid convergence index) on
// synthetic sequences q(h) = q* + C h^p of known order, where the error is known exactly; then on
// small film solves against much finer meshes: the estimate of every headline load bounds the
// difference to the reference, and a case out of the asymptotic range is flagged.
#include <sealfe/film/film_summary.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/film/reynolds_solver.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace sealfe;

namespace
{
struct Sequence
{
  double fine, coarse, coarsest, exact;
};

/// q(h) = q* + C h^p (+ D h^(p + 1)) on h = 1/8, 1/4, 1/2.
Sequence power_law(double p, double C = 1, double D = 0, double exact = 10)
{
  auto q = [&](double h) { return exact + C * std::pow(h, p) + D * std::pow(h, p + 1); };
  return {q(0.125), q(0.25), q(0.5), exact};
}

GridConvergence verdict(const Sequence &s, double expected, double floor = 0)
{
  return grid_convergence(s.fine, s.coarse, s.coarsest, expected, floor, 1e-12);
}
} // namespace

// An exact power law of the expected order: the observed order is that order, the estimate is
// Fs = 1.25 times the exact error (Richardson's extrapolation is exact for a pure power law).
TEST(GridConvergence, ExactPowerLawOfTheExpectedOrder)
{
  for (const double p : {1.0, 2.0, 4.0, 6.0})
  {
    const Sequence s = power_law(p, -3.5);
    const GridConvergence g = verdict(s, p);
    EXPECT_NEAR(g.observed_order, p, 1e-9);
    EXPECT_TRUE(g.asymptotic);
    EXPECT_EQ(g.convergence, "asymptotic");
    EXPECT_EQ(g.safety_factor, 1.25);
    const double error = std::abs(s.fine - s.exact);
    EXPECT_NEAR(g.estimate, 1.25 * error, 1e-9 * error);
  }
}

// An observed order far from the expected one (p = 0.76 where 1 is expected, as on the
// ε = 0.999 JFO case; p = 2.5 where 4 is expected): flagged non-asymptotic, Fs = 3 with the
// order clamped to [0.5, expected], which still bounds the exact error.
TEST(GridConvergence, OrderBelowOrAboveTheExpectedIsFlaggedAndWidened)
{
  for (const auto &[p, expected] : {std::pair{0.76, 1.0}, {2.5, 4.0}, {1.5, 1.0}, {0.3, 1.0}})
  {
    const Sequence s = power_law(p, 2.0);
    const GridConvergence g = verdict(s, expected);
    EXPECT_NEAR(g.observed_order, p, 1e-9);
    EXPECT_FALSE(g.asymptotic);
    EXPECT_EQ(g.convergence, "non-asymptotic");
    EXPECT_EQ(g.safety_factor, 3.0);
    EXPECT_NEAR(g.order_used, std::clamp(p, 0.5, expected), 1e-12);
    const double error = std::abs(s.fine - s.exact);
    EXPECT_GE(g.estimate, error) << p;
    // the GCI at the order used, exactly
    EXPECT_NEAR(g.estimate, 3 * std::abs(s.fine - s.coarse) / (std::pow(2.0, g.order_used) - 1),
                1e-12 * g.estimate);
  }
}

// Two terms, C h + D h^2 with D/C = -2 (the error peaks at h = 1/4): the pre-asymptotic sequence
// is non-monotone; the estimate (3 x the larger difference at order 0.5) still bounds the error.
TEST(GridConvergence, NonMonotoneSequence)
{
  const Sequence s = power_law(1, 1.0, -2.0);
  ASSERT_LT((s.fine - s.coarse) * (s.coarse - s.coarsest), 0);
  const GridConvergence g = verdict(s, 1);
  EXPECT_EQ(g.convergence, "non-monotone");
  EXPECT_FALSE(g.asymptotic);
  const double larger = std::max(std::abs(s.fine - s.coarse), std::abs(s.coarse - s.coarsest));
  EXPECT_NEAR(g.estimate, 3 * larger / (std::sqrt(2.0) - 1), 1e-12 * g.estimate);
  EXPECT_GE(g.estimate, std::abs(s.fine - s.exact));
}

// Pre-asymptotic two-term sequences of the expected leading order, C h^p + D h^(p+1): the
// observed order approaches p from the sequence, and the estimate bounds the exact error for
// correction terms up to the size of the leading one.
TEST(GridConvergence, TwoTermSequencesAreBounded)
{
  for (const double p : {1.0, 4.0})
    for (const double D : {-1.0, -0.5, 0.5, 1.0, 2.0})
    {
      const Sequence s = power_law(p, 1.0, D);
      const GridConvergence g = verdict(s, p);
      EXPECT_GE(g.estimate, std::abs(s.fine - s.exact)) << "p " << p << " D " << D;
    }
}

// Without a third mesh: flagged "two-mesh", Fs = 3 at the expected order, with the reason.
TEST(GridConvergence, TwoMeshFallbackIsFlagged)
{
  const Sequence s = power_law(1, 1.0);
  const GridConvergence g =
      grid_convergence(s.fine, s.coarse, std::nullopt, 1, 0, 1e-12, "1 radial cell");
  EXPECT_EQ(g.convergence, "two-mesh");
  EXPECT_FALSE(g.asymptotic);
  EXPECT_FALSE(std::isfinite(g.observed_order));
  EXPECT_NEAR(g.estimate, 3 * std::abs(s.fine - s.coarse), 1e-12);
  EXPECT_NE(g.reason.find("1 radial cell"), std::string::npos);
  EXPECT_TRUE(g.to_json()["observed_order"].is_null());
}

// The earlier two-mesh figure is a floor; differences at round-off are "round-off".
TEST(GridConvergence, FloorAndRoundOff)
{
  const Sequence s = power_law(4, 1.0);
  const GridConvergence g = verdict(s, 4, 1.0);
  EXPECT_EQ(g.estimate, 1.0);
  const GridConvergence r = grid_convergence(1.0, 1.0 + 1e-16, 1.0 - 1e-16, 4, 2e-16, 1e-12);
  EXPECT_EQ(r.convergence, "round-off");
  EXPECT_TRUE(r.asymptotic);
  EXPECT_EQ(r.estimate, 2e-16);
}

TEST(GridConvergence, ExpectedOrder)
{
  EXPECT_EQ(expected_load_order(2, false), 4.0);
  EXPECT_EQ(expected_load_order(1, false), 2.0);
  EXPECT_EQ(expected_load_order(2, true), 1.0);
}

namespace
{
/// summary.json of a solve of `s` (with its error estimate), as `sealfe solve` reports it.
nlohmann::json solve_summary(const FilmSettings &s)
{
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  const FilmLoads loads = solver.run();
  return finite_element_solve_summary(s, solver, loads, MPI_COMM_WORLD);
}

FilmLoads solve_loads(FilmSettings s, unsigned int degree, unsigned int nr)
{
  s.polynomial_degree = degree;
  s.mesh.radial_cells = nr;
  s.mesh.circumferential_cells = 16 * nr;
  s.estimate_error = false;
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  return solver.run();
}

const std::pair<const char *, double FilmLoads::*> headline_loads[] = {
    {"force_z", &FilmLoads::force_z},
    {"moment_x", &FilmLoads::moment_x},
    {"moment_y", &FilmLoads::moment_y},
    {"leakage_inner", &FilmLoads::leakage_inner},
    {"friction_torque", &FilmLoads::friction_torque},
    {"cavitated_fraction", &FilmLoads::cavitated_fraction}};

/// |q_h - q_exact| <= estimate for every headline load, where q_exact is estimated from the
/// reference as q_ref + (q_ref - q_h) / (ratio^p - 1) (the reference `ratio` times finer, the
/// quantity converging at order p): the reference's own error counts against the estimate.
void expect_bounds(const nlohmann::json &summary, const FilmLoads &fine, const FilmLoads &reference,
                   double ratio, double p)
{
  const double factor = std::pow(ratio, p) / (std::pow(ratio, p) - 1);
  for (const auto &[name, member] : headline_loads)
  {
    const double error = factor * std::abs(fine.*member - reference.*member);
    const double estimate = summary["error_estimate"][name];
    const auto &g = summary["error_estimate"]["grid_convergence"][name];
    std::cout << name << ": value " << fine.*member << ", error " << error << ", estimate "
              << estimate << " (two-mesh " << g["two_mesh_estimate"] << ", "
              << g["convergence"].get<std::string>() << ", observed order " << g["observed_order"]
              << ")\n";
    // 1e-9 relative: the reference's own accuracy where the loads agree to round-off
    EXPECT_LE(error, estimate + 1e-9 * std::abs(reference.*member)) << name;
    EXPECT_GE(estimate, g["two_mesh_estimate"].get<double>()) << name;
  }
}
} // namespace

// Full film (default seal, tilt ε = 0.5, degree 2, 8 x 128): every load's estimate bounds its
// error against a degree-4 solve on 16 x 256 cells (error ~ (h/2)^8 of it: negligible).
TEST(ErrorEstimateBound, FullFilmAgainstAFineDegree4Solve)
{
  FilmSettings s;
  s.geometry.tilt = 0.5 * s.geometry.clearance / s.geometry.outer_radius;
  s.geometry.tilt_angle = 0.3;
  const nlohmann::json summary = solve_summary(s);
  ASSERT_TRUE(summary["error_estimate"]["available"].get<bool>());
  EXPECT_EQ(summary["error_estimate"]["expected_order"].get<double>(), 4.0);
  EXPECT_EQ(summary["error_estimate"]["coarser_dofs"].size(), 2u);
  expect_bounds(summary, solve_loads(s, 2, 8), solve_loads(s, 4, 16), 1e300, 1);
}

// JFO on a flat face tilted to ε = 0.9 (a cavity over ~3/4 of the dam), degree 2 on 4 x 64 cells
// (4h: 1 x 16): every estimate bounds the error against 32 x 512 cells (8x finer; its own error
// counted at the expected order 1 of a cavitating film).
TEST(ErrorEstimateBound, CavitatingJFOAgainstAnEightTimesFinerMesh)
{
  FilmSettings s;
  s.geometry.coning = 0;
  s.geometry.tilt = 0.9 * s.geometry.clearance / s.geometry.outer_radius;
  s.cavitation.model = Cavitation::jfo;
  s.mesh.radial_cells = 4;
  s.mesh.circumferential_cells = 64;
  const nlohmann::json summary = solve_summary(s);
  ASSERT_TRUE(summary["error_estimate"]["available"].get<bool>());
  EXPECT_EQ(summary["error_estimate"]["expected_order"].get<double>(), 1.0);
  expect_bounds(summary, solve_loads(s, 2, 4), solve_loads(s, 2, 32), 8, 1);
}

// ε = 0.999 (JFO, flat face, 8 x 128): the film's thin region, |θ - ψ - π| < sqrt(2(1 - ε)/ε)
// = 0.045 rad, is narrower than one cell (2π/128 = 0.049 rad), so the meshes h, 2h, 4h cannot be
// in the asymptotic range: the force must be flagged, with a warning naming it on stderr.
TEST(ErrorEstimateBound, UnresolvedFilmIsFlaggedAndWarned)
{
  FilmSettings s;
  s.geometry.coning = 0;
  s.geometry.tilt = 0.999 * s.geometry.clearance / s.geometry.outer_radius;
  s.cavitation.model = Cavitation::jfo;
  ::testing::internal::CaptureStderr();
  const nlohmann::json summary = solve_summary(s);
  const std::string err = ::testing::internal::GetCapturedStderr();
  const auto &e = summary["error_estimate"];
  const auto &force = e["grid_convergence"]["force_z"];
  EXPECT_FALSE(force["asymptotic"].get<bool>());
  EXPECT_FALSE(e["asymptotic"].get<bool>());
  EXPECT_NE(force["convergence"].get<std::string>(), "asymptotic");
  EXPECT_EQ(force["safety_factor"].get<double>(), 3.0);
  EXPECT_GT(e["force_z"].get<double>(), force["two_mesh_estimate"].get<double>());
  EXPECT_NE(err.find("sealfe: warning: the error estimate of force_z"), std::string::npos) << err;
  for (const char *key : {"estimate", "asymptotic", "observed_order", "expected_order",
                          "convergence", "two_mesh_estimate", "safety_factor", "reason"})
    EXPECT_TRUE(force.contains(key)) << key;
}

// A mesh that can be halved once but not twice (2 x 32 cells: 1 x 16, then 0.5 radial cells): the
// two-mesh fallback, flagged, with the reason.
TEST(ErrorEstimateBound, TwoMeshFallbackWhenTheMeshCannotBeCoarsenedTwice)
{
  FilmSettings s;
  s.geometry.tilt = 0.5 * s.geometry.clearance / s.geometry.outer_radius;
  s.mesh.radial_cells = 2;
  s.mesh.circumferential_cells = 32;
  const nlohmann::json summary = solve_summary(s);
  const auto &e = summary["error_estimate"];
  ASSERT_TRUE(e["available"].get<bool>());
  EXPECT_EQ(e["coarser_dofs"].size(), 1u);
  const auto &force = e["grid_convergence"]["force_z"];
  EXPECT_EQ(force["convergence"].get<std::string>(), "two-mesh");
  EXPECT_FALSE(force["asymptotic"].get<bool>());
  EXPECT_TRUE(force["observed_order"].is_null());
  EXPECT_NE(force["reason"].get<std::string>().find("cannot be coarsened twice"),
            std::string::npos);
}
