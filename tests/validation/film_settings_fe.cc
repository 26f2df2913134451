// Validation of the film settings aggregate and of what is built from it:
//  - FilmSettings::set/get by prm entry name (the map every sweep uses);
//  - the JFO mesh-sequencing solver solves the same physics as the fine one (a copy of the whole
//    settings: flow factors and contact included);
//  - repeated runs on one geometry reuse the mesh and give the numbers of a fresh solver;
//  - the coefficient error estimate is the load error estimate's formula (2^k - 1);
//  - FiniteElementFilm (level 2 of FilmForceModel): a direct Reynolds solve, the exact
//    axisymmetric coned-face force, one mesh for all states.
#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/coefficients/finite_element_film.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
/// Exact axisymmetric coned face (as in reynolds_exact.cc): r h^3 p' = c, so
/// p = pi + (po - pi) I(r) / I(ro), I(r) = int_ri^r ds / (s h(s)^3), h = a + b s.
struct ConedExact
{
  double ri, ro, C0, beta, pi, po;
  double a() const { return C0 - beta * ri; }
  double antiderivative(double s) const
  {
    const double A = a(), u = A + beta * s;
    if (std::abs(beta * (ro - ri)) < 1e-12 * C0)
      return std::log(s) / (C0 * C0 * C0);
    return std::log(s / u) / (A * A * A) + 1 / (A * A * u) + 1 / (2 * A * u * u);
  }
  double I(double r) const { return antiderivative(r) - antiderivative(ri); }
  double pressure(double r) const { return pi + (po - pi) * I(r) / I(ro); }
  double force() const
  {
    const dealii::QGauss<1> g(10);
    const unsigned int n = 200;
    double f = 0;
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int q = 0; q < g.size(); ++q)
      {
        const double r = ri + (ro - ri) * (k + g.point(q)[0]) / n;
        f += 2 * M_PI * pressure(r) * r * g.weight(q) * (ro - ri) / n;
      }
    return f;
  }
};

/// Rough faces (Patir-Cheng flow factors, GW/CEB contact) with JFO cavitation on a wavy face.
FilmSettings rough_jfo_settings()
{
  FilmSettings s;
  s.cavitation.model = Cavitation::jfo;
  s.geometry.wave_amplitude = 0.4e-6;
  s.geometry.wave_number = 3;
  s.geometry.coning = 0;
  s.conditions.inner_pressure = 1e5;
  s.conditions.outer_pressure = 1e5;
  s.flow_factors = FlowFactors(FlowFactors::Model::patir_cheng, 0.2e-6);
  AsperityContactParameters contact;
  contact.composite_roughness = 0.2e-6;
  s.contact = AsperityContact(AsperityContact::Model::gw_ceb, contact);
  s.mesh.radial_cells = 8;
  s.mesh.circumferential_cells = 64;
  s.estimate_error = false;
  return s;
}

void expect_same_physics(const FilmSettings &a, const FilmSettings &b)
{
  EXPECT_EQ(a.flow_factors.is_smooth(), b.flow_factors.is_smooth());
  EXPECT_EQ(a.flow_factors.composite_roughness(), b.flow_factors.composite_roughness());
  EXPECT_EQ(a.contact.enabled(), b.contact.enabled());
  EXPECT_EQ(a.contact.parameters().composite_roughness, b.contact.parameters().composite_roughness);
  EXPECT_EQ(a.contact.parameters().asperity_density, b.contact.parameters().asperity_density);
  EXPECT_EQ(a.cavitation.model, b.cavitation.model);
  EXPECT_EQ(a.cavitation.pressure, b.cavitation.pressure);
  EXPECT_EQ(a.polynomial_degree, b.polynomial_degree);
  EXPECT_EQ(a.linear_solver, b.linear_solver);
  EXPECT_EQ(a.solver_tolerance, b.solver_tolerance);
  EXPECT_EQ(a.conditions.viscosity, b.conditions.viscosity);
  EXPECT_EQ(a.geometry.wave_amplitude, b.geometry.wave_amplitude);
}
} // namespace

TEST(FilmSettings, SetAndGetByPrmName)
{
  FilmSettings s;
  for (const auto &name : FilmSettings::settable_names())
  {
    s.set(name, 0.25);
    EXPECT_EQ(s.get(name), 0.25) << name;
  }
  s.set("Clearance", 2e-6);
  EXPECT_EQ(s.geometry.clearance, 2e-6);
  s.set("Inner pressure", 1e5);
  s.set("Pressure difference", 3e5);
  EXPECT_EQ(s.conditions.outer_pressure, 4e5);
  s.set("Rotor speed", 500);
  EXPECT_EQ(s.conditions.rotor_speed, 500);
  EXPECT_THROW(s.set("Clearence", 1e-6), std::runtime_error);
  EXPECT_THROW(s.get("nothing"), std::runtime_error);
}

TEST(FilmSettings, ContactTakesTheRoughnessSigma)
{
  dealii::ParameterHandler prm;
  FilmSettings::declare_parameters(prm);
  prm.parse_input_from_string("subsection Roughness\n set Model = patir-cheng\n"
                              " set Composite roughness = 3e-7\nend\n"
                              "subsection Contact\n set Model = gw-ceb\nend\n");
  FilmSettings s;
  s.parse_parameters(prm);
  EXPECT_EQ(s.contact.parameters().composite_roughness, 3e-7);
  EXPECT_EQ(s.flow_factors.composite_roughness(), 3e-7);
}

// The mesh-sequencing (coarse) solver of a JFO solve used to get a hand-made copy of the settings
// without the flow factors and the contact model: a rough-face solve was warm-started from
// smooth-film physics. Its settings must equal the fine solver's.
TEST(FilmSettings, JfoCoarseLevelSolvesTheSamePhysics)
{
  ReynoldsSolver solver(rough_jfo_settings(), MPI_COMM_WORLD);
  const FilmLoads loads = solver.run();
  ASSERT_NE(solver.coarse_level_solver(), nullptr) << "no mesh sequencing on this mesh";
  expect_same_physics(solver.coarse_level_solver()->settings, solver.settings);
  EXPECT_GT(solver.coarse_nonlinear_iterations(), 0u);
  EXPECT_GT(loads.contact_force, 0.0);
  EXPECT_GT(loads.cavitated_fraction, 0.0);
}

TEST(FilmSettings, RepeatedRunsReuseTheMesh)
{
  FilmSettings s;
  s.geometry.tilt = 0.3 * s.geometry.clearance / s.geometry.outer_radius;
  ReynoldsSolver reused(s, MPI_COMM_WORLD);
  reused.run();
  const auto n = reused.n_dofs();
  for (const double z : {-0.2e-6, 0.1e-6, 0.3e-6})
  {
    FilmSettings t = s;
    t.geometry.axial_offset = z;
    t.geometry.tilt_rate_x = 0.01;
    t.set("Rotor speed", 300 + 1e9 * z);
    t.set("Outer pressure", 3e5 + 1e11 * z);
    const FilmLoads a = reused.run(t.geometry, t.conditions);
    ReynoldsSolver fresh(t, MPI_COMM_WORLD);
    const FilmLoads b = fresh.run();
    EXPECT_NEAR(a.force_z / b.force_z, 1.0, 1e-12);
    EXPECT_NEAR(a.moment_x / b.moment_x, 1.0, 1e-10);
    EXPECT_NEAR(a.leakage_outer / b.leakage_outer, 1.0, 1e-10);
    EXPECT_EQ(reused.n_dofs(), n);
  }
  EXPECT_EQ(reused.n_setups(), 1u);
  // A new clearance changes the radial grading: a new mesh.
  FilmSettings u = s;
  u.geometry.clearance *= 1.5;
  reused.run(u.geometry, u.conditions);
  EXPECT_EQ(reused.n_setups(), 2u);
}

// The coefficient error estimate used 2^(k+1) - 1 while the loads used 2^k - 1 for the same kind
// of quantity: both must be at least |X_h - X_2h| / (2^k - 1) (the two-mesh floor), and both
// follow the same three-mesh rule (grid_convergence, meshes h, 2h, 4h; issue 14, item 4).
TEST(FilmSettings, CoefficientErrorEstimateIsTheLoadFormula)
{
  FilmSettings s;
  s.mesh.radial_cells = 4;
  s.mesh.circumferential_cells = 64;
  s.geometry.tilt = 0.3 * s.geometry.clearance / s.geometry.outer_radius;
  CoefficientSolver with_estimate(s, CoefficientSettings(), MPI_COMM_WORLD);
  const CoefficientResult r = with_estimate.compute();
  ASSERT_TRUE(r.has_error_estimate);
  ASSERT_GT(r.coarsest_dofs, 0u);
  const unsigned int k = s.polynomial_degree;
  const double factor = 1.0 / (std::pow(2.0, k) - 1);
  const double expected = expected_load_order(k, false); // full film

  CoefficientSolver separate(s, CoefficientSettings(), MPI_COMM_WORLD);
  const FilmCoefficients fine = separate.coefficients(s.geometry, s.conditions, 0);
  const FilmLoads fine_loads = separate.reynolds().run(s.geometry, s.conditions, 0);
  const FilmCoefficients coarse = separate.coefficients(s.geometry, s.conditions, 1);
  const FilmLoads coarse_loads = separate.reynolds().run(s.geometry, s.conditions, 1);
  const FilmCoefficients coarsest = separate.coefficients(s.geometry, s.conditions, 2);
  const FilmLoads coarsest_loads = separate.reynolds().run(s.geometry, s.conditions, 2);
  auto rule = [&](const FilmCoefficients::Matrix3 &h, const FilmCoefficients::Matrix3 &h2,
                  const FilmCoefficients::Matrix3 &h4, unsigned int i, unsigned int j)
  {
    const double scale = std::max(std::sqrt(std::abs(h[i][i] * h[j][j])), std::abs(h[i][j]));
    return grid_convergence(h[i][j], h2[i][j], h4[i][j], expected,
                            factor * std::abs(h[i][j] - h2[i][j]), grid_convergence_noise * scale)
        .estimate;
  };
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
    {
      const double eK = factor * std::abs(fine.stiffness[i][j] - coarse.stiffness[i][j]);
      const double eD = factor * std::abs(fine.damping[i][j] - coarse.damping[i][j]);
      const double tK = 1e-9 * std::abs(fine.stiffness[i][i]) + 1e-300;
      const double tD = 1e-9 * std::abs(fine.damping[i][i]) + 1e-300;
      EXPECT_GE(r.stiffness_error[i][j], eK - tK);
      EXPECT_GE(r.damping_error[i][j], eD - tD);
      EXPECT_NEAR(r.stiffness_error[i][j],
                  rule(fine.stiffness, coarse.stiffness, coarsest.stiffness, i, j), tK);
      EXPECT_NEAR(r.damping_error[i][j], rule(fine.damping, coarse.damping, coarsest.damping, i, j),
                  tD);
    }
  EXPECT_GE(r.load_error.force_z,
            factor * std::abs(fine_loads.force_z - coarse_loads.force_z) * (1 - 1e-9));
  const FilmLoads floor = estimate_load_errors(fine_loads, coarse_loads, k);
  const GridConvergence force =
      grid_convergence(fine_loads.force_z, coarse_loads.force_z, coarsest_loads.force_z, expected,
                       floor.force_z, grid_convergence_noise * std::abs(fine_loads.force_z));
  EXPECT_NEAR(r.load_error.force_z, force.estimate, 1e-9 * std::abs(fine_loads.force_z));
  EXPECT_GE(r.load_error.moment_x, floor.moment_x * (1 - 1e-9));
}

TEST(FiniteElementFilm, LoadsAreADirectSolve)
{
  FilmSettings s;
  s.geometry.tilt = 0.3 * s.geometry.clearance / s.geometry.outer_radius;
  s.geometry.tilt_angle = 0.4;
  FiniteElementFilm model(s, MPI_COMM_WORLD);
  EXPECT_EQ(model.level(), FilmLevel::finite_element);
  const FilmState state = FilmState::from(s.geometry, s.conditions);
  const FilmLoads a = model.loads(state);
  // The state's film (the tilt goes through the tilt vector, so it equals the settings' film to
  // round-off only): the same numbers as a direct solve.
  const FilmThickness film = state.apply(s.geometry);
  const OperatingConditions conditions = state.apply(s.conditions);
  ReynoldsSolver direct(s, MPI_COMM_WORLD);
  const FilmLoads b = direct.run(film, conditions);
  EXPECT_EQ(a.force_z, b.force_z);
  EXPECT_EQ(a.moment_x, b.moment_x);
  EXPECT_EQ(a.moment_y, b.moment_y);
  EXPECT_EQ(a.leakage_outer, b.leakage_outer);
  EXPECT_EQ(a.friction_torque, b.friction_torque);
  ReynoldsSolver settings_film(s, MPI_COMM_WORLD);
  const FilmLoads c0 = settings_film.run();
  EXPECT_NEAR(a.force_z / c0.force_z, 1.0, 1e-12);
  EXPECT_NEAR(a.moment_x / c0.moment_x, 1.0, 1e-9);
  // The coefficients are the coefficient solver's at the state.
  CoefficientSolver c(s, CoefficientSettings(), MPI_COMM_WORLD);
  const FilmCoefficients k = model.coefficients(state);
  const FilmCoefficients k_direct = c.coefficients(film, conditions);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
    {
      EXPECT_EQ(k.stiffness[i][j], k_direct.stiffness[i][j]);
      EXPECT_EQ(k.damping[i][j], k_direct.damping[i][j]);
    }
}

TEST(FiniteElementFilm, AxisymmetricForceIsExactAndTheMeshIsBuiltOnce)
{
  // The mesh and degree of reynolds_exact.cc's coned-face test, whose tolerance is 1e-7.
  FilmSettings s;
  s.polynomial_degree = 3;
  s.mesh.radial_cells = 24;
  s.mesh.circumferential_cells = 128;
  FiniteElementFilm model(s, MPI_COMM_WORLD);
  FilmState state = FilmState::from(s.geometry, s.conditions);
  const auto n_dofs_first = [&]
  {
    model.loads(state);
    return model.reynolds().n_dofs();
  }();
  for (const double z : {0.0, -0.2e-6, 0.3e-6})
  {
    state.axial_offset = z;
    state.rotor_speed = 500 + 1e9 * z; // no pressure from rotation on an axisymmetric film
    state.inner_pressure = 1e5;
    const FilmLoads loads = model.loads(state);
    const FilmThickness film = state.apply(s.geometry);
    const OperatingConditions conditions = state.apply(s.conditions);
    // h = C0 + z + beta (r - ri): the exact solution with clearance C0 + z.
    const ConedExact exact{film.inner_radius, film.outer_radius,         film.clearance + z,
                           film.coning,       conditions.inner_pressure, conditions.outer_pressure};
    EXPECT_NEAR(loads.force_z / exact.force(), 1.0, 1e-7) << "z = " << z;
    EXPECT_EQ(model.reynolds().n_dofs(), n_dofs_first);
  }
  EXPECT_EQ(model.reynolds().n_setups(), 1u);
}
