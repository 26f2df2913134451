// Long study (ctest label "long"): the error estimate of the hard JFO cases against fine
// meshes (issue 14, item 4). Each estimate of the production mesh must bound the difference to the
// finest mesh, the finest mesh's own error counted at the lowest order the three-mesh rule credits
// (0.5).
#include <sealfe/film/film_summary.h>
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>

using namespace sealfe;

namespace
{
struct Case
{
  FilmSettings settings;
  unsigned int nr, nt;            // production mesh
  std::vector<unsigned int> fine; // refinement factors of the references
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
  const double ratio = c.fine.back(), p = 0.5;
  const double factor = std::pow(ratio, p) / (std::pow(ratio, p) - 1);
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
    const double difference = std::abs(loads.*member - references.back().*member);
    const double bound = e[name].get<double>();
    EXPECT_LE(factor * difference, bound) << name;
  }
}
} // namespace

// The Varney & Green seal with flat faces tilted to ε = 0.999 (h_min = 1e-9 m), JFO, on the
// default 8 x 128 cells; references 4x and 8x finer (32 x 512, 64 x 1024).
TEST(ErrorEstimateReference, TiltedTo0999)
{
  Case c;
  c.settings.geometry.coning = 0;
  c.settings.geometry.tilt =
      0.999 * c.settings.geometry.clearance / c.settings.geometry.outer_radius;
  c.settings.cavitation.model = Cavitation::jfo;
  c.nr = 8;
  c.nt = 128;
  c.fine = {4, 8};
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
