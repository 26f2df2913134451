// Long study (ctest label "long"): mesh convergence of seals with surface features on the
// built-in mesh with cell edges on the film's steps (aligned) and on the plain polar grid
// (unaligned), observed orders from successive halvings; dimples with JFO (cavitated area and
// load); and the cost of JFO against the full film on faces that resolve 12 spiral grooves and
// about 1000 dimples.
#include "../surface_feature_seals.h"

#include <sealfe/film/surface_features.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <vector>

#include <unistd.h>

using namespace sealfe;
using namespace sealfe::test;

namespace
{
struct Timed
{
  FilmLoads loads;
  double dofs, seconds;
};

Timed solve(const FilmSettings &s)
{
  const auto start = std::chrono::steady_clock::now();
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  const FilmLoads loads = solver.run();
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {loads, double(solver.n_dofs()), t};
}

/// Observed orders log2(|q_4h - q_2h| / |q_2h - q_h|) of a load over a sequence of halvings.
std::vector<double> orders(const std::vector<Timed> &runs, double FilmLoads::*load)
{
  std::vector<double> p;
  for (std::size_t i = 2; i < runs.size(); ++i)
    p.push_back(std::log2(std::abs(runs[i - 2].loads.*load - runs[i - 1].loads.*load) /
                          std::abs(runs[i - 1].loads.*load - runs[i].loads.*load)));
  return p;
}

void print(const std::string &what, const std::vector<Timed> &runs,
           const std::vector<std::pair<std::string, double FilmLoads::*>> &loads)
{
  for (const Timed &r : runs)
  {
    std::cout << what << ": dofs " << r.dofs << ", " << r.seconds << " s";
    for (const auto &[name, m] : loads)
      std::cout << ", " << name << " " << r.loads.*m;
    std::cout << "\n";
  }
  for (const auto &[name, m] : loads)
  {
    std::cout << what << ": observed orders of " << name << ":";
    for (const double p : orders(runs, m))
      std::cout << " " << p;
    std::cout << "\n";
  }
}
} // namespace

// Rayleigh pads (20 pads, b/L = 1.2: a two-dimensional pressure field), degree 2. Aligned: the
// film is smooth inside every cell, so the loads converge at the order of a smooth problem
// (2k = 4 for a full film) unless the corners of the steps limit it. Unaligned: cells straddle
// the steps and the quadrature samples a jump: O(h).
TEST(SurfaceFeaturesLong, RayleighPadsAlignedAndUnaligned)
{
  for (const bool align : {true, false})
  {
    std::vector<Timed> runs;
    for (const unsigned int k : {1u, 2u, 4u, 8u})
    {
      RayleighPadSeal seal;
      seal.pads = 20;
      seal.cells_per_pad = 10 * k;
      seal.radial_cells = 4 * k;
      seal.align = align;
      runs.push_back(solve(seal.settings()));
    }
    print(align ? "pads aligned" : "pads unaligned", runs,
          {{"force_z", &FilmLoads::force_z}, {"friction_torque", &FilmLoads::friction_torque}});
    const std::vector<double> p = orders(runs, &FilmLoads::force_z);
    if (align)
    {
      EXPECT_GT(p.back(), 1.8); // well above the unaligned O(h)
    }
  }
}

// Spiral grooves (16), degree 2: the aligned mesh's theta-lines follow the log spirals (the
// mesh is sheared), unaligned = plain polar grid. The grooves end inside the dam (r = 33 mm):
// there the film's jump has acute corners (alpha = 17 degrees), where the pressure gradient is
// singular, so neither mesh recovers the smooth order; both must converge (order > 0.5).
TEST(SurfaceFeaturesLong, SpiralGroovesAlignedAndUnaligned)
{
  for (const bool align : {true, false})
  {
    std::vector<Timed> runs;
    for (const unsigned int k : {1u, 2u, 4u, 8u})
    {
      SpiralGrooveSeal seal;
      seal.cells_per_groove = 4 * k;
      seal.radial_cells = 4 * k;
      seal.align = align;
      runs.push_back(solve(seal.settings()));
    }
    print(align ? "spiral aligned" : "spiral unaligned", runs,
          {{"force_z", &FilmLoads::force_z}, {"leakage_outer", &FilmLoads::leakage_outer}});
    EXPECT_GT(orders(runs, &FilmLoads::force_z).back(), 0.5);
  }
}

// Dimples with JFO (degree 1: the cavity edge limits the order to about 1 anyway): force and
// cavitated fraction under refinement, and the mass balance on every mesh. One row of 29 large
// dimples (r_p = 2 mm) so that the finest mesh (2048 x 64 cells) has 35 cells across a dimple.
TEST(SurfaceFeaturesLong, DimplesJfoConvergence)
{
  std::vector<Timed> runs;
  for (const unsigned int k : {2u, 4u, 8u, 16u})
  {
    DimpledSeal seal;
    seal.radius = 2e-3;
    seal.degree = 1;
    seal.cells_around = 128 * k;
    seal.radial_cells = 4 * k;
    runs.push_back(solve(seal.settings()));
    const FilmLoads &l = runs.back().loads;
    const double flow_scale = 0.25 * seal.omega * seal.h * (seal.ro * seal.ro - seal.ri * seal.ri);
    EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer + l.squeeze_flow), 1e-8 * flow_scale);
  }
  print("dimples jfo", runs,
        {{"force_z", &FilmLoads::force_z},
         {"cavitated_fraction", &FilmLoads::cavitated_fraction},
         {"friction_torque", &FilmLoads::friction_torque}});
  // converging: the last difference smaller than the one before
  for (double FilmLoads::*m : {&FilmLoads::force_z, &FilmLoads::cavitated_fraction})
    EXPECT_GT(orders(runs, m).back(), 0.0);
}

// The same dimples on the gmsh mesh with lines on the circles (Mesh size 1 mm = r_p / 2, then 0..4
// refinements that keep the new vertices on the circles: nested meshes, 2 to 32 cells across a
// dimple). Full film: the pressure of a flat dimple between two equal ambient pressures is odd
// about the dimple's centre line, so the exact force above ambient is 0; the fitted mesh is not
// symmetric, its force is the discretisation error, O(h^2) for degree 1 with the steps on cell
// edges (the pressure is smooth on each side of a step; the polygon misses the circles by O(h^2)).
// JFO: the cavity's reformation edge is free (not a mesh line) and the streamline term is
// O(h)-consistent (doc/reynolds.md): order 1 expected.
TEST(SurfaceFeaturesLong, DimplesOnTheFittedMesh)
{
  const std::string file = (std::filesystem::temp_directory_path() /
                            ("sealfe-long-dimples-" + std::to_string(::getpid()) + ".msh"))
                               .string();
  for (const std::string model : {"none", "jfo"})
  {
    std::vector<Timed> runs;
    for (const unsigned int refinements : {0u, 1u, 2u, 3u, 4u})
    {
      DimpledSeal seal;
      seal.radius = 2e-3;
      seal.degree = 1;
      seal.cavitation = model;
      seal.mesh_size = 1e-3;
      seal.mesh_file = file;
      seal.refinements = refinements;
      runs.push_back(solve(seal.settings()));
      const FilmLoads &l = runs.back().loads;
      const double flow_scale =
          0.25 * seal.omega * seal.h * (seal.ro * seal.ro - seal.ri * seal.ri);
      EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer + l.squeeze_flow), 1e-8 * flow_scale);
    }
    print("dimples fitted " + model, runs,
          {{"force_z", &FilmLoads::force_z},
           {"cavitated_fraction", &FilmLoads::cavitated_fraction},
           {"friction_torque", &FilmLoads::friction_torque}});
    if (model == "none")
    {
      // the force itself is the error: order from successive values
      for (std::size_t k = 1; k < runs.size(); ++k)
        EXPECT_GT(std::log2(std::abs(runs[k - 1].loads.force_z / runs[k].loads.force_z)), 1.8);
      EXPECT_GT(orders(runs, &FilmLoads::friction_torque).back(), 1.8);
    }
    else
    {
      // order 1 for the cavity (measured 0.95, 0.98). The force is still pre-asymptotic at
      // these sizes (orders 0.55, 0.72 up to 620 000 dofs; 1.27 with one refinement more, 2.5e6
      // dofs, too large for this test), so only convergence is claimed: each of the last two
      // changes of the force is smaller than the one before (an order > 0), no rate.
      EXPECT_GT(orders(runs, &FilmLoads::cavitated_fraction).back(), 0.8);
      auto change = [&](const std::size_t k)
      { return std::abs(runs[k].loads.force_z - runs[k - 1].loads.force_z); };
      for (std::size_t k = runs.size() - 2; k < runs.size(); ++k)
        EXPECT_LT(change(k), change(k - 1));
    }
  }
  std::filesystem::remove(file);
}

// Speed (issue 16): faces that resolve 12 spiral grooves and ~1000 dimples, JFO against the
// full film on the same mesh.
TEST(SurfaceFeaturesLong, JfoCostOnResolvedFaces)
{
  {
    SpiralGrooveSeal seal;
    seal.grooves = 12;
    seal.cells_per_groove = 32;
    seal.radial_cells = 32;
    FilmSettings s = seal.settings();
    // ambient supply on both circles so that the film cavitates downstream of the grooves only
    s.conditions.inner_pressure = s.conditions.outer_pressure = 1e5;
    s.conditions.reference_pressure = 1e5;
    const Timed full = solve(s);
    s.cavitation.model = Cavitation::jfo;
    const Timed jfo = solve(s);
    std::cout << "12 spiral grooves: dofs " << jfo.dofs << ", full film " << full.seconds
              << " s, JFO " << jfo.seconds << " s, ratio " << jfo.seconds / full.seconds
              << ", cavitated fraction " << jfo.loads.cavitated_fraction << ", force "
              << full.loads.force_z << " / " << jfo.loads.force_z << " N\n";
  }
  {
    // r_p = 0.3 mm, S_p = 0.2: 5 rows of 195 dimples (975), 8 cells per dimple pitch
    DimpledSeal seal;
    seal.radius = 3e-4;
    seal.degree = 1;
    seal.cells_around = 195 * 8;
    seal.radial_cells = 40;
    seal.cavitation = "none";
    FilmSettings s = seal.settings();
    std::cout << "dimples: " << s.geometry.features->count() << " per row, area density "
              << s.geometry.features->achieved_area_density() << "\n";
    const Timed full = solve(s);
    s.cavitation.model = Cavitation::jfo;
    const Timed jfo = solve(s);
    std::cout << "~1000 dimples: dofs " << jfo.dofs << ", full film " << full.seconds << " s, JFO "
              << jfo.seconds << " s, ratio " << jfo.seconds / full.seconds
              << ", cavitated fraction " << jfo.loads.cavitated_fraction << ", force "
              << jfo.loads.force_z << " N\n";
  }
}
