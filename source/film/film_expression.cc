#include <sealfe/film/film_expression.h>
#include <sealfe/numerics/number_lists.h>

#include <deal.II/base/utilities.h>

#include <cctype>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace
{
[[noreturn]] void fail(const std::string &what)
{
  throw std::runtime_error("Geometry: Film expression: " + what);
}

bool is_name_start(const char c)
{
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool is_name_char(const char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

/// Walks the formula token by token: `name(identifier)` for each whole identifier, `other(text)`
/// for everything else (a number with its exponent, "1e-6", is one token: its e is not a name).
template <typename Name, typename Other>
void for_each_token(const std::string &formula, Name name, Other other)
{
  for (std::size_t i = 0; i < formula.size();)
  {
    std::size_t j = i;
    if (is_name_start(formula[i]))
    {
      while (j < formula.size() && is_name_char(formula[j]))
        ++j;
      name(formula.substr(i, j - i));
    }
    else if (std::isdigit(static_cast<unsigned char>(formula[i])) || formula[i] == '.')
    {
      while (j < formula.size() &&
             (std::isdigit(static_cast<unsigned char>(formula[j])) || formula[j] == '.'))
        ++j;
      if (j < formula.size() && (formula[j] == 'e' || formula[j] == 'E'))
      {
        std::size_t k = j + 1;
        if (k < formula.size() && (formula[k] == '+' || formula[k] == '-'))
          ++k;
        if (k < formula.size() && std::isdigit(static_cast<unsigned char>(formula[k])))
        {
          j = k;
          while (j < formula.size() && std::isdigit(static_cast<unsigned char>(formula[j])))
            ++j;
        }
      }
      other(formula.substr(i, j - i));
    }
    else
      other(formula.substr(i, ++j - i));
    i = j;
  }
}

/// The parser knows x, y and t only: rewrite the names r and theta (whole identifiers,
/// so "rho" or "theta0" stay) as functions of x and y.
std::string polar_to_cartesian(const std::string &formula)
{
  std::string out;
  for_each_token(
      formula,
      [&](const std::string &name) {
        out += name == "r" ? "sqrt(x*x+y*y)" : name == "theta" ? "atan2(y,x)" : name;
      },
      [&](const std::string &text) { out += text; });
  return out;
}

/// Whether the identifier `name` occurs in the formula (whole identifiers, as above).
bool mentions(const std::string &formula, const std::string &name)
{
  bool found = false;
  for_each_token(
      formula, [&](const std::string &n) { found = found || n == name; },
      [](const std::string &) {});
  return found;
}

std::map<std::string, double> parse_constants(const std::string &list)
{
  std::map<std::string, double> constants;
  for (const std::string &item : dealii::Utilities::split_string_list(list, ','))
  {
    if (item.empty())
      continue;
    const auto eq = item.find('=');
    const std::string name = dealii::Utilities::trim(item.substr(0, eq));
    if (eq == std::string::npos || name.empty() || !is_name_start(name[0]))
      fail("constant '" + item + "' is not of the form name=value (Film expression constants)");
    for (const char c : name)
      if (!is_name_char(c))
        fail("constant name '" + name + "' is not a name (letters, digits, _)");
    for (const char *reserved : {"r", "theta", "x", "y", "t", "pi", "Pi", "e"})
      if (name == reserved)
        fail("constant name '" + name + "' is reserved (r, theta, x, y, t, pi, e)");
    const double v = numerics::parse_finite_number(
        item.substr(eq + 1), "Geometry: Film expression constants: constant '" + name + "'");
    constants[name] = v;
  }
  return constants;
}

/// deal.II's exceptions carry a multi-line report; keep the muparser message on one line.
std::string one_line(const std::string &what)
{
  std::string s = what;
  const auto info = s.find("Additional information:");
  if (info != std::string::npos)
    s = s.substr(info + std::string("Additional information:").size());
  const auto stack = s.find("Stacktrace:");
  if (stack != std::string::npos)
    s = s.substr(0, stack);
  std::string out;
  for (const char c : s)
    if (c == '\n' || c == '\t' || c == '-')
    {
      if (!out.empty() && out.back() != ' ')
        out += ' ';
      if (c == '-' && !out.empty())
        out.back() = '-';
    }
    else if (!(c == ' ' && !out.empty() && out.back() == ' '))
      out += c;
  return dealii::Utilities::trim(out);
}
} // namespace

FilmExpression::FilmExpression(const std::string &formula, const std::string &constants,
                               const double ro)
    : text(formula), parser(1, 0.0),
      // Centred differences: the truncation error is O(step^2), the round-off O(eps / step); a
      // relative step eps^(1/3) ~ 6e-6 of the length scale balances the two (error ~1e-11 of the
      // derivative for a film that varies on the scale of the dam).
      r_step(6e-6 * ro),
      // t is reserved (no constant can be named t), so a formula without the name t is steady
      time_dependent(mentions(formula, "t"))
{
  if (dealii::Utilities::trim(formula).empty())
    fail("the formula is empty");
  const auto c = parse_constants(constants);
  // deal.II prints muparser's report to std::cerr before it throws: keep it for the one-line
  // message instead.
  std::ostringstream report;
  std::streambuf *const cerr_buffer = std::cerr.rdbuf(report.rdbuf());
  try
  {
    parser.initialize("x,y,t", polar_to_cartesian(formula), c);
    // muparser reports unknown names and some syntax errors only when it evaluates
    const double v = parser.value(dealii::Point<3>(ro, 0, 0));
    (void)v;
    std::cerr.rdbuf(cerr_buffer);
  }
  catch (std::exception &e)
  {
    std::cerr.rdbuf(cerr_buffer);
    fail("'" + formula + "' cannot be evaluated: " + one_line(e.what()) +
         " (variables: r, theta, x, y, t; constants from Film expression constants)");
  }
}

double FilmExpression::value(const double r, const double theta, const double t) const
{
  return parser.value(dealii::Point<3>(r * std::cos(theta), r * std::sin(theta), t));
}

// The derivatives are centred differences in the polar coordinates themselves, not
// FunctionParser::gradient: that differentiates in x and y only (no t) with a fixed absolute
// step, and d/dr, d/dtheta would then need the chain rule at every point; here each derivative
// is two evaluations with a step scaled to its variable (r: 6e-6 ro; theta: 6e-6 rad, relative
// truncation error (n 6e-6)^2 / 6 for a film with n waves; t: 1e-7 s, relative error
// (w 1e-7)^2 / 6 for a film varying at w rad/s, 2e-5 at w = 1e5 rad/s).
double FilmExpression::d_dr(const double r, const double theta, const double t) const
{
  return (value(r + r_step, theta, t) - value(r - r_step, theta, t)) / (2 * r_step);
}

double FilmExpression::d_dtheta(const double r, const double theta, const double t) const
{
  const double step = 6e-6;
  return (value(r, theta + step, t) - value(r, theta - step, t)) / (2 * step);
}

double FilmExpression::d_dt(const double r, const double theta, const double t) const
{
  // exactly zero without t: spares two parser calls per quadrature point of every solve
  if (!time_dependent)
    return 0;
  const double step = 1e-7;
  return (value(r, theta, t + step) - value(r, theta, t - step)) / (2 * step);
}

} // namespace sealfe
