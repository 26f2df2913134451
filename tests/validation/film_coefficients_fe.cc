// Finite-element film coefficients (coefficient_solver.h) against independent references:
//  - the perturbation method (linearised discrete Reynolds system) against central differences of
//    the nonlinear solve, in full film and with half-Sommerfeld cavitation;
//  - the axial stiffness and damping of the axisymmetric coned face against the derivative of the
//    exact 1D solution (curvature included);
//  - Green & Etsion's narrow-seal k11, d11 and (omega/2) d11 as ri/ro -> 1, and on the Varney &
//    Green seal;
//  - the symmetries of an axisymmetric film, and the FMRR speeds (Wileman & Green).
#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/coefficients/coefficient_solver.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include "../cavitating_wavy_seal.h"
#include "../coefficient_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>

using namespace sealfe;
using namespace sealfe::test;

namespace
{
std::unique_ptr<CoefficientSolver>
make_solver(const unsigned int degree, const unsigned int radial,
            const unsigned int circumferential,
            const CoefficientSettings::Method method = CoefficientSettings::Method::perturbation)
{
  auto s = std::make_unique<CoefficientSolver>(MPI_COMM_WORLD);
  s->reynolds().polynomial_degree = degree;
  s->reynolds().mesh().radial_cells = radial;
  s->reynolds().mesh().circumferential_cells = circumferential;
  s->reynolds().estimate_error = false;
  s->settings.method = method;
  return s;
}

void print(const char *name, const Matrix3 &m)
{
  std::cout << name << "\n";
  for (const auto &r : m)
    std::cout << "  " << r[0] << " " << r[1] << " " << r[2] << "\n";
}

/// The Varney & Green seal (defaults) tilted to eps = gamma ro / C0 at psi = 0.7: a film without
/// symmetry, so that all 18 coefficients are non-zero.
FilmThickness tilted_film(const double eps)
{
  FilmThickness f;
  f.tilt = eps * f.clearance / f.outer_radius;
  f.tilt_angle = 0.7;
  return f;
}
} // namespace

TEST(FilmCoefficientsFE, PerturbationMatchesCentralDifferencesInFullFilm)
{
  const FilmThickness film = tilted_film(0.4);
  OperatingConditions conditions;
  conditions.rotor_speed = 1500;
  conditions.stator_speed = -300;
  auto perturbation = make_solver(2, 6, 64, CoefficientSettings::Method::perturbation);
  auto difference = make_solver(2, 6, 64, CoefficientSettings::Method::finite_difference);
  const CoefficientResult p = perturbation->compute(film, conditions);
  const CoefficientResult d = difference->compute(film, conditions);
  print("K perturbation", p.coefficients.stiffness);
  print("K finite difference", d.coefficients.stiffness);
  print("D perturbation", p.coefficients.damping);
  const double ro = film.outer_radius;
  const double ek = relative_difference(p.coefficients.stiffness, d.coefficients.stiffness, ro);
  const double ed = relative_difference(p.coefficients.damping, d.coefficients.damping, ro);
  std::cout << "dofs " << p.dofs << ": perturbation vs central differences (step 1e-4 C0, "
            << "1e-4 C0/ro): stiffness " << ek << ", damping " << ed << "\n";
  // Both differentiate the same discrete loads; central differences add O(step^2) truncation
  // (~ (1e-4)^2 (n/C0 * C0)^2 with n ~ 3 from h^3: ~1e-7) and round-off ~1e-13/1e-4 = 1e-9.
  EXPECT_LT(ek, 1e-5);
  EXPECT_LT(ed, 1e-5);
  // D = B^T A^-1 B with the symmetric Reynolds matrix A and B_jk = int w_j phi_k (the load
  // functional of a mode equals its squeeze source): symmetric to round-off.
  const Matrix3 D = uniform(p.coefficients.damping, ro);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < i; ++j)
      EXPECT_NEAR(D[i][j], D[j][i], 1e-9 * max_abs(D));
  // The loads of the operating point are the same solve.
  EXPECT_NEAR(p.loads.force_z, d.loads.force_z, 1e-12 * std::abs(p.loads.force_z));
}

TEST(FilmCoefficientsFE, PerturbationMatchesCentralDifferencesWithRoughFaces)
{
  // Patir-Cheng average flow (anisotropic pattern gamma = 3, sigma = 0.2 um, so H = h/sigma >= 3:
  // inside the fits, which are smooth in h) with GW/CEB asperity contact in the loads, on the
  // tilted full-film operating point: the perturbation method must be the derivative of the
  // discrete loads, to the same 1e-5 as the smooth film.
  dealii::ParameterHandler prm;
  CoefficientSolver::declare_parameters(prm);
  prm.enter_subsection("Roughness");
  prm.set("Model", "patir-cheng");
  prm.set("Composite roughness", "2e-7");
  prm.set("Surface pattern", "3");
  prm.leave_subsection();
  prm.enter_subsection("Contact");
  prm.set("Model", "gw-ceb");
  prm.leave_subsection();
  const FilmThickness film = tilted_film(0.4);
  OperatingConditions conditions;
  conditions.rotor_speed = 1500;
  CoefficientResult results[2];
  for (const auto method :
       {CoefficientSettings::Method::perturbation, CoefficientSettings::Method::finite_difference})
  {
    CoefficientSolver s(MPI_COMM_WORLD);
    s.parse_parameters(prm);
    s.reynolds().polynomial_degree = 2;
    s.reynolds().mesh().radial_cells = 6;
    s.reynolds().mesh().circumferential_cells = 64;
    s.reynolds().estimate_error = false;
    s.settings.method = method;
    results[method == CoefficientSettings::Method::finite_difference] = s.compute(film, conditions);
  }
  const CoefficientResult &p = results[0], &d = results[1];
  const double ro = film.outer_radius;
  const double ek = relative_difference(p.coefficients.stiffness, d.coefficients.stiffness, ro);
  const double ed = relative_difference(p.coefficients.damping, d.coefficients.damping, ro);
  std::cout << "rough faces with contact: perturbation vs central differences: stiffness " << ek
            << ", damping " << ed << "; K_zz " << p.coefficients.stiffness[0][0]
            << ", contact force " << p.loads.contact_force << " of " << p.loads.force_z << " N\n";
  EXPECT_GT(p.loads.contact_force, 0); // the contact model does act
  EXPECT_LT(ek, 1e-5);
  EXPECT_LT(ed, 1e-5);
}

namespace
{
/// Perturbation against central differences with a cavitation model: the largest relative
/// difference of K and D (entry-wise, with entries below 1e-3 of their matrix measured against
/// 1e-3 of it) for a sequence of steps, and the same for the matrix as a whole (floor 1).
struct CavitatingCheck
{
  std::vector<double> steps, stiffness, damping, stiffness_matrix, axial_column;
  double cavitated_fraction;
};

CavitatingCheck check_cavitating(const Cavitation model, const FilmThickness &film,
                                 const OperatingConditions &conditions, const unsigned int nr,
                                 const unsigned int nt, const std::vector<double> &steps)
{
  CavitatingCheck c;
  c.steps = steps;
  auto perturbation = make_solver(2, nr, nt);
  perturbation->reynolds().cavitation.model = model;
  const CoefficientResult p = perturbation->compute(film, conditions);
  c.cavitated_fraction = p.loads.cavitated_fraction;
  const double ro = film.outer_radius;
  for (const double step : steps)
  {
    auto difference = make_solver(2, nr, nt, CoefficientSettings::Method::finite_difference);
    difference->reynolds().cavitation.model = model;
    difference->settings.relative_step = step;
    const CoefficientResult d = difference->compute(film, conditions);
    c.stiffness.push_back(
        relative_difference(p.coefficients.stiffness, d.coefficients.stiffness, ro));
    c.damping.push_back(relative_difference(p.coefficients.damping, d.coefficients.damping, ro));
    c.stiffness_matrix.push_back(
        relative_difference(p.coefficients.stiffness, d.coefficients.stiffness, ro, 1.0));
    // The axial column (dh = 1) alone.
    Matrix3 a = p.coefficients.stiffness, b = d.coefficients.stiffness;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 1; j < 3; ++j)
        a[i][j] = b[i][j];
    c.axial_column.push_back(relative_difference(a, b, ro));
    std::cout << "cavitation model " << static_cast<int>(model) << ", cavitated fraction "
              << c.cavitated_fraction << ", step " << step << ": stiffness " << c.stiffness.back()
              << " (matrix " << c.stiffness_matrix.back() << ", axial column "
              << c.axial_column.back() << "), damping " << c.damping.back() << "\n";
  }
  return c;
}
} // namespace

TEST(FilmCoefficientsFE, PerturbationMatchesCentralDifferencesWithCavitation)
{
  // Half-Sommerfeld and Reynolds (Swift-Stieber) on a tilted face at pi = po = p_cav = 0 (pure
  // hydrodynamics, half of the dam cavitates). The perturbation method freezes the cavitation
  // boundary; the clipped loads are continuous there, so this is their derivative, except where
  // a quadrature point (half-Sommerfeld) or a node (Reynolds active set) crosses p_cav within the
  // step. Those crossings lie in a band of the dam whose area is O(step), so central differences
  // differ from the perturbation by O(step^2) (truncation, as in full film) plus at most O(step):
  // stated tolerance 1e-4 at step 1e-4, shrinking with the step.
  const FilmThickness film = tilted_film(0.5);
  OperatingConditions conditions;
  conditions.outer_pressure = 0;
  for (const auto model : {Cavitation::half_sommerfeld, Cavitation::reynolds})
  {
    const CavitatingCheck c = check_cavitating(model, film, conditions, 6, 64, {1e-3, 1e-4});
    EXPECT_GT(c.cavitated_fraction, 0.4);
    EXPECT_LT(c.stiffness[1], 1e-4);
    EXPECT_LT(c.damping[1], 1e-4);
    EXPECT_LT(c.stiffness[0], 1e-3);
  }
}

TEST(FilmCoefficientsFE, PerturbationMatchesCentralDifferencesWithJFO)
{
  // Mass-conserving JFO on a wavy, tilted seal at a low sealed pressure (several cavities with
  // reformation). The solver linearises the complementarity system at its converged cavitated
  // set (pressure and liquid fraction together, ReynoldsSolver::linearized_loads), the exact
  // derivative wherever that set does not change within the step; as for Reynolds, the nodes
  // that change it lie in an O(step) band: stated tolerance 1e-4 at step 1e-4 for every entry.
  const FilmThickness film = sealfe::testing::wavy_film();
  const OperatingConditions conditions = sealfe::testing::low_pressure();
  const CavitatingCheck c = check_cavitating(Cavitation::jfo, film, conditions, 8, 128, {1e-4});
  EXPECT_GT(c.cavitated_fraction, 0.5);
  EXPECT_LT(c.damping[0], 1e-4);
  EXPECT_LT(c.stiffness[0], 1e-4);
}

namespace
{
struct NarrowDeparture
{
  double stiffness, damping, cross, axial_stiffness, axial_damping;
};

/// Relative departures of the FE angular coefficients from Green & Etsion's for a coned face of
/// width (1 - Ri) ro at fixed ro, C0 and film shape h_o/h_i = 1 + x (x = beta* (ro - ri)/C0).
NarrowDeparture narrow_departure(const double width, const double x, const unsigned int radial,
                                 const unsigned int circumferential)
{
  FilmThickness film;
  film.inner_radius = (1 - width) * film.outer_radius;
  film.coning = x * film.clearance / (film.outer_radius - film.inner_radius);
  OperatingConditions conditions; // FMS: rotor 1000 rad/s, po - pi = 400 kPa
  auto solver = make_solver(3, radial, circumferential);
  const FilmCoefficients fe = solver->coefficients(film, conditions);
  const GreenEtsionCoefficients ge(film, conditions);
  NarrowDeparture d;
  d.stiffness = fe.tilt_direct_stiffness() / ge.angular_stiffness() - 1;
  d.damping = fe.tilt_direct_damping() / ge.angular_damping() - 1;
  d.cross = fe.tilt_cross_stiffness() /
                ge.cross_coupled_stiffness(conditions.rotor_speed, conditions.stator_speed) -
            1;
  d.axial_stiffness = fe.stiffness[0][0] / ge.axial_stiffness() - 1;
  d.axial_damping = fe.damping[0][0] / ge.axial_damping() - 1;
  return d;
}
} // namespace

TEST(FilmCoefficientsFE, NarrowSealLimitApproachesGreenEtsion)
{
  // ri -> ro at fixed ro, C0 and coning beta* (the seal's own beta* = 1 mrad). Green & Etsion
  // drop the curvature term (h^3/r) dp/dr of the radial flow, the circumferential pressure flow
  // and the variation of the moment arm across the dam. The circumferential flow and the moment
  // arm give O(eps^2), eps = 1 - ri/ro; the curvature term gives O(eps) times the asymmetry of
  // the hydrostatic pressure across the dam, which is O(x) with x = beta* (ro - ri)/C0 -> 0 like
  // eps. So the departure is O(eps^2): the observed rate tends to 2 from below as x -> 0.
  // (At fixed x instead, the O(x eps) term stays first order: see the next test.)
  const std::vector<double> widths = {0.13, 0.08, 0.04, 0.02, 0.01};
  std::vector<NarrowDeparture> d;
  for (const double w : widths)
  {
    FilmThickness vg;
    d.push_back(narrow_departure(w, vg.coning * w * vg.outer_radius / vg.clearance, 4, 32));
    std::cout << "1 - ri/ro = " << w << ": departure k " << d.back().stiffness << ", d "
              << d.back().damping << ", c " << d.back().cross << ", K_zz "
              << d.back().axial_stiffness << ", D_zz " << d.back().axial_damping << "\n";
  }
  // The Varney & Green seal itself (ri/ro = 0.87): about 10% (the FE moments are smaller).
  EXPECT_GT(std::abs(d[0].stiffness), 0.05);
  EXPECT_LT(std::abs(d[0].stiffness), 0.15);
  EXPECT_GT(std::abs(d[0].damping), 0.05);
  EXPECT_LT(std::abs(d[0].damping), 0.15);
  for (unsigned int i = 1; i < widths.size(); ++i)
  {
    const double lw = std::log(widths[i - 1] / widths[i]);
    const double rk = std::log(d[i - 1].stiffness / d[i].stiffness) / lw;
    const double rd = std::log(d[i - 1].damping / d[i].damping) / lw;
    const double rc = std::log(d[i - 1].cross / d[i].cross) / lw;
    std::cout << "observed rate between " << widths[i - 1] << " and " << widths[i] << ": k " << rk
              << ", d " << rd << ", c " << rc << "\n";
    EXPECT_LT(std::abs(d[i].stiffness), std::abs(d[i - 1].stiffness));
    EXPECT_LT(std::abs(d[i].damping), std::abs(d[i - 1].damping));
    EXPECT_LT(std::abs(d[i].cross), std::abs(d[i - 1].cross));
    EXPECT_GT(rk, 1.2); // faster than first order everywhere, increasing towards 2
    EXPECT_GT(rd, 1.2);
    if (i > 1)
    {
      EXPECT_GT(rk, std::log(d[i - 2].stiffness / d[i - 1].stiffness) /
                        std::log(widths[i - 2] / widths[i - 1]));
    }
  }
  const double last = std::log(d[3].stiffness / d[4].stiffness) / std::log(2.0);
  EXPECT_GT(last, 1.7);
  EXPECT_LT(last, 2.1);
  // The rotating film: c = (omega/2) d for the FE as for the closed form.
  for (const auto &x : d)
    EXPECT_NEAR(x.cross, x.damping, 1e-6);
  // At 1 - ri/ro = 0.01 every coefficient is within 2e-3 of the closed form.
  EXPECT_LT(std::abs(d.back().stiffness), 2e-3);
  EXPECT_LT(std::abs(d.back().damping), 2e-3);
  EXPECT_LT(std::abs(d.back().axial_stiffness), 2e-3);
  EXPECT_LT(std::abs(d.back().axial_damping), 2e-3);
}

TEST(FilmCoefficientsFE, NarrowSealLimitAtFixedFilmShapeIsFirstOrder)
{
  // Holding h_o/h_i = 1 + x fixed (x = 5.3 of the Varney & Green seal) as ri -> ro, the
  // curvature term of the radial flow acting on the asymmetric coned pressure leaves a first-
  // order departure: rate 1.
  const double x = 1e-3 * (0.0408 - 0.0355) / 1e-6;
  const std::vector<double> widths = {0.04, 0.02, 0.01};
  std::vector<NarrowDeparture> d;
  for (const double w : widths)
    d.push_back(narrow_departure(w, x, 8, 64));
  for (unsigned int i = 1; i < widths.size(); ++i)
  {
    const double rk = std::log(d[i - 1].stiffness / d[i].stiffness) / std::log(2.0);
    const double rd = std::log(d[i - 1].damping / d[i].damping) / std::log(2.0);
    std::cout << "fixed x: 1 - ri/ro = " << widths[i] << ": departure k " << d[i].stiffness
              << ", d " << d[i].damping << "; rate k " << rk << ", d " << rd << "\n";
    EXPECT_NEAR(rk, 1.0, 0.05);
    EXPECT_NEAR(rd, 1.0, 0.05);
  }
}

namespace
{
/// Exact axisymmetric coned face (curvature included), h = a + b s with a = C0 + z - beta ri,
/// b = beta: the hydrostatic pressure p = pi + (po - pi) I(r)/I(ro), I(r) = int_ri^r ds/(s h^3)
/// (tests/validation/reynolds_exact.cc), its derivative in z, and the squeeze pressure of an axial
/// velocity zdot: (r h^3 p')' = 12 mu zdot r with p(ri) = p(ro) = 0.
struct ConedAxial
{
  double ri, ro, C0, beta, pi, po, mu;
  double a() const { return C0 - beta * ri; }
  double u(const double s) const { return a() + beta * s; }
  /// antiderivatives of 1/(s u^3), 1/(s u^4) and s/u^3 (partial fractions; checked by the test
  /// against finite differences of the pressure and of the force)
  double A3(const double s) const
  {
    const double A = a(), U = u(s);
    return std::log(s / U) / (A * A * A) + 1 / (A * A * U) + 1 / (2 * A * U * U);
  }
  double A4(const double s) const
  {
    const double A = a(), U = u(s);
    return std::log(s / U) / (A * A * A * A) + 1 / (A * A * A * U) + 1 / (2 * A * A * U * U) +
           1 / (3 * A * U * U * U);
  }
  double B3(const double s) const
  {
    const double U = u(s);
    return (-1 / U + a() / (2 * U * U)) / (beta * beta);
  }
  double I(const double r) const { return A3(r) - A3(ri); }
  double J(const double r) const { return A4(r) - A4(ri); }
  double S(const double r) const { return B3(r) - B3(ri); }
  double pressure(const double r) const { return pi + (po - pi) * I(r) / I(ro); }
  /// dp/dz: dI/dz = -3 J
  double pressure_z(const double r) const
  {
    return (po - pi) * 3 * (I(r) * J(ro) - J(r) * I(ro)) / (I(ro) * I(ro));
  }
  /// squeeze pressure per unit zdot: p = 6 mu (S(r) - S(ro) I(r)/I(ro))
  double squeeze_pressure(const double r) const { return 6 * mu * (S(r) - S(ro) * I(r) / I(ro)); }
  /// 2 pi int f(r) r dr by composite 10-point Gauss-Legendre (smooth integrand: exact to round-off)
  double integrate(const std::function<double(double)> &f) const
  {
    const dealii::QGauss<1> g(10);
    const unsigned int n = 200;
    double sum = 0;
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int q = 0; q < g.size(); ++q)
      {
        const double r = ri + (ro - ri) * (k + g.point(q)[0]) / n;
        sum += 2 * M_PI * f(r) * r * g.weight(q) * (ro - ri) / n;
      }
    return sum;
  }
  double force() const
  {
    return integrate([this](double r) { return pressure(r); });
  }
  double axial_stiffness() const
  {
    return -integrate([this](double r) { return pressure_z(r); });
  }
  double axial_damping() const
  {
    return -integrate([this](double r) { return squeeze_pressure(r); });
  }
};
} // namespace

TEST(FilmCoefficientsFE, AxialStiffnessAndDampingOfConedFaceMatchExact1D)
{
  FilmThickness film; // the Varney & Green seal: coned 1 mrad, C0 = 1 um
  OperatingConditions conditions;
  conditions.rotor_speed = 0; // hydrostatic (rotation does not change the axisymmetric film)
  ConedAxial exact{film.inner_radius,   film.outer_radius,         film.clearance,
                   film.coning,         conditions.inner_pressure, conditions.outer_pressure,
                   conditions.viscosity};
  // Self-checks of the exact solution: dF/dz by central differences of the exact force, and the
  // squeeze ODE r h^3 p' - 6 mu r^2 = const by differences of the squeeze pressure.
  {
    const double dz = 1e-4 * film.clearance;
    ConedAxial plus = exact, minus = exact;
    plus.C0 += dz;
    minus.C0 -= dz;
    EXPECT_NEAR(-(plus.force() - minus.force()) / (2 * dz) / exact.axial_stiffness(), 1.0, 1e-7);
    auto flux = [&](double r)
    {
      const double d = 1e-6 * r, h = exact.u(r);
      return r * h * h * h * (exact.squeeze_pressure(r + d) - exact.squeeze_pressure(r - d)) /
                 (2 * d) -
             6 * exact.mu * r * r;
    };
    EXPECT_NEAR(flux(0.036) / flux(0.040), 1.0, 1e-6);
  }
  auto solver = make_solver(3, 16, 32);
  const CoefficientResult r = solver->compute(film, conditions);
  const double K = r.coefficients.stiffness[0][0], D = r.coefficients.damping[0][0];
  std::cout << "dofs " << r.dofs << ": K_zz " << K << " exact " << exact.axial_stiffness()
            << " rel " << K / exact.axial_stiffness() - 1 << "; D_zz " << D << " exact "
            << exact.axial_damping() << " rel " << D / exact.axial_damping() - 1 << "\n";
  EXPECT_NEAR(K / exact.axial_stiffness(), 1.0, 1e-6);
  EXPECT_NEAR(D / exact.axial_damping(), 1.0, 1e-6);
}

TEST(FilmCoefficientsFE, AxisymmetricFilmIsIsotropicAndAxialDecouples)
{
  // Coned, untilted film; one ring spinning (FMS) and two counter-rotating rings (FMRR). The mesh
  // (nodes at theta = 2 pi j/N, N divisible by 4) is mapped onto itself by a quarter turn and by
  // the reflection theta -> -theta, so the discrete film has the symmetries of the continuous
  // one and the zero pattern below holds to the round-off of the direct solve.
  const FilmThickness film;
  for (const auto &[w1, w2] : std::vector<std::pair<double, double>>{{1000, 0}, {-2000, 3000}})
  {
    OperatingConditions conditions;
    conditions.rotor_speed = w1;
    conditions.stator_speed = w2;
    auto solver = make_solver(2, 6, 64);
    const FilmCoefficients c = solver->coefficients(film, conditions);
    print("K", c.stiffness);
    print("D", c.damping);
    const double ro = film.outer_radius;
    const Matrix3 K = uniform(c.stiffness, ro), D = uniform(c.damping, ro);
    const double sK = max_abs(K), sD = max_abs(D), tol = 1e-9;
    // Tilt block [[k, c], [-c, k]] and [[d, 0], [0, d]].
    EXPECT_NEAR(K[1][1], K[2][2], tol * sK);
    EXPECT_NEAR(K[1][2], -K[2][1], tol * sK);
    EXPECT_NEAR(D[1][1], D[2][2], tol * sD);
    EXPECT_NEAR(D[1][2], 0, tol * sD);
    EXPECT_NEAR(D[2][1], 0, tol * sD);
    EXPECT_TRUE(c.tilt_block_is_isotropic(1e-9));
    // Axial row and column decouple from the tilts.
    for (const unsigned int t : {1u, 2u})
    {
      EXPECT_NEAR(K[0][t], 0, tol * sK);
      EXPECT_NEAR(K[t][0], 0, tol * sK);
      EXPECT_NEAR(D[0][t], 0, tol * sD);
      EXPECT_NEAR(D[t][0], 0, tol * sD);
    }
  }
}

TEST(FilmCoefficientsFE, TwoRotatingRingsGiveTheFMRRCrossCoupling)
{
  // Wileman & Green: the film's direct stiffness k11 and damping d11 do not depend on the ring
  // speeds; the cross-coupled stiffness is D11 = (omega1 + omega2)/2 d11. The FE operator sees the
  // ring speeds only through the mean surface speed, and at an axisymmetric equilibrium a tilt
  // perturbation's Couette term omega_m d(dh)/dtheta equals a tilt-rate squeeze term, so
  // c = omega_m d up to the quadrature error of that identity.
  const FilmThickness film;
  auto solver = make_solver(2, 6, 64);
  OperatingConditions fms;
  fms.rotor_speed = 1000;
  const FilmCoefficients ref = solver->coefficients(film, fms);
  const GreenEtsionCoefficients ge(film, fms);
  for (const auto &[w1, w2] : std::vector<std::pair<double, double>>{
           {0, 1000}, {500, 500}, {-2000, 3000}, {-2000, -1000}, {-2000, 2000}})
  {
    OperatingConditions c = fms;
    c.rotor_speed = w1;
    c.stator_speed = w2;
    const FilmCoefficients k = solver->coefficients(film, c);
    const double mean = 0.5 * (w1 + w2);
    const double ratio = k.tilt_cross_stiffness() / (mean * k.tilt_direct_damping());
    std::cout << "omega1 " << w1 << " omega2 " << w2 << ": k " << k.tilt_direct_stiffness() << " d "
              << k.tilt_direct_damping() << " c " << k.tilt_cross_stiffness() << " c/(omega_m d) "
              << ratio << " c / GE "
              << k.tilt_cross_stiffness() / ge.cross_coupled_stiffness(w1, w2) << "\n";
    EXPECT_NEAR(k.tilt_direct_stiffness(), ref.tilt_direct_stiffness(),
                1e-9 * std::abs(ref.tilt_direct_stiffness()));
    EXPECT_NEAR(k.tilt_direct_damping(), ref.tilt_direct_damping(),
                1e-9 * ref.tilt_direct_damping());
    EXPECT_NEAR(k.tilt_cross_stiffness(), mean / 500.0 * ref.tilt_cross_stiffness(),
                1e-9 * std::abs(ref.tilt_cross_stiffness()) * std::max(1.0, std::abs(mean) / 500));
    if (mean != 0)
    {
      EXPECT_NEAR(ratio, 1.0, 1e-6);
    }
  }
}
