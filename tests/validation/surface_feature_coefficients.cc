// Film stiffness and damping of textured faces (coefficient_solver.h with surface features): the
// perturbation method (the linearised discrete Reynolds system) against central differences of
// the nonlinear solve, for tilted spiral grooves in full film and for dimples with JFO. A mode
// moves the whole face (h + dz + tilt), so the film's steps move with it and the linearisation is
// that of the same discrete loads.
#include "../coefficient_comparison.h"
#include "../surface_feature_seals.h"

#include <sealfe/coefficients/coefficient_solver.h>

#include <gtest/gtest.h>

#include <iostream>

using namespace sealfe;
using namespace sealfe::test;

namespace
{
struct Comparison
{
  double stiffness, damping, cavitated_fraction;
};

/// Perturbation against central differences of relative step `step` (of C0 and C0/ro).
Comparison compare(const FilmSettings &film, const double step)
{
  CoefficientSettings perturbation, difference;
  perturbation.method = CoefficientSettings::Method::perturbation;
  difference.method = CoefficientSettings::Method::finite_difference;
  difference.relative_step = step;
  FilmSettings s = film;
  s.estimate_error = false;
  CoefficientSolver p(s, perturbation, MPI_COMM_WORLD), d(s, difference, MPI_COMM_WORLD);
  const CoefficientResult a = p.compute(), b = d.compute();
  const double ro = s.geometry.outer_radius;
  const Comparison c{relative_difference(a.coefficients.stiffness, b.coefficients.stiffness, ro),
                     relative_difference(a.coefficients.damping, b.coefficients.damping, ro),
                     a.loads.cavitated_fraction};
  std::cout << "dofs " << a.dofs << ", cavitated fraction " << c.cavitated_fraction
            << ": perturbation vs central differences (step " << step << "): stiffness "
            << c.stiffness << ", damping " << c.damping << "; K_zz "
            << a.coefficients.stiffness[0][0] << " N/m, D_zz " << a.coefficients.damping[0][0]
            << " N s/m\n";
  for (const auto *m : {&a.coefficients.stiffness, &b.coefficients.stiffness,
                        &a.coefficients.damping, &b.coefficients.damping})
  {
    for (const auto &row : uniform(*m, ro))
      std::cout << "  " << row[0] << " " << row[1] << " " << row[2];
    std::cout << "\n";
  }
  return c;
}
} // namespace

// Full film: both differentiate the same discrete loads, the differences add O(step^2)
// truncation (~1e-8 at step 1e-4 with n ~ 3 from h^3) and round-off ~1e-13/1e-4: 1e-5 as for
// the smooth face (film_coefficients_fe.cc).
TEST(SurfaceFeatureCoefficients, SpiralGroovesFullFilm)
{
  SpiralGrooveSeal seal;
  seal.grooves = 8;
  seal.cells_per_groove = 8;
  seal.radial_cells = 8;
  FilmSettings s = seal.settings();
  s.geometry.tilt = 0.3 * seal.h / seal.ro; // a tilted face: all nine entries non-zero
  s.geometry.tilt_angle = 0.7;
  s.conditions.outer_pressure = 1e6; // no cavity: the full-film claim
  const Comparison c = compare(s, 1e-4);
  EXPECT_EQ(c.cavitated_fraction, 0.0);
  EXPECT_LT(c.stiffness, 1e-5);
  EXPECT_LT(c.damping, 1e-5);
}

// JFO: the linearisation holds the converged cavitated set; the nodes that change it within the
// step lie in an O(step) band, so the two differ by O(step) + O(step^2). Each dimple has its own
// cavity edge with a steep pressure gradient, so the band's constant is large: measured on this
// seal, force central differences at steps 1e-3, 1e-4, 1e-5 of C0 move by 0.4 %, 0.17 %, < 1e-5
// (the cavitated set is unchanged at 1e-5). Step 1e-5: the set holds, the difference is
// truncation and the Newton tolerance (1e-10 / 1e-5 = 1e-5 of the load derivative): 1e-4.
TEST(SurfaceFeatureCoefficients, DimplesJfo)
{
  DimpledSeal seal; // 512 x 16 cells: about 4 cells across a dimple
  seal.degree = 1;
  const Comparison c = compare(seal.settings(), 1e-5);
  EXPECT_GT(c.cavitated_fraction, 0.1);
  EXPECT_LT(c.stiffness, 1e-4);
  EXPECT_LT(c.damping, 1e-4);
}
