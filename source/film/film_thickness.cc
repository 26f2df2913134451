#include <sealfe/film/film_expression.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/surface_features.h>
#include <sealfe/numerics/minimisation.h>
#include <sealfe/numerics/number_lists.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
void FilmThickness::declare_parameters(dealii::ParameterHandler &prm)
{
  using dealii::Patterns::Double;
  const FilmThickness defaults; // the member initialisers are the defaults
  // Physical bounds (doc/guarantees.md): beyond them no face seal exists and the film equation
  // overflows or loses every digit in double precision. Non-positive values that have a message
  // of their own in validate() are left to it.
  const double lowest = Double::min_double_value;
  const double max_radius = 10;    // m
  const double max_film = 1e-2;    // m: a film of 1 cm is no thin film
  const double max_angle = 1;      // rad
  const double max_velocity = 1e3; // m/s, axial squeeze velocity
  const double max_rate = 1e6;     // rad/s, tilt rates
  prm.enter_subsection("Geometry");
  prm.declare_entry("Inner radius", numerics::to_prm_string(defaults.inner_radius),
                    Double(0, max_radius), "Inner radius ri of the sealing dam (m).");
  prm.declare_entry("Outer radius", numerics::to_prm_string(defaults.outer_radius),
                    Double(0, max_radius), "Outer radius ro of the sealing dam (m).");
  prm.declare_entry("Clearance", numerics::to_prm_string(defaults.clearance),
                    Double(lowest, max_film),
                    "Centreline clearance C0 (m): the film at r = ri on the tilt's neutral line.");
  prm.declare_entry("Coning", numerics::to_prm_string(defaults.coning),
                    Double(-max_angle, max_angle),
                    "Coning beta (rad): h grows by beta*(r - ri); positive opens outward.");
  prm.declare_entry("Tilt", numerics::to_prm_string(defaults.tilt), Double(0, max_angle),
                    "Relative tilt gamma of the faces (rad).");
  prm.declare_entry("Tilt angle", numerics::to_prm_string(defaults.tilt_angle), Double(),
                    "Angle psi (rad) at which the tilt makes the film thickest.");
  prm.declare_entry("Wave amplitude", numerics::to_prm_string(defaults.wave_amplitude),
                    Double(-max_film, max_film), "Circumferential waviness amplitude A_w (m).");
  prm.declare_entry("Wave number", numerics::to_prm_string(defaults.wave_number), Double(0),
                    "Number of waves n_w per revolution.");
  prm.declare_entry("Wave phase", numerics::to_prm_string(defaults.wave_phase), Double(),
                    "Angle theta_w (rad) of a waviness crest: A_w cos(n_w (theta - theta_w)).");
  prm.declare_entry(
      "Axial offset", numerics::to_prm_string(defaults.axial_offset), Double(-max_film, max_film),
      "Axial displacement z (m) of the flexible ring from the set point (adds to h).");
  prm.declare_entry("Film expression", "", dealii::Patterns::Anything(),
                    "Additional film term (m) added to h, a formula (muparser) in r (m), theta "
                    "(rad), x, y (m), t (s) and the constants below, e.g. a*cos(n*theta)*(r - "
                    "0.0355)/0.005. Empty: none. A formula that makes the film touch down is "
                    "refused like any other touch-down.");
  prm.declare_entry("Film expression constants", "", dealii::Patterns::Anything(),
                    "Constants of the film expression, e.g. \"a=1e-6, n=8\".");
  SurfaceFeatures::declare_parameters(prm);
  prm.leave_subsection();

  prm.enter_subsection("Squeeze motion");
  prm.declare_entry("Axial velocity", numerics::to_prm_string(defaults.axial_velocity),
                    Double(-max_velocity, max_velocity),
                    "Axial velocity dz/dt (m/s) of the flexible ring (opens the film if > 0).");
  prm.declare_entry("Tilt rate x", numerics::to_prm_string(defaults.tilt_rate_x),
                    Double(-max_rate, max_rate),
                    "Rate (rad/s) of the flexible ring's tilt about the x axis (w = tilt_x y).");
  prm.declare_entry("Tilt rate y", numerics::to_prm_string(defaults.tilt_rate_y),
                    Double(-max_rate, max_rate),
                    "Rate (rad/s) of the flexible ring's tilt about the y axis (w = -tilt_y x).");
  prm.leave_subsection();
}

void FilmThickness::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Geometry");
  inner_radius = prm.get_double("Inner radius");
  outer_radius = prm.get_double("Outer radius");
  clearance = prm.get_double("Clearance");
  coning = prm.get_double("Coning");
  tilt = prm.get_double("Tilt");
  tilt_angle = prm.get_double("Tilt angle");
  wave_amplitude = prm.get_double("Wave amplitude");
  wave_number = prm.get_double("Wave number");
  wave_phase = prm.get_double("Wave phase");
  axial_offset = prm.get_double("Axial offset");
  const std::string formula = prm.get("Film expression");
  expression.reset();
  if (formula.find_first_not_of(" \t") != std::string::npos)
    expression = std::make_shared<const FilmExpression>(
        formula, prm.get("Film expression constants"), outer_radius);
  features = SurfaceFeatures::parse(prm, inner_radius, outer_radius);
  prm.leave_subsection();
  prm.enter_subsection("Squeeze motion");
  axial_velocity = prm.get_double("Axial velocity");
  tilt_rate_x = prm.get_double("Tilt rate x");
  tilt_rate_y = prm.get_double("Tilt rate y");
  prm.leave_subsection();
}

double FilmThickness::added_value(const double r, const double theta) const
{
  double h = 0;
  if (expression)
    h += expression->value(r, theta + frame_angle, time);
  if (features)
    h += features->depth(r, theta);
  return h;
}

double FilmThickness::expression_d_dr(const double r, const double theta) const
{
  return expression->d_dr(r, theta + frame_angle, time);
}

double FilmThickness::expression_d_dtheta(const double r, const double theta) const
{
  return expression->d_dtheta(r, theta + frame_angle, time);
}

double FilmThickness::expression_d_dt(const double r, const double theta) const
{
  return expression->d_dt(r, theta + frame_angle, time);
}

double FilmThickness::feature_frame_speed(const double rotor_speed, const double stator_speed) const
{
  if (!features)
    return 0;
  return features->face == SurfaceFeatures::Face::rotor ? rotor_speed : stator_speed;
}

bool FilmThickness::features_on_rotor() const
{
  return features && features->face == SurfaceFeatures::Face::rotor;
}

FilmThickness FilmThickness::turned_frame(const double angle) const
{
  FilmThickness h = *this;
  if (angle == 0)
    return h;
  // a vector v of the old frame has the components R(-angle) v in the new one; the tilt's
  // thickest direction psi becomes psi - angle, as a wave crest theta_w becomes theta_w - angle
  const double c = std::cos(angle), s = std::sin(angle);
  h.tilt_angle = tilt_angle - angle;
  h.tilt_rate_x = c * tilt_rate_x + s * tilt_rate_y;
  h.tilt_rate_y = -s * tilt_rate_x + c * tilt_rate_y;
  h.wave_phase = wave_phase - angle;
  h.frame_angle = frame_angle + angle;
  return h;
}

void FilmThickness::set_tilt_vector(const double tx, const double ty)
{
  tilt = std::hypot(tx, ty);
  tilt_angle = (tilt > 0) ? std::atan2(tx, -ty) : 0.0;
}

namespace
{
/// Extremum of h over the dam: h is linear in r at fixed theta, so the extremes lie on r = ri or
/// r = ro; on each circle the extremum in theta is sampled finely and polished, or, without
/// waviness, taken in closed form (the tilt term gamma r cos(theta - phi) is extreme at phi and
/// phi + pi): the transient asks for it at every film evaluation.
FilmThickness::Extremum extremum(const FilmThickness &h, const bool maximum)
{
  FilmThickness::Extremum best{0, 0, 0};
  bool first = true;
  if (h.expression)
  {
    // Analytic film + a formula: no longer linear in r. Sample a polar grid (33 circles x 2048
    // angles), then polish the best sample by alternating Brent searches in theta and r.
    // Surface features (recesses) are left out: they never bring the faces closer.
    const auto film = [&](const double r, const double theta)
    {
      const double v =
          h.analytic_value(r, theta) + h.expression->value(r, theta + h.frame_angle, h.time);
      return maximum ? -v : v;
    };
    const unsigned int nr = 32, nt = 2048;
    double best_value = std::numeric_limits<double>::infinity(), r_best = 0, t_best = 0;
    for (unsigned int i = 0; i <= nr; ++i)
      for (unsigned int j = 0; j < nt; ++j)
      {
        const double r = h.inner_radius + (h.outer_radius - h.inner_radius) * i / nr;
        const double t = 2 * M_PI * j / nt;
        const double v = film(r, t);
        if (v < best_value)
          best_value = v, r_best = r, t_best = t;
      }
    const double dr = (h.outer_radius - h.inner_radius) / nr, dt = 2 * M_PI / nt;
    for (unsigned int round = 0; round < 3; ++round)
    {
      const auto in_theta =
          numerics::sampled_minimum([&](const double t) { return film(r_best, t); }, t_best - dt,
                                    t_best + dt, 8, numerics::Domain::interval);
      if (in_theta.value < best_value)
        best_value = in_theta.value, t_best = in_theta.x;
      const auto in_r = numerics::sampled_minimum(
          [&](const double r) { return film(r, t_best); }, std::max(h.inner_radius, r_best - dr),
          std::min(h.outer_radius, r_best + dr), 8, numerics::Domain::interval);
      if (in_r.value < best_value)
        best_value = in_r.value, r_best = in_r.x;
    }
    best = {maximum ? -best_value : best_value, r_best, std::fmod(t_best + 4 * M_PI, 2 * M_PI)};
    if (maximum && h.features)
      best.value += h.features->max_depth();
    return best;
  }
  for (const double r : {h.inner_radius, h.outer_radius})
  {
    if (h.wave_amplitude == 0)
    {
      const bool at_tilt_angle = (h.tilt >= 0) == maximum;
      const double theta =
          std::fmod(h.tilt_angle + (at_tilt_angle ? 0 : M_PI) + 4 * M_PI, 2 * M_PI);
      const double value = h.value(r, theta);
      if (first || (maximum ? value > best.value : value < best.value))
        best = {value, r, theta};
      first = false;
      continue;
    }
    const auto on_circle = [&](const double theta) { return h.value(r, theta); };
    const numerics::Minimum m =
        maximum
            ? numerics::sampled_maximum(on_circle, 0, 2 * M_PI, 4096, numerics::Domain::periodic)
            : numerics::sampled_minimum(on_circle, 0, 2 * M_PI, 4096, numerics::Domain::periodic);
    if (first || (maximum ? m.value > best.value : m.value < best.value))
      best = {m.value, r, std::fmod(m.x + 4 * M_PI, 2 * M_PI)};
    first = false;
  }
  if (maximum && h.features)
    best.value += h.features->max_depth(); // an upper bound
  return best;
}
} // namespace

FilmThickness::Extremum FilmThickness::minimum() const
{
  return extremum(*this, false);
}

FilmThickness::Extremum FilmThickness::maximum() const
{
  return extremum(*this, true);
}

void FilmThickness::validate(const bool allow_touch_down) const
{
  auto fail = [](const std::string &what) { throw std::runtime_error(what); };
  for (double v : {inner_radius, outer_radius, clearance, coning, tilt, tilt_angle, wave_amplitude,
                   wave_number, axial_offset})
    if (!std::isfinite(v))
      fail("Geometry: a parameter is not a finite number");
  if (!(inner_radius > 0))
    fail("Geometry: Inner radius must be positive (got " + numerics::to_prm_string(inner_radius) +
         " m)");
  if (!(outer_radius > inner_radius))
  {
    std::ostringstream s;
    s << "Geometry: Inner radius (" << inner_radius << " m) must be smaller than Outer radius ("
      << outer_radius << " m)";
    fail(s.str());
  }
  if (!(clearance > 0))
  {
    std::ostringstream s;
    s << "Geometry: Clearance must be positive (got " << clearance << " m)";
    fail(s.str());
  }
  if (wave_amplitude != 0 && wave_number != std::round(wave_number))
  {
    std::ostringstream s;
    s << "Geometry: Wave number must be a whole number of waves per revolution (got " << wave_number
      << "): otherwise the film jumps at theta = 0";
    fail(s.str());
  }
  const Extremum m = minimum();
  if (expression && !std::isfinite(m.value))
    fail("Geometry: Film expression '" + expression->formula() +
         "' is not a finite number everywhere on the dam (a division by zero or a log of a "
         "non-positive number?)");
  if (!(m.value > 0) && !allow_touch_down)
  {
    std::ostringstream s;
    s << "Geometry: the film touches down: h = " << m.value << " m (overlap " << 0.0 - m.value
      << " m) at r = " << m.r << " m, theta = " << m.theta << " rad"
      << (expression ? " with Film expression '" + expression->formula() + "'" : std::string())
      << "; reduce tilt/waviness" << (expression ? "/the expression" : "")
      << " or raise the clearance (or model rough faces in contact: "
         "Roughness/Model = patir-cheng with Contact/Model = gw-ceb)";
    fail(s.str());
  }
}

} // namespace sealfe
