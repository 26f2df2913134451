// The two integration routes of the loads give the same numbers. A full film on smooth faces
// takes its loads from sums gathered during the assembly (AffineLoadSums, film_loads.h: each
// load is affine in the nodal pressures); half-Sommerfeld integrates the solved pressure point by
// point (LoadIntegrator::integrate). With the cavitation pressure far below every pressure of the
// film, half-Sommerfeld clips nothing, its solve is the full film's, and its loads are the same
// integrals of the same solution: the two must agree to round-off (the same terms summed in
// another order). This is the identity "the loads are affine in the nodal pressures" (each load
// is an integral of p - p_ref, or of dp/dtheta, against fixed weights), so the test is kept with
// the validation tests; it also checks that the affine route is the one the full film takes.
#include "../surface_feature_seals.h"
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/surface_features.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
/// The Varney & Green seal tilted to eps = 0.5 about an axis at 0.3 rad (so that both moments
/// are non-zero), on the built-in mesh.
FilmSettings tilted_seal(const unsigned int degree, const Cavitation model)
{
  FilmSettings s;
  s.geometry.tilt = 0.5 * s.geometry.clearance / s.geometry.outer_radius;
  s.geometry.tilt_angle = 0.3;
  s.polynomial_degree = degree;
  s.mesh.radial_cells = 8;
  s.mesh.circumferential_cells = 64;
  s.estimate_error = false;
  s.cavitation.model = model;
  s.cavitation.pressure = -1e12; // Pa: below every pressure of this film, nothing is clipped
  return s;
}
} // namespace

TEST(FilmLoads, AssembledSumsEqualThePointByPointIntegration)
{
  for (const unsigned int degree : {1u, 2u, 3u})
  {
    ReynoldsSolver full(tilted_seal(degree, Cavitation::none), MPI_COMM_WORLD);
    ReynoldsSolver clipped(tilted_seal(degree, Cavitation::half_sommerfeld), MPI_COMM_WORLD);
    const FilmLoads a = full.run(), b = clipped.run();
    ASSERT_TRUE(full.loads_from_assembled_sums()) << "degree " << degree;
    ASSERT_FALSE(clipped.loads_from_assembled_sums()) << "degree " << degree;
    // Round-off of sums of ~1e4 point terms: 1e-12 of each load's scale (force F, moments F ro,
    // the leakage and friction scales of the film).
    const double F = std::abs(a.force_z), ro = full.settings.geometry.outer_radius;
    const double Q = std::abs(a.leakage_outer), T = std::abs(a.friction_torque);
    const double tol = 1e-12;
    EXPECT_NEAR(a.force_z, b.force_z, tol * F) << "degree " << degree;
    EXPECT_NEAR(a.moment_x, b.moment_x, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.moment_y, b.moment_y, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.moment_restoring, b.moment_restoring, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.moment_transverse, b.moment_transverse, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.leakage_inner, b.leakage_inner, tol * Q) << "degree " << degree;
    EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tol * Q) << "degree " << degree;
    EXPECT_NEAR(a.friction_torque, b.friction_torque, tol * T) << "degree " << degree;
    EXPECT_NEAR(a.squeeze_flow, b.squeeze_flow, tol * Q) << "degree " << degree;
    EXPECT_NEAR(a.area, b.area, tol * a.area) << "degree " << degree;
    // the pressure range: the same interpolant at the same points
    EXPECT_NEAR(a.max_pressure, b.max_pressure, tol * a.max_pressure) << "degree " << degree;
    EXPECT_NEAR(a.min_pressure, b.min_pressure, tol * a.max_pressure) << "degree " << degree;
    EXPECT_EQ(b.cavitated_fraction, 0.0);
    // and the moments are not zero by symmetry here, so the comparison means something
    EXPECT_GT(std::abs(a.moment_y), 1e-3 * F * ro);
  }
}

// The same identity with the reference pressure at 0.3 po (the pressure parts of the loads are
// integrals of p - p_ref: the route that subtracts p_ref A after summing loses digits when p_ref
// is near the pressures), squeeze (axial and tilt rates: the squeeze term in the right-hand side
// and the squeeze flow) and Rayleigh pads on the rotor (the solve in the rotor's frame and the
// friction on the smooth face, film_loads.cc friction_face()).
TEST(FilmLoads, AssembledSumsEqualThePointByPointIntegrationWithReferencePressureSqueezeAndPads)
{
  test::RayleighPadSeal pads;
  pads.pads = 10;
  FilmSettings s = pads.settings();
  auto features = std::make_shared<SurfaceFeatures>(*s.geometry.features);
  features->face = SurfaceFeatures::Face::rotor;
  s.geometry.features = features;
  s.conditions.inner_pressure = 1e5;
  s.conditions.outer_pressure = 3e5;
  s.conditions.reference_pressure = 0.3 * s.conditions.outer_pressure;
  s.geometry.axial_velocity = -1e-6; // m/s, closing
  s.geometry.tilt_rate_x = 2e-5;     // rad/s: r * rate ~ 7e-7 m/s
  s.estimate_error = false;
  s.cavitation.pressure = -1e12; // Pa: nothing clipped
  s.cavitation.model = Cavitation::none;
  ReynoldsSolver full(s, MPI_COMM_WORLD);
  s.cavitation.model = Cavitation::half_sommerfeld;
  ReynoldsSolver clipped(s, MPI_COMM_WORLD);
  const FilmLoads a = full.run(), b = clipped.run();
  ASSERT_TRUE(full.loads_from_assembled_sums());
  ASSERT_FALSE(clipped.loads_from_assembled_sums());
  // Round-off relative to the size of the integrands: the pressure range times the area for
  // the force (and times ro for the moments), the flows and torque by their own sizes.
  const double F = (a.max_pressure - a.min_pressure) * a.area, ro = pads.ro;
  const double Q = std::max(std::abs(a.leakage_inner), std::abs(a.leakage_outer));
  const double T = std::abs(a.friction_torque), S = std::abs(a.squeeze_flow);
  const double tol = 1e-12;
  EXPECT_NEAR(a.force_z, b.force_z, tol * F);
  EXPECT_NEAR(a.moment_x, b.moment_x, tol * F * ro);
  EXPECT_NEAR(a.moment_y, b.moment_y, tol * F * ro);
  EXPECT_NEAR(a.moment_restoring, b.moment_restoring, tol * F * ro);
  EXPECT_NEAR(a.moment_transverse, b.moment_transverse, tol * F * ro);
  EXPECT_NEAR(a.leakage_inner, b.leakage_inner, tol * Q);
  EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tol * Q);
  EXPECT_NEAR(a.friction_torque, b.friction_torque, tol * T);
  EXPECT_NEAR(a.squeeze_flow, b.squeeze_flow, tol * S);
  EXPECT_EQ(b.cavitated_fraction, 0.0);
  // the squeeze and the tilt rate make the flow and the moments non-zero: the comparison bites
  // (squeeze flow |dz/dt| A: the tilt rate's part integrates to zero over the annulus)
  EXPECT_NEAR(S, 1e-6 * a.area, 1e-9 * 1e-6 * a.area);
  EXPECT_GT(std::abs(a.moment_x), 1e-4 * F * ro);
}
