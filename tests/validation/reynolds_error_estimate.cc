// The error estimate reported with every FE load is an upper bound of the true discretisation
// error: checked on the default seal with a 0.5-eps tilt and waviness, for degrees 1 and 2 and
// several meshes, against a reference from a much finer degree-4 solve (whose own error is
// orders of magnitude below the tested ones).
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
FilmThickness tilted_film()
{
  FilmThickness f;
  f.tilt = 0.5 * f.clearance / f.outer_radius;
  f.tilt_angle = 0.3;
  return f;
}

FilmLoads solve(unsigned int degree, unsigned int nr, unsigned int nt, unsigned int coarsening = 0)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  s.polynomial_degree = degree;
  s.mesh().radial_cells = nr;
  s.mesh().circumferential_cells = nt;
  return s.run(tilted_film(), OperatingConditions(), coarsening);
}
} // namespace

TEST(ReynoldsErrorEstimate, BoundsTheTrueErrorOfEveryLoad)
{
  const FilmLoads ref = solve(4, 16, 256);
  for (const unsigned int degree : {1u, 2u})
    for (const unsigned int nr : {4u, 8u})
    {
      const unsigned int nt = 16 * nr;
      const FilmLoads fine = solve(degree, nr, nt);
      const FilmLoads coarse = solve(degree, nr, nt, 1);
      const FilmLoads est = estimate_load_errors(fine, coarse, degree);
      const double F = ref.force_z, M = std::hypot(ref.moment_x, ref.moment_y);
      auto check =
          [&](const char *name, double value, double reference, double estimate, double scale)
      {
        const double error = std::abs(value - reference);
        std::cout << "k=" << degree << " nr=" << nr << " " << name << ": true " << error / scale
                  << " estimate " << estimate / scale << " (relative)\n";
        // Only meaningful above the reference's own accuracy (1e-9 relative).
        EXPECT_LE(error, estimate + 1e-9 * scale) << name;
      };
      check("force_z", fine.force_z, ref.force_z, est.force_z, F);
      check("moment_x", fine.moment_x, ref.moment_x, est.moment_x, M);
      check("moment_y", fine.moment_y, ref.moment_y, est.moment_y, M);
      check("leakage_inner", fine.leakage_inner, ref.leakage_inner, est.leakage_inner,
            std::abs(ref.leakage_inner));
    }
}
