#include <sealfe/coefficients/finite_element_film.h>

#include <sstream>

namespace sealfe
{
FiniteElementFilm::FiniteElementFilm(const FilmSettings &settings, MPI_Comm comm,
                                     const CoefficientSettings &coefficient_settings)
    : base(settings), solver(settings, coefficient_settings, comm)
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
  return solver.coefficients(state.apply(base.geometry), state.apply(base.conditions));
}

} // namespace sealfe
