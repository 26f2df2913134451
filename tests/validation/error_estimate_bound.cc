// The error estimate bounds the discretisation error or says that it cannot (issue 14, item 4).
// The three-mesh rule (grid_convergence.h: observed order, Roache's grid convergence index) on
// synthetic sequences q(h) = q* + C h^p of known order, where the error is known exactly; then on
// small film solves against much finer meshes: the estimate of every headline load bounds the
// difference to the reference, and a case out of the asymptotic range is flagged.
#include <sealfe/film/film_summary.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

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
    EXPECT_NEAR(g.estimate,
                3 * std::abs(s.fine - s.coarse) / (std::pow(2.0, g.order_used) - 1),
                1e-12 * g.estimate);
  }
}

// Two terms, C h + D h^2 with D/C = -4 (the two cancel at h = 1/4): the pre-asymptotic sequence
// is non-monotone; the estimate (3 x the larger difference at order 0.5) still bounds the error.
TEST(GridConvergence, NonMonotoneSequence)
{
  const Sequence s = power_law(1, 1.0, -4.0);
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
