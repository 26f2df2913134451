// Validation of Geometry/Film expression (film_expression.h): a formula that reproduces an
// analytic film term gives the same loads to the solver tolerance; its time derivative is the
// squeeze; a formula that touches down, does not parse or names an unknown variable is refused
// with one line; the empty default is exactly the analytic film.
#include <sealfe/coefficients/finite_element_film.h>
#include <sealfe/film/film_expression.h>
#include <sealfe/film/film_force_model.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace sealfe;

namespace
{
FilmSettings parsed(const std::string &geometry)
{
  dealii::ParameterHandler prm;
  FilmSettings::declare_parameters(prm);
  prm.parse_input_from_string("subsection Geometry\n" + geometry + "end\n");
  FilmSettings s;
  s.parse_parameters(prm);
  return s;
}

/// Default seal, tilted (eps = 0.5 at ro) and wavy, ungraded mesh (the grading depends on the
/// analytic coning, which the formula replaces), no error estimate.
FilmSettings tilted(const std::string &geometry, const Cavitation model)
{
  FilmSettings s = parsed(geometry + " set Tilt = 1.2e-5\n set Tilt angle = 0.7\n"
                                     " set Wave amplitude = 0.2e-6\n set Wave number = 3\n");
  s.mesh.radial_grading = false;
  s.mesh.radial_cells = 8;
  s.mesh.circumferential_cells = 64;
  s.estimate_error = false;
  s.cavitation.model = model;
  s.conditions.outer_pressure = 1e5;
  return s;
}

FilmLoads solve(const FilmSettings &s)
{
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  return solver.run();
}

void expect_same_loads(const FilmLoads &a, const FilmLoads &b, const double tolerance)
{
  const double ro = 0.0408;
  const double force = std::abs(a.force_z), leakage = std::abs(a.leakage_outer);
  std::cout << "force " << a.force_z << " vs " << b.force_z << ", moment_x " << a.moment_x << " vs "
            << b.moment_x << ", leakage " << a.leakage_outer << " vs " << b.leakage_outer
            << ", cavitated " << a.cavitated_fraction << " vs " << b.cavitated_fraction << "\n";
  EXPECT_NEAR(a.force_z, b.force_z, tolerance * force);
  EXPECT_NEAR(a.moment_x, b.moment_x, tolerance * force * ro);
  EXPECT_NEAR(a.moment_y, b.moment_y, tolerance * force * ro);
  EXPECT_NEAR(a.leakage_inner, b.leakage_inner, tolerance * leakage);
  EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tolerance * leakage);
  EXPECT_NEAR(a.friction_torque, b.friction_torque, tolerance * std::abs(a.friction_torque));
  EXPECT_NEAR(a.cavitated_fraction, b.cavitated_fraction, tolerance);
}

std::string refusal(const std::string &geometry)
{
  try
  {
    FilmSettings s = parsed(geometry);
    s.geometry.validate();
  }
  catch (std::runtime_error &e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// Coning beta (r - ri) written as a formula with Coning = 0: the film is the same function (to
// round-off), so the discrete problem is the same; the loads agree to the solver tolerance
// (direct solve: round-off; the JFO Newton tolerance 1e-10 relative), 1e-9 of each load's scale.
TEST(FilmExpression, ConingAsAFormulaGivesTheAnalyticLoads)
{
  for (const Cavitation model : {Cavitation::none, Cavitation::jfo})
  {
    const FilmLoads analytic = solve(tilted(" set Coning = 1e-3\n", model));
    const FilmLoads formula = solve(tilted(" set Coning = 0\n set Film expression = b*(r - r_i)\n"
                                           " set Film expression constants = b=1e-3, r_i=0.0355\n",
                                           model));
    expect_same_loads(analytic, formula, 1e-9);
    if (model == Cavitation::jfo)
    {
      EXPECT_GT(analytic.cavitated_fraction, 0.01); // the JFO case does cavitate
    }
  }
}

// The formula's t: a film v t at t = 0 has dh/dt = v, the squeeze of Axial velocity = v. The
// centred difference is exact for a linear function (round-off only).
TEST(FilmExpression, TimeDerivativeIsTheSqueeze)
{
  const FilmLoads velocity = solve(tilted(" set Coning = 1e-3\n", Cavitation::none));
  FilmSettings s = tilted(" set Coning = 1e-3\n", Cavitation::none);
  s.geometry.axial_velocity = 1e-4;
  const FilmLoads squeezed = solve(s);
  const FilmLoads formula = solve(tilted(
      " set Coning = 1e-3\n set Film expression = v*t\n set Film expression constants = v=1e-4\n",
      Cavitation::none));
  expect_same_loads(squeezed, formula, 1e-9);
  // and the squeeze does something (the test is not vacuous)
  EXPECT_GT(std::abs(squeezed.force_z - velocity.force_z), 1e-3 * std::abs(velocity.force_z));
}

// The dynamics passes its time to the film: a formula v t evaluated by the level-2 film at a state
// of time T is the film offset by v T and closing at v (what a transient sees at time T).
TEST(FilmExpression, TheDynamicsStateCarriesTheTime)
{
  const double v = 1e-4, T = 5e-3;
  const FilmSettings formula = tilted(
      " set Coning = 1e-3\n set Film expression = v*t\n set Film expression constants = v=1e-4\n",
      Cavitation::none);
  FilmState state = FilmState::from(formula.geometry, formula.conditions);
  state.time = T;
  const FilmLoads at_t = FiniteElementFilm(formula, MPI_COMM_WORLD).loads(state);
  FilmSettings moved = tilted(" set Coning = 1e-3\n", Cavitation::none);
  moved.geometry.axial_offset = v * T;
  moved.geometry.axial_velocity = v;
  expect_same_loads(solve(moved), at_t, 1e-9);
  // v T = 0.5 um changes the loads (the test is not vacuous)
  EXPECT_GT(
      std::abs(at_t.force_z - solve(tilted(" set Coning = 1e-3\n", Cavitation::none)).force_z),
      1e-2 * std::abs(at_t.force_z));
}

// Derivatives by centred differences: a formula with known derivatives.
TEST(FilmExpression, DerivativesOfAFormula)
{
  const FilmExpression e("a*cos(n*theta)*(r/0.04)^2 + w*t", "a=1e-6, n=8, w=2e-3", 0.0408);
  const double r = 0.038, theta = 0.3, t = 0.01;
  const double a = 1e-6, n = 8, s = (r / 0.04) * (r / 0.04);
  EXPECT_NEAR(e.value(r, theta, t), a * std::cos(n * theta) * s + 2e-3 * t, 1e-20);
  // relative accuracy of the differences: (n 6e-6)^2 / 6 ~ 4e-10 in theta, 1e-10 in r
  EXPECT_NEAR(e.d_dtheta(r, theta, t), -a * n * std::sin(n * theta) * s, 1e-9 * a * n);
  EXPECT_NEAR(e.d_dr(r, theta, t), a * std::cos(n * theta) * 2 * r / (0.04 * 0.04),
              1e-9 * a / 0.04);
  EXPECT_NEAR(e.d_dt(r, theta, t), 2e-3, 1e-9 * 2e-3);
}

TEST(FilmExpression, TouchDownAndBadFormulasAreRefusedInOneLine)
{
  // C0 = 1 um; -2 um cos(theta) touches down at theta = 0
  const std::string touch = refusal(" set Film expression = -2e-6*cos(theta)\n");
  std::cout << touch << "\n";
  EXPECT_NE(touch.find("touches down"), std::string::npos);
  EXPECT_NE(touch.find("Film expression"), std::string::npos);
  for (const std::string bad :
       {" set Film expression = a*cos(\n", " set Film expression = q*r\n",
        " set Film expression = a*r\n set Film expression constants = a=\n",
        " set Film expression = a*r\n set Film expression constants = r=1\n",
        " set Film expression = 1e-6/(r - r)\n"})
  {
    const std::string message = refusal(bad);
    std::cout << message << "\n";
    EXPECT_NE(message.find("Film expression"), std::string::npos) << bad;
    EXPECT_EQ(message.find('\n'), std::string::npos) << bad;
  }
}

// The empty default: no expression object, the film is the analytic one bit for bit.
TEST(FilmExpression, EmptyIsTodaysFilm)
{
  const FilmSettings s = parsed(" set Tilt = 1e-5\n");
  EXPECT_FALSE(s.geometry.expression);
  EXPECT_FALSE(s.geometry.features);
  // h = C0 + beta (r - ri) + gamma r cos(theta - psi) with the defaults C0 = 1e-6 m,
  // beta = 1e-3, ri = 0.0355 m, psi = 0 (film_thickness.h), evaluated in the same order
  const double r = 0.037, theta = 1.1;
  EXPECT_EQ(s.geometry.value(r, theta), 1e-6 + 0.0 + 1e-3 * (r - 0.0355) +
                                            1e-5 * r * std::cos(theta - 0.0) +
                                            0.0 * std::cos(0.0 * (theta - 0.0)));
}
