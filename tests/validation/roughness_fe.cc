// Rough faces in the finite-element solver: Patir-Cheng average flow and GW/CEB contact.
//  - smooth limit: as h/sigma grows the loads tend to the smooth solution, bounded by the flow
//    factors' own departure from 1;
//  - surface pattern: transverse roughness (gamma < 1) leaks more than isotropic, longitudinal
//    (gamma > 1) less (phi_r > 1 resp. < 1, Patir & Cheng 1978);
//  - the shear-flow term is antisymmetric in which face is rough (the full-film problem is
//    linear in phi_s = (V_r1 - V_r2) Phi_s);
//  - mixed lubrication (Green (2002) Table 1 asperities): total load falls monotonically with the
//    clearance and the asperity share vanishes above h/sigma ~ 3-4 (Green 2002).
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
FilmLoads solve(const FilmThickness &film, const FlowFactors &flow,
                const AsperityContact::Model contact_model = AsperityContact::Model::none,
                const double share = 0.5)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  s.flow_factors = flow;
  if (!flow.is_smooth())
    s.flow_factors = FlowFactors(FlowFactors::Model::patir_cheng, flow.composite_roughness(),
                                 flow.surface_pattern(), share);
  if (contact_model != AsperityContact::Model::none)
  {
    AsperityContactParameters p; // Green 2002 Table 1
    p.composite_roughness = flow.composite_roughness();
    s.contact = AsperityContact(contact_model, p);
  }
  return s.run(film, OperatingConditions());
}
} // namespace

TEST(RoughnessFE, SmoothLimit)
{
  FilmThickness film; // default coned seal, min h = C0 = 1 um at r = ri
  film.tilt = 0.3 * film.clearance / film.outer_radius;
  const FilmLoads smooth = solve(film, FlowFactors());
  std::vector<double> departures;
  for (const double H_min : {10.0, 30.0, 100.0})
  {
    const FlowFactors flow(FlowFactors::Model::patir_cheng, film.clearance / H_min);
    const FilmLoads rough = solve(film, flow);
    const double d = std::abs(rough.force_z / smooth.force_z - 1);
    const double dq = std::abs(rough.leakage_outer / smooth.leakage_outer - 1);
    // the flow factors' largest departure from 1 on this film (at its thinnest point)
    const auto ff = flow.film_factors(film.clearance);
    const double bound = std::max({std::abs(ff.phi_r.value - 1), std::abs(ff.phi_theta.value - 1),
                                   std::abs(ff.h_T.value / film.clearance - 1)});
    std::cout << "h_min/sigma = " << H_min << ": force " << d << ", leakage " << dq
              << ", factor departure " << bound << "\n";
    EXPECT_LE(d, 3 * bound + 1e-12); // h^3 phi: three times the factor departure at most
    EXPECT_LE(dq, 3 * bound + 1e-12);
    departures.push_back(d);
  }
  EXPECT_LT(departures[2], departures[0]);
  EXPECT_LT(departures[2], 1e-4);
}

TEST(RoughnessFE, SurfacePatternOrdersLeakage)
{
  FilmThickness film;
  const double sigma = film.clearance / 3; // h_min/sigma = 3
  std::vector<double> q;
  for (const double gamma : {1.0 / 3, 1.0, 3.0})
    q.push_back(
        solve(film, FlowFactors(FlowFactors::Model::patir_cheng, sigma, gamma)).leakage_inner);
  std::cout << "leakage transverse " << q[0] << ", isotropic " << q[1] << ", longitudinal " << q[2]
            << "\n";
  EXPECT_GT(q[0], q[1]);
  EXPECT_GT(q[1], q[2]);
}

TEST(RoughnessFE, ShearFlowFlipsWithTheRoughFace)
{
  FilmThickness film;
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  const FlowFactors flow(FlowFactors::Model::patir_cheng, film.clearance / 3);
  const FilmLoads rotor = solve(film, flow, AsperityContact::Model::none, 1.0);
  const FilmLoads both = solve(film, flow, AsperityContact::Model::none, 0.5);
  const FilmLoads stator = solve(film, flow, AsperityContact::Model::none, 0.0);
  const double effect = rotor.moment_x - both.moment_x;
  std::cout << "shear-flow effect on moment_x: rotor rough " << effect << ", stator rough "
            << stator.moment_x - both.moment_x << " (of " << both.moment_x << ")\n";
  EXPECT_GT(std::abs(effect), 1e-4 * std::abs(both.moment_x)); // the term does act
  EXPECT_NEAR(stator.moment_x - both.moment_x, -effect, 1e-8 * std::abs(both.moment_x));
  EXPECT_NEAR(stator.force_z + rotor.force_z, 2 * both.force_z, 1e-8 * both.force_z);
}

TEST(RoughnessFE, MixedLubricationLoadCurve)
{
  const double sigma = 5e-7;
  const FlowFactors flow(FlowFactors::Model::patir_cheng, sigma);
  double previous = std::numeric_limits<double>::max();
  for (const double H : {0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0})
  {
    FilmThickness film;
    film.clearance = H * sigma;
    const FilmLoads l = solve(film, flow, AsperityContact::Model::gw_ceb);
    const double share = l.contact_force / l.force_z;
    std::cout << "h_min/sigma " << H << ": total " << l.force_z << " N, contact " << share
              << " of it, real contact area " << l.contact_area_fraction << "\n";
    EXPECT_LT(l.force_z, previous); // monotone in the clearance
    previous = l.force_z;
    EXPECT_NEAR(l.min_film_over_sigma, H, 1e-9);
    if (H >= 4)
    {
      EXPECT_LT(share, 1e-2); // the asperities carry nothing above h/sigma ~ 3-4
    }
    if (H <= 1)
    {
      EXPECT_GT(share, 0.5); // and most of the load near touch-down
    }
  }
}

TEST(RoughnessFE, TouchDownIsCarriedByTheAsperities)
{
  FilmThickness film;
  film.tilt = 3e-5; // h < 0 near (ro, pi): an error for a smooth film
  film.coning = 0;
  const FlowFactors flow(FlowFactors::Model::patir_cheng, 5e-7);
  EXPECT_THROW(solve(film, FlowFactors()), std::runtime_error);
  const FilmLoads l = solve(film, flow, AsperityContact::Model::gw_ceb);
  EXPECT_TRUE(std::isfinite(l.force_z));
  EXPECT_GT(l.contact_force, 0);
  EXPECT_LT(l.min_film, 0);
  EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer), 1e-9 * std::abs(l.leakage_inner));
}
