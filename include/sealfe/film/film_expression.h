// FilmExpression: an additional film term h_e(r, theta, x, y, t) (m) written as a formula
// (muparser through deal.II's FunctionParser), with user constants; added to FilmThickness.
#pragma once

#include <deal.II/base/function_parser.h>

#include <string>

namespace sealfe
{
/// A parsed film formula. Variables: r (m), theta (rad, from +x towards +y, in (-pi, pi]), x, y
/// (m) and t (s); constants from a list "a=1e-6, n=8". Derivatives by centred differences in
/// (r, theta, t) with steps scaled to the dam (see film_expression.cc for why).
class FilmExpression
{
public:
  /// Throws std::runtime_error with one line naming the problem (an unparsable formula, an
  /// unknown name, a malformed or reserved constant). `ro` sets the radial difference step.
  FilmExpression(const std::string &formula, const std::string &constants, const double ro);

  double value(const double r, const double theta, const double t) const;
  double d_dr(const double r, const double theta, const double t) const;
  double d_dtheta(const double r, const double theta, const double t) const;
  double d_dt(const double r, const double theta, const double t) const;

  const std::string &formula() const { return text; }
  /// Whether the formula names t (a film that changes in time by itself).
  bool depends_on_time() const { return time_dependent; }

private:
  std::string text;
  /// Variables x, y, t as a point of three coordinates (r and theta rewritten), not a
  /// time-dependent parser: value() then changes no state that threads share (the assembly
  /// evaluates the film on several; deal.II keeps one muparser per thread).
  dealii::FunctionParser<3> parser;
  double r_step;
  bool time_dependent; // the formula names t
};

} // namespace sealfe
