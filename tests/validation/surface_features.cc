// Validation of surface features (film/surface_features.h) against theory:
//  - Rayleigh step pads: many pads on a wide dam -> the mid-radius pressure of Rayleigh's
//    infinitely wide step slider (closed_form/rayleigh_step.h), and his optimum;
//  - spiral grooves: many grooves -> the narrow-groove theory (closed_form/narrow_groove.h);
//  - dimples with JFO: the discrete mass balance, and the load the non-conserving models invent;
//  - the built-in mesh has cell edges on the steps (pads) and follows the spirals (grooves).
#include "../surface_feature_seals.h"

#include <sealfe/closed_form/narrow_groove.h>
#include <sealfe/closed_form/rayleigh_step.h>
#include <sealfe/film/film_summary.h>
#include <sealfe/film/surface_features.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

using namespace sealfe;
using namespace sealfe::test;

namespace
{
/// FE pressure at the step of the pad starting at angle 0 on the mid-radius circle, and Rayleigh's
/// p_max for the 1D slider at that radius (U = omega r, B = r angle).
struct StepPressure
{
  double fe, rayleigh;
};

StepPressure step_pressure(const RayleighPadSeal &seal)
{
  const FilmSettings s = seal.settings();
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  solver.run();
  const double rm = 0.5 * (seal.ri + seal.ro), t = seal.step_angle();
  // the pad half way round, away from theta = 0 (nothing special there, but the mesh wraps)
  const double shift = seal.period() * (seal.pads / 2);
  const double p =
      solver.pressure_at({dealii::Point<2>(rm * std::cos(t + shift), rm * std::sin(t + shift))})[0];
  const closed_form::RayleighStep slider{seal.film_ratio * seal.h2,
                                         seal.h2,
                                         rm * seal.step_fraction * seal.pad_angle(),
                                         rm * (1 - seal.step_fraction) * seal.pad_angle(),
                                         seal.mu,
                                         seal.omega * rm};
  return {p, slider.max_pressure()};
}
} // namespace

TEST(RayleighStep, ClosedFormOptimum)
{
  // Rayleigh's numbers: film ratio 1.866, step at 0.718 of the pad, and the maximum load
  // coefficient W h2^2 / (mu U B^2) = 0.206.
  EXPECT_NEAR(closed_form::RayleighStep::optimum_film_ratio(), 1.866, 5e-4);
  EXPECT_NEAR(closed_form::RayleighStep::optimum_step_fraction(), 0.718, 5e-4);
  const double H = closed_form::RayleighStep::optimum_film_ratio();
  const double f = closed_form::RayleighStep::optimum_step_fraction();
  const closed_form::RayleighStep s{H, 1, f, 1 - f, 1, 1};
  EXPECT_NEAR(s.load_per_width(), 0.206, 5e-4);
  // a local maximum: any step off it loses load
  for (const double dH : {-0.05, 0.05})
    EXPECT_LT((closed_form::RayleighStep{H + dH, 1, f, 1 - f, 1, 1}.load_per_width()),
              s.load_per_width());
  for (const double df : {-0.02, 0.02})
    EXPECT_LT((closed_form::RayleighStep{H, 1, f + df, 1 - f - df, 1, 1}.load_per_width()),
              s.load_per_width());
}

// Many pads on a wide dam: the mid-radius pressure at the step approaches Rayleigh's p_max as
// the dam width b over the pad length L grows. Side leakage lowers the mid-width pressure of a
// pad of finite width by about exp(-pi b / (2 L)) (the slowest decaying mode of the Laplacian
// across the pad); the remaining departure is the curvature of the annulus, O(theta_pad^2).
TEST(RayleighStep, ManyPadsApproachTheInfinitelyWideSlider)
{
  double previous = 1;
  for (const unsigned int pads : {10u, 20u, 40u, 80u})
  {
    RayleighPadSeal seal;
    seal.pads = pads;
    const StepPressure p = step_pressure(seal);
    const double b_over_L = (seal.ro - seal.ri) / (0.5 * (seal.ri + seal.ro) * seal.pad_angle());
    const double departure = (p.rayleigh - p.fe) / p.rayleigh;
    std::cout << "pads " << pads << ": b/L = " << b_over_L << ", FE " << p.fe << " Pa, Rayleigh "
              << p.rayleigh << " Pa, departure " << departure
              << " (exp(-pi b/2L) = " << std::exp(-M_PI * b_over_L / 2)
              << ", theta_pad^2 = " << seal.pad_angle() * seal.pad_angle() << ")\n";
    EXPECT_LT(std::abs(departure), previous);
    previous = std::abs(departure);
    if (pads == 80u)
    {
      EXPECT_LT(std::abs(departure),
                std::exp(-M_PI * b_over_L / 2) + seal.pad_angle() * seal.pad_angle());
    }
  }
}

// Rayleigh's optimum on the seal: with 80 pads (b/L = 4.7) the FE step pressure at
// (1.866, 0.718) beats the neighbours in film ratio and step position.
TEST(RayleighStep, OptimumOnTheSeal)
{
  RayleighPadSeal seal;
  seal.pads = 80;
  const double best = step_pressure(seal).fe;
  for (const auto &[dH, df] :
       std::vector<std::pair<double, double>>{{-0.3, 0.0}, {0.3, 0.0}, {0.0, -0.1}, {0.0, 0.1}})
  {
    RayleighPadSeal off = seal;
    off.film_ratio += dH;
    off.step_fraction += df;
    const StepPressure p = step_pressure(off);
    std::cout << "H = " << off.film_ratio << ", f = " << off.step_fraction << ": FE " << p.fe
              << " Pa (Rayleigh " << p.rayleigh << "), optimum " << best << " Pa\n";
    EXPECT_LT(p.fe, best);
  }
}

// Spiral grooves: the load and leakage approach the narrow-groove theory as the groove count
// grows. Its error is the end effect at the band edges, where the pressure adjusts over about
// one groove pitch: a load and leakage error ~ pitch / band ~ 1/N.
TEST(SpiralGrooves, ManyGroovesApproachNarrowGrooveTheory)
{
  SpiralGrooveSeal seal;
  closed_form::NarrowGrooveSeal theory{
      seal.ri,    seal.ro, seal.rg, seal.ro,    seal.h, seal.depth, seal.fraction,
      seal.alpha, true,    seal.mu, seal.omega, 0,      0,          0};
  const auto t = theory.solve();
  std::cout << "narrow groove theory: force " << t.force << " N, leakage out " << t.leakage_outer
            << " m^3/s, p(rg) " << t.p_groove_inner << " Pa\n";
  EXPECT_GT(t.force, 0);
  EXPECT_LT(t.leakage_outer, 0); // pumped inward
  std::vector<double> departures, leakage_departures;
  for (const unsigned int n : {8u, 16u, 32u})
  {
    seal.grooves = n;
    ReynoldsSolver solver(seal.settings(), MPI_COMM_WORLD);
    const FilmLoads loads = solver.run();
    const double df = (loads.force_z - t.force) / t.force;
    const double dq = (loads.leakage_outer - t.leakage_outer) / t.leakage_outer;
    std::cout << "grooves " << n << ": dofs " << solver.n_dofs() << ", force " << loads.force_z
              << " N (departure " << df << "), leakage " << loads.leakage_outer << " (departure "
              << dq << ")\n";
    departures.push_back(std::abs(df));
    leakage_departures.push_back(std::abs(dq));
  }
  // the same end effect for the load and the pumped leakage: both departures fall like 1/N
  for (const auto &d : {departures, leakage_departures})
  {
    for (std::size_t i = 1; i < d.size(); ++i)
      EXPECT_LT(d[i], d[i - 1]);
    const double order = std::log2(d[1] / d[2]);
    std::cout << "observed order in 1/N: " << order << "\n";
    EXPECT_GT(order, 0.7);
  }
}

// Dimples with JFO: the leakages balance to 1e-8 of the flow scale (the discrete mass balance
// holds to the Newton tolerance whatever the film), every dimple cavitates, and the
// half-Sommerfeld and Reynolds models (not mass conserving) carry more load than JFO: they let
// the film reform at once after the cavity.
TEST(Dimples, JfoMassBalanceAndTheLoadOtherModelsInvent)
{
  DimpledSeal seal;
  ReynoldsSolver solver(seal.settings(), MPI_COMM_WORLD);
  const FilmLoads jfo = solver.run();
  EXPECT_LT(relative_mass_imbalance(solver, jfo, "JFO"), 1e-8);
  const auto &f = *solver.settings.geometry.features;
  std::cout << "dimples: " << f.count() << " per row, area density " << f.achieved_area_density()
            << "\n";
  EXPECT_GT(jfo.cavitated_fraction, 0.0);
  EXPECT_GT(jfo.force_z, 0.0);
  for (const std::string model : {"half-sommerfeld", "reynolds"})
  {
    DimpledSeal other = seal;
    other.cavitation = model;
    ReynoldsSolver s(other.settings(), MPI_COMM_WORLD);
    const FilmLoads l = s.run();
    std::cout << model << ": force " << l.force_z << " N ("
              << (l.force_z - jfo.force_z) / jfo.force_z * 100
              << " % above JFO), cavitated fraction " << l.cavitated_fraction << ", leakages "
              << l.leakage_inner << " + " << l.leakage_outer << "\n";
    EXPECT_GT(l.force_z, jfo.force_z);
  }
}

// The mesh: pads have cell edges on every step angle; spiral grooves' mesh lines follow the
// spirals (every vertex on a groove edge has the groove depth on one side and none on the
// other).
TEST(SurfaceFeatures, MeshLinesOnTheSteps)
{
  RayleighPadSeal seal;
  seal.pads = 10;
  const FilmSettings s = seal.settings();
  AnnulusMesh mesh = s.mesh;
  mesh.alignment = s.geometry.features->mesh_alignment();
  const std::vector<double> angles = mesh.angular_nodes(mesh.circumferential_cells);
  for (const double target : {0.0, seal.groove_angle(), seal.step_angle()})
  {
    double nearest = 1;
    for (const double a : angles)
      nearest = std::min(nearest, std::abs(std::remainder(a - target, seal.period())));
    EXPECT_LT(nearest, 1e-12) << target;
  }
  SpiralGrooveSeal spiral;
  const FilmSettings g = spiral.settings();
  mesh = g.mesh;
  mesh.alignment = g.geometry.features->mesh_alignment();
  const auto &features = *g.geometry.features;
  const double period = 2 * M_PI / spiral.grooves;
  for (const double r : {0.034, 0.036, 0.039})
  {
    // the groove edges at this radius are mesh-line angles: depth changes just across them
    const double edge = mesh.alignment.phase + mesh.alignment.shift(r);
    const double e = 1e-9;
    EXPECT_EQ(features.depth(r, edge + e), spiral.depth);
    EXPECT_EQ(features.depth(r, edge - e), 0.0);
    EXPECT_EQ(features.depth(r, edge + spiral.fraction * period - e), spiral.depth);
    EXPECT_EQ(features.depth(r, edge + spiral.fraction * period + e), 0.0);
  }
}

// The frame of the textured face (reynolds_solver.cc, local_film): on an axisymmetric film only
// the relative speed of the faces matters, so (1) stator features with the stator turning at w2
// and the rotor at w1 give the loads of w2 = 0 and w1 - w2; (2) the same features on the rotor
// (pads mirrored: their drawing runs in -theta) give the mirror image of the stator case: the
// same force, leakages and friction torque (the torque resisting the rotor, integrated on the
// smooth face, film_loads.cc). Pads (full film) and dimples (JFO: the cavity moves with the
// dimples; the dimple pattern is its own mirror image). Tolerance 1e-8: the JFO Newton
// tolerance (1e-10 relative mass residual) with margin.
TEST(SurfaceFeatures, OnlyTheRelativeSpeedMatters)
{
  RayleighPadSeal pads;
  pads.pads = 10;
  DimpledSeal dimples;
  dimples.cells_around = 256;
  dimples.radial_cells = 8;
  for (FilmSettings base : {pads.settings(), dimples.settings()})
  {
    base.conditions.inner_pressure = base.conditions.outer_pressure = 1e5;
    base.conditions.reference_pressure = 1e5;
    ReynoldsSolver a(base, MPI_COMM_WORLD);
    const FilmLoads still = a.run();

    FilmSettings turning = base;
    turning.conditions.stator_speed = 200;
    turning.conditions.rotor_speed += 200;
    ReynoldsSolver b(turning, MPI_COMM_WORLD);
    const FilmLoads moving = b.run();

    FilmSettings on_rotor = base;
    auto features = std::make_shared<SurfaceFeatures>(*base.geometry.features);
    features->face = SurfaceFeatures::Face::rotor;
    on_rotor.geometry.features = features;
    ReynoldsSolver c(on_rotor, MPI_COMM_WORLD);
    const FilmLoads rotor = c.run();

    const double flow_scale = mass_balance_flow_scale(base.geometry, base.conditions, still);
    for (const FilmLoads *l : {&moving, &rotor})
    {
      std::cout << "force " << l->force_z << " vs " << still.force_z << ", leakage "
                << l->leakage_outer << " vs " << still.leakage_outer << ", friction "
                << l->friction_torque << " vs " << still.friction_torque << ", cavitated "
                << l->cavitated_fraction << " vs " << still.cavitated_fraction << "\n";
      EXPECT_NEAR(l->force_z, still.force_z, 1e-8 * std::abs(still.force_z));
      // leakages against the flow scale (pi = po: they are small)
      EXPECT_NEAR(l->leakage_outer, still.leakage_outer, 1e-8 * flow_scale);
      EXPECT_NEAR(l->leakage_inner, still.leakage_inner, 1e-8 * flow_scale);
      EXPECT_NEAR(l->friction_torque, still.friction_torque,
                  1e-8 * std::abs(still.friction_torque));
      EXPECT_NEAR(l->cavitated_fraction, still.cavitated_fraction, 1e-8);
    }
  }
}

// Bad feature input: one line each, naming the problem.
TEST(SurfaceFeatures, BadInputIsRefusedInOneLine)
{
  const std::string pads = "subsection Geometry\n subsection Surface features\n"
                           "  subsection Rayleigh pads\n   set Number = 12\n";
  const std::string end = "  end\n end\nend\n";
  for (const std::string &text :
       {pads + "   set Step depth = 0\n" + end,
        pads + "   set Step depth = 1e-6\n   set Pad angle = 0.6\n" + end,
        pads + "   set Step depth = 1e-6\n   set Inner radius = 0.02\n" + end,
        pads + "   set Step depth = 1e-6\n   set Feeding groove angle = 0.05\n" + end,
        pads +
            "   set Step depth = 1e-6\n  end\n  subsection Spiral grooves\n   set Number = 8\n"
            "   set Depth = 1e-6\n" +
            end,
        std::string("subsection Geometry\n subsection Surface features\n  subsection Dimples\n"
                    "   set Area density = 0.78\n   set Radius = 2e-3\n   set Depth = 1e-6\n") +
            end})
  {
    std::string message;
    try
    {
      parse_settings(text);
    }
    catch (std::runtime_error &e)
    {
      message = e.what();
    }
    std::cout << message << "\n";
    EXPECT_NE(message.find("Surface features"), std::string::npos) << text;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  // a mesh that cannot put edges on the steps of 12 pads
  RayleighPadSeal seal;
  seal.pads = 12;
  FilmSettings s = seal.settings();
  s.mesh.circumferential_cells = 100;
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  try
  {
    solver.run();
    ADD_FAILURE() << "not refused";
  }
  catch (std::runtime_error &e)
  {
    std::cout << e.what() << "\n";
    EXPECT_NE(std::string(e.what()).find("Align with features"), std::string::npos);
  }
}
