// Benchmark (not a timed test): the cost of repeated ReynoldsSolver::run calls on one geometry
// with only the state changing (z, tilt rate, rotor speed, outer pressure), as a transient or a
// sweep makes them, on the default mesh (P2, 8 x 128) for full film and JFO. Prints the time per
// run; the only assertion is that the numbers are finite. Uses only run(film, conditions), so the
// same file measures a solver that rebuilds the mesh every run and one that reuses it.
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

using namespace sealfe;

TEST(RepeatedRunBenchmark, TimePerRunOnOneGeometry)
{
  for (const Cavitation model : {Cavitation::none, Cavitation::jfo})
  {
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solver.cavitation.model = model;
    solver.estimate_error = false;
    FilmThickness film;
    film.tilt = 0.3 * film.clearance / film.outer_radius;
    film.wave_amplitude = 0.3e-6;
    film.wave_number = 3;
    OperatingConditions conditions;
    if (model == Cavitation::jfo)
      conditions.inner_pressure = conditions.outer_pressure = 1e5;
    solver.run(film, conditions); // first run: builds the mesh
    const unsigned int n = 40;
    std::vector<double> times;
    double sum = 0;
    for (unsigned int i = 0; i < n; ++i)
    {
      film.axial_offset = 1e-8 * std::sin(0.3 * i);
      film.tilt_rate_x = 0.01 * std::cos(0.2 * i);
      conditions.rotor_speed = 1000 + 10.0 * i;
      conditions.outer_pressure += 100;
      const auto start = std::chrono::steady_clock::now();
      sum += solver.run(film, conditions).force_z;
      times.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    std::cout << (model == Cavitation::jfo ? "jfo " : "none") << " dofs " << solver.n_dofs()
              << "  time per run: median " << times[n / 2] << " s, minimum " << times[0] << " s\n";
    EXPECT_TRUE(std::isfinite(sum));
  }
}
