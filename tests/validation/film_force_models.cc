// The level-0 FilmForceModel (NarrowSealFilm): its coefficients are Green & Etsion's closed forms,
// its loads carry the narrow-seal hydrostatic force of a coned face in closed form, and the
// stiffness and damping the closed forms give are the derivatives of those loads.
#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/dynamics/film_levels.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
/// The Wileman & Green reference seal (ri/ro = 0.8, beta* ro/C0 = 12.5) with pi > 0, so that the
/// half-Sommerfeld film stays whole for small disturbances.
struct Seal
{
  FilmThickness geometry;
  OperatingConditions operating;
  Seal()
  {
    geometry.inner_radius = 0.032;
    geometry.outer_radius = 0.04;
    geometry.clearance = 1e-5;
    geometry.coning = 3.13e-3;
    operating.inner_pressure = 1e5;
    operating.outer_pressure = 1e6;
    operating.viscosity = 5e-4;
    operating.rotor_speed = 2000;
    operating.stator_speed = 0;
  }
};

/// Etsion's measure (curvature neglected: dA = rm dr dtheta, arms rm), in which the narrow-seal
/// closed forms are exact integrals.
NarrowSealQuadrature etsion_measure()
{
  NarrowSealQuadrature q;
  q.curvature = Curvature::neglected;
  return q;
}
} // namespace

TEST(FilmForceModels, NarrowSealFilmCoefficientsAreGreenEtsion)
{
  const Seal seal;
  const NarrowSealFilm film(seal.geometry, seal.operating);
  const FilmState state = FilmState::from(seal.geometry, seal.operating);
  const FilmCoefficients a = film.coefficients(state);
  const FilmCoefficients b =
      GreenEtsionCoefficients(seal.geometry, seal.operating).coefficients(2000, 0);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
    {
      EXPECT_EQ(a.stiffness[i][j], b.stiffness[i][j]);
      EXPECT_EQ(a.damping[i][j], b.damping[i][j]);
    }
  EXPECT_EQ(film.level(), FilmLevel::closed_form);
  // the factory of the dynamics builds the same model for level 0
  const auto model =
      make_film_force_model(FilmLevel::closed_form, seal.geometry, seal.operating, {});
  EXPECT_EQ(model->coefficients(state).stiffness[1][1], b.stiffness[1][1]);
}

// Axisymmetric coned face, no tilt: the narrow-seal pressure is the hydrostatic p_s of Varney &
// Green (2017) Eq. 12, p_s = po - (po - pi) h_i^2 (h_o^2 - h^2) / (h^2 (h_o^2 - h_i^2)), h = h_i
// + beta* (r - ri). With dh = beta* dr, int_ri^ro (h_o^2 - h^2)/h^2 dr = (h_o - h_i)^2 / (beta*
// h_i), so int p_s dr = L (po - (po - pi) h_i / (h_i + h_o)) and, in Etsion's measure,
//   F_z = 2 pi rm L (po - (po - pi) h_i / (h_i + h_o)),   L = ro - ri.
// Its derivative in the clearance (h_i, h_o -> h_i + z, h_o + z) is
//   K_zz = -dF_z/dz = 2 pi (po - pi) rm L^2 beta* / (h_i + h_o)^2,
// Green & Etsion's axial stiffness.
TEST(FilmForceModels, NarrowSealFilmHydrostaticForceAndAxialStiffness)
{
  const Seal seal;
  const NarrowSealFilm film(seal.geometry, seal.operating, etsion_measure());
  const FilmState state = FilmState::from(seal.geometry, seal.operating);
  const double ri = 0.032, ro = 0.04, L = ro - ri, rm = 0.5 * (ri + ro);
  const double hi = 1e-5, ho = hi + 3.13e-3 * L, pi = 1e5, po = 1e6;
  const double force = 2 * M_PI * rm * L * (po - (po - pi) * hi / (hi + ho));
  // the quadrature is accurate to ~5e-10 relative (narrow_seal.h)
  EXPECT_NEAR(film.loads(state).force_z, force, 1e-9 * force);

  const double dz = 1e-4 * hi;
  FilmState up = state, down = state;
  up.axial_offset = dz;
  down.axial_offset = -dz;
  const double k_zz = -(film.loads(up).force_z - film.loads(down).force_z) / (2 * dz);
  const double k_closed = 2 * M_PI * (po - pi) * rm * L * L * 3.13e-3 / ((hi + ho) * (hi + ho));
  // central differences: O((dz/h)^2) = 1e-8
  EXPECT_NEAR(k_zz, k_closed, 1e-6 * k_closed);
  EXPECT_NEAR(film.coefficients(state).stiffness[0][0], k_closed, 1e-12 * k_closed);
}

// The tilt block of Green & Etsion (k11, c = (omega1 + omega2)/2 d11, d11) against central
// differences of the moments of NarrowSealFilm::loads in the tilts and tilt rates, in Etsion's
// measure where Green & Etsion's forms are the exact moments of the narrow-seal pressure.
TEST(FilmForceModels, NarrowSealFilmTiltBlockIsDerivativeOfLoads)
{
  const Seal seal;
  const NarrowSealFilm film(seal.geometry, seal.operating, etsion_measure());
  const FilmState state = FilmState::from(seal.geometry, seal.operating);
  const FilmCoefficients closed = film.coefficients(state);
  auto moments = [&](const FilmState &s)
  {
    const FilmLoads l = film.loads(s);
    return std::array<double, 2>{{l.moment_x, l.moment_y}};
  };
  const double dtilt = 1e-4 * 1e-5 / 0.04; // 1e-4 of the tilt that closes the film
  const double drate = 1e-3;               // rad/s: the squeeze term is linear in the rate
  double scale_k = 0, scale_d = 0;
  for (unsigned int i = 1; i < 3; ++i)
    for (unsigned int j = 1; j < 3; ++j)
    {
      scale_k = std::max(scale_k, std::abs(closed.stiffness[i][j]));
      scale_d = std::max(scale_d, std::abs(closed.damping[i][j]));
    }
  for (unsigned int j = 0; j < 2; ++j)
  {
    FilmState tp = state, tm = state, rp = state, rm = state;
    (j == 0 ? tp.tilt_x : tp.tilt_y) = dtilt;
    (j == 0 ? tm.tilt_x : tm.tilt_y) = -dtilt;
    (j == 0 ? rp.tilt_rate_x : rp.tilt_rate_y) = drate;
    (j == 0 ? rm.tilt_rate_x : rm.tilt_rate_y) = -drate;
    const auto mtp = moments(tp), mtm = moments(tm), mrp = moments(rp), mrm = moments(rm);
    for (unsigned int i = 0; i < 2; ++i)
    {
      const double k = -(mtp[i] - mtm[i]) / (2 * dtilt);
      const double d = -(mrp[i] - mrm[i]) / (2 * drate);
      EXPECT_NEAR(k, closed.stiffness[1 + i][1 + j], 1e-6 * scale_k) << "K " << i << j;
      EXPECT_NEAR(d, closed.damping[1 + i][1 + j], 1e-6 * scale_d) << "D " << i << j;
    }
  }
}
