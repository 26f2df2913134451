// Long study (ctest label "long"): the error estimate of the hard JFO cases against fine
// meshes (issue 14, item 4). Each estimate of the production mesh must bound its difference to the
// value extrapolated from the finest meshes.
#include <sealfe/film/film_summary.h>
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace sealfe;

namespace
{
struct Case
{
  FilmSettings settings;
  unsigned int nr, nt;            // production mesh
  std::vector<unsigned int> fine; // refinement factors of the references: 2, 4, ...
};

FilmLoads solve_on(FilmSettings s, unsigned int nr, unsigned int nt)
{
  s.mesh.radial_cells = nr;
  s.mesh.circumferential_cells = nt;
  s.estimate_error = false;
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  return solver.run();
}

void check(const Case &c)
{
  FilmSettings s = c.settings;
  s.mesh.radial_cells = c.nr;
  s.mesh.circumferential_cells = c.nt;
  ReynoldsSolver solver(s, MPI_COMM_WORLD);
  const FilmLoads loads = solver.run();
  const nlohmann::json summary = finite_element_solve_summary(s, solver, loads, MPI_COMM_WORLD);
  const auto &e = summary["error_estimate"];
  ASSERT_TRUE(e["available"].get<bool>());
  std::vector<FilmLoads> references;
  for (const unsigned int f : c.fine)
    references.push_back(solve_on(s, f * c.nr, f * c.nt));
  std::cout << "stage_wall_time " << summary["stage_wall_time"] << "\n";
  for (const auto &[name, member] : {std::pair{"force_z", &FilmLoads::force_z},
                                     {"moment_y", &FilmLoads::moment_y},
                                     {"leakage_inner", &FilmLoads::leakage_inner},
                                     {"friction_torque", &FilmLoads::friction_torque},
                                     {"cavitated_fraction", &FilmLoads::cavitated_fraction}})
  {
    const auto &g = e["grid_convergence"][name];
    std::cout << name << ": " << loads.*member << " +- " << e[name] << " (old +- "
              << g["two_mesh_estimate"] << ", " << g["convergence"].get<std::string>()
              << ", observed order " << g["observed_order"] << "); references";
    for (unsigned int i = 0; i < c.fine.size(); ++i)
      std::cout << " " << c.fine[i] << "x: " << references[i].*member;
    std::cout << "\n";
    // The exact value from the finest meshes (each twice the previous): Richardson with their
    // own observed order, clamped to [0.5, 2].
    const unsigned int n = references.size();
    const double q1 = references[n - 1].*member, q2 = references[n - 2].*member,
                 q3 = n > 2 ? references[n - 3].*member : loads.*member;
    const double p = std::clamp(std::log2(std::abs((q2 - q3) / (q1 - q2))), 0.5, 2.0);
    const double exact = q1 + (q1 - q2) / (std::pow(2.0, p) - 1);
    const double error = std::abs(loads.*member - exact);
    std::cout << "  order of the finest meshes " << p << ", extrapolated " << exact << ", error "
              << error << "\n";
    EXPECT_LE(error, e[name].get<double>()) << name;
  }
}
} // namespace

// The Varney & Green seal with flat faces tilted to ε = 0.999 (h_min = 1e-9 m), JFO, on the
// default 8 x 128 cells; references 2x, 4x and 8x finer (up to 64 x 1024).
TEST(ErrorEstimateReference, TiltedTo0999)
{
  Case c;
  c.settings.geometry.coning = 0;
  c.settings.geometry.tilt =
      0.999 * c.settings.geometry.clearance / c.settings.geometry.outer_radius;
  c.settings.cavitation.model = Cavitation::jfo;
  c.nr = 8;
  c.nt = 128;
  c.fine = {2, 4, 8};
  check(c);
}

// The wavy JFO example (prm/wavy_jfo.prm: 3 waves of 0.5 C0, flat faces, 2e4/5e4 Pa) at a rotor
// speed of 1e5 rad/s (cavity over ~95 % of the dam), on its 8 x 256 cells; references 2x and 4x
// finer.
TEST(ErrorEstimateReference, WavyAt1e5RadPerSecond)
{
  Case c;
  c.settings.geometry.coning = 0;
  c.settings.geometry.wave_amplitude = 0.5e-6;
  c.settings.geometry.wave_number = 3;
  c.settings.conditions.inner_pressure = 2e4;
  c.settings.conditions.outer_pressure = 5e4;
  c.settings.conditions.rotor_speed = 1e5;
  c.settings.cavitation.model = Cavitation::jfo;
  c.nr = 8;
  c.nt = 256;
  c.fine = {2, 4};
  check(c);
}
