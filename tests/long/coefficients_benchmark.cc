// Benchmark (not a timed test): the cost of a full set of film coefficients (6 linearised solves,
// one batched ReynoldsSolver::linearized_loads call) against the solve it linearises
// (ReynoldsSolver::run), and the cost of the finite-difference check, over mesh sizes. Prints a
// table for doc/coefficients.md; the only assertions are that the numbers are finite.
#include <sealfe/coefficients/coefficient_solver.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

using namespace sealfe;

namespace
{
double seconds(const std::chrono::steady_clock::time_point &t)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// The minimum over repeats: on a shared machine other processes only ever add time, so the
/// minimum is the best estimate of the uncontended cost.
double minimum(const std::vector<double> &v)
{
  return *std::min_element(v.begin(), v.end());
}
} // namespace

TEST(CoefficientsBenchmark, CostOfACoefficientSetAgainstTheSolve)
{
  FilmThickness film; // the Varney & Green seal, slightly tilted (a general film)
  film.tilt = 0.3 * film.clearance / film.outer_radius;
  film.tilt_angle = 0.7;
  const OperatingConditions conditions;
  std::cout << "degree  radial x circ  dofs     solve [s]  6 linearised [s]  ratio  "
               "per-solve [s]  FD 12 solves [s]\n";
  for (const unsigned int degree : {2u, 3u})
    for (const auto &[nr, nt] : std::vector<std::pair<unsigned int, unsigned int>>{
             {4, 32}, {8, 64}, {8, 128}, {16, 256}, {32, 512}})
    {
      CoefficientSolver s(MPI_COMM_WORLD);
      s.reynolds().polynomial_degree = degree;
      s.reynolds().mesh().radial_cells = nr;
      s.reynolds().mesh().circumferential_cells = nt;
      s.reynolds().estimate_error = false;
      const unsigned int repeats = nt <= 64 ? 21 : (nt <= 256 ? 9 : 5);
      std::vector<double> t_solve, t_lin;
      // What CoefficientSolver does: the 6 directions in one batched call.
      std::vector<ReynoldsSolver::FilmPerturbation> directions(6);
      const std::function<double(double, double)> shapes[3] = {
          [](double, double) { return 1.0; }, [](double r, double th) { return r * std::sin(th); },
          [](double r, double th) { return -r * std::cos(th); }};
      for (unsigned int j = 0; j < 3; ++j)
      {
        directions[j].dh = shapes[j];
        directions[3 + j].dh_dt = shapes[j];
      }
      for (unsigned int k = 0; k < repeats; ++k)
      {
        auto t = std::chrono::steady_clock::now();
        s.reynolds().run(film, conditions);
        t_solve.push_back(seconds(t));
        t = std::chrono::steady_clock::now();
        s.reynolds().linearized_loads(directions);
        t_lin.push_back(seconds(t));
      }
      double t_fd = 0;
      if (nt <= 256)
      {
        s.settings.method = CoefficientSettings::Method::finite_difference;
        const CoefficientResult r = s.compute(film, conditions);
        t_fd = r.coefficient_time;
        s.settings.method = CoefficientSettings::Method::perturbation;
      }
      const double a = minimum(t_solve), b = minimum(t_lin);
      std::cout << std::setw(6) << degree << std::setw(8) << nr << " x " << std::setw(4) << nt
                << std::setw(9) << s.reynolds().n_dofs() << std::setw(12) << std::setprecision(4)
                << a << std::setw(16) << b << std::setw(10) << b / a << std::setw(14) << b / 6
                << std::setw(16) << t_fd << std::endl;
      // Where the time of the last run + coefficient set went (s).
      s.reynolds().run(film, conditions);
      s.reynolds().linearized_loads(directions);
      std::cout << "        stages:";
      for (const auto &[stage, time] : s.reynolds().stage_times())
        std::cout << " " << stage << " " << time;
      std::cout << std::endl;
      EXPECT_TRUE(std::isfinite(b / a));
    }
}
