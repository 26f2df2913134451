#include <sealfe/coefficients/finite_element_film.h>

#include <deal.II/base/utilities.h>

#include <chrono>
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
  return solver.reynolds().run(state.apply(base.geometry), state.apply(base.conditions));
}

FilmCoefficients FiniteElementFilm::coefficients(const FilmState &state) const
{
  const auto start = std::chrono::steady_clock::now();
  const OperatingConditions conditions = state.apply(base.conditions);
  FilmCoefficients k = solver.coefficients(state.apply(base.geometry), conditions);
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
