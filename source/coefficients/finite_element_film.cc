#include <sealfe/coefficients/finite_element_film.h>

#include <deal.II/base/utilities.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace sealfe
{
FiniteElementFilm::FiniteElementFilm(const FilmSettings &settings, MPI_Comm comm,
                                     const CoefficientSettings &coefficient_settings)
    : base(settings), comm(comm), solver(settings, coefficient_settings, comm)
{
}

std::string FiniteElementFilm::description() const
{
  const char *cavitation[] = {"full film", "half-Sommerfeld", "Reynolds cavitation", "JFO"};
  std::ostringstream s;
  s << "finite element, degree " << base.polynomial_degree << ", "
    << cavitation[static_cast<int>(base.cavitation.model)]
    << (base.flow_factors.is_smooth() ? "" : ", rough faces")
    << (base.contact.enabled() ? ", asperity contact" : "");
  return s.str();
}

FilmLoads FiniteElementFilm::loads(const FilmState &state) const
{
  // solved in the features' frame (rotor-borne features at their Phase, where the mesh is aligned
  // with their steps), the stator-frame parts turned by -rotor_angle into it
  const FilmLoads loads =
      solver.reynolds().run(state.in_feature_frame(base.geometry), state.apply(base.conditions));
  last_frame_angle = state.feature_frame_angle(base.geometry); // the frame of the stored solution
  return state.turned_back(loads, base.geometry);
}

namespace
{
/// K or D of the features' frame, turned by `angle` into the stator frame: with q = T q' and
/// F = T F' (T = diag(1, R(angle)) on (z, tilt) and on (force, moment)), -dF/dq = T K' T^T.
FilmCoefficients::Matrix3 turned_matrix(const FilmCoefficients::Matrix3 &k, const double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  const double T[3][3] = {{1, 0, 0}, {0, c, -s}, {0, s, c}};
  FilmCoefficients::Matrix3 tk{}, out{};
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      for (unsigned int l = 0; l < 3; ++l)
        tk[i][j] += T[i][l] * k[l][j];
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      for (unsigned int l = 0; l < 3; ++l)
        out[i][j] += tk[i][l] * T[j][l];
  return out;
}
} // namespace

FilmCoefficients FiniteElementFilm::coefficients(const FilmState &state) const
{
  const auto start = std::chrono::steady_clock::now();
  const OperatingConditions conditions = state.apply(base.conditions);
  FilmCoefficients k = solver.coefficients(state.in_feature_frame(base.geometry), conditions);
  const double angle = state.feature_frame_angle(base.geometry);
  last_frame_angle = angle;
  if (angle != 0)
  {
    k.stiffness = turned_matrix(k.stiffness, angle);
    k.damping = turned_matrix(k.damping, angle);
  }
  const ReynoldsSolver &reynolds = solver.reynolds();
  std::ostringstream model;
  model << k.model << ", " << reynolds.n_dofs() << " dofs, degree " << reynolds.degree();
  k.model = model.str();
  ++n_evaluations;
  if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    std::cerr << "sealfe: level-2 film coefficients #" << n_evaluations << " at rotor speed "
              << conditions.rotor_speed << ", stator speed " << conditions.stator_speed
              << " rad/s (" << reynolds.n_dofs() << " dofs, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s)" << std::endl;
  return k;
}

} // namespace sealfe
