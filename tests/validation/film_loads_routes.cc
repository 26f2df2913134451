// The two integration routes of the loads give the same numbers. A full film on smooth faces
// takes its loads from sums gathered during the assembly (AffineLoadSums, film_loads.h: each
// load is affine in the nodal pressures); half-Sommerfeld integrates the solved pressure point by
// point (LoadIntegrator::integrate). With the cavitation pressure far below every pressure of the
// film, half-Sommerfeld clips nothing, its solve is the full film's, and its loads are the same
// integrals of the same solution: the two must agree to round-off (the same terms summed in
// another order).
#include <sealfe/film/reynolds_solver.h>

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
