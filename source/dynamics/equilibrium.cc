#include <sealfe/dynamics/equilibrium.h>

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace
{
double heating_film(const FlexibleStatorSeal &seal, const FilmState &state)
{
  const FaceContact::Loads c = seal.contact.loads(state.apply(seal.geometry));
  switch (seal.thermal.film)
  {
  case ThermalConing::Film::minimum:
    return std::max(c.min_film, 0.1 * seal.contact.composite_roughness());
  case ThermalConing::Film::centerline:
    return seal.geometry.clearance + state.axial_offset;
  default:
    return c.heating_film;
  }
}
} // namespace

double quasi_static_coning(const FlexibleStatorSeal &seal, FilmState state)
{
  auto f = [&](const double beta)
  {
    state.coning = beta;
    return seal.thermal.quasi_static(heating_film(seal, state), state.rotor_speed);
  };
  const double f0 = f(0);
  if (!(f0 > 0))
    return 0;
  auto g = [&](const double beta) { return beta - f(beta); };
  const double g1 = g(f0);
  if (g1 <= 0)
    return f0;
  boost::uintmax_t iterations = 100;
  const auto root = boost::math::tools::toms748_solve(
      g, 0.0, f0, -f0, g1, boost::math::tools::eps_tolerance<double>(40), iterations);
  return 0.5 * (root.first + root.second);
}

SealEquilibrium solve_equilibrium(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                                  const FilmState &at)
{
  FilmState state = at;
  state.tilt_x = state.tilt_y = 0;
  state.axial_velocity = state.tilt_rate_x = state.tilt_rate_y = 0;
  const double C0 = seal.geometry.clearance, sigma = seal.contact.composite_roughness();
  const double closing = seal.closing.value(seal.geometry.inner_radius, seal.geometry.outer_radius,
                                            state.inner_pressure, state.outer_pressure);
  SealEquilibrium eq;
  eq.closing_force = closing;
  auto balance = [&](const double z)
  {
    state.axial_offset = z;
    state.coning = seal.thermal.enabled() ? quasi_static_coning(seal, state) : seal.geometry.coning;
    const double film_force = film.loads(state).force_z;
    const double contact = seal.contact.loads(state.apply(seal.geometry)).force;
    return film_force + contact - seal.stator.axial_stiffness * z - closing;
  };
  // the film at r = ri is C0 + z: scan it geometrically from sigma/2 to 1e3 C0
  const double h_low = 0.5 * sigma, h_high = 1e3 * C0;
  const unsigned int n = 80;
  double z_prev = h_low - C0, g_prev = balance(z_prev);
  if (g_prev < 0)
  {
    std::ostringstream s;
    s << "equilibrium: the closing force " << closing << " N closes the faces below any film: "
      << "film + contact at a film of sigma/2 carry only " << closing + g_prev << " N (short by "
      << -g_prev << " N)";
    throw std::runtime_error(s.str());
  }
  double lo = NAN, hi = NAN, g_lo = 0, g_hi = 0;
  for (unsigned int k = 1; k <= n; ++k)
  {
    const double h = h_low * std::pow(h_high / h_low, double(k) / n);
    const double z = h - C0, g = balance(z);
    if (g_prev >= 0 && g < 0)
    {
      if (eq.roots_found == 0)
      {
        lo = z_prev;
        hi = z;
        g_lo = g_prev;
        g_hi = g;
      }
      ++eq.roots_found;
    }
    else if (g_prev < 0 && g >= 0)
      ++eq.roots_found;
    z_prev = z;
    g_prev = g;
  }
  if (eq.roots_found == 0)
  {
    std::ostringstream s;
    s << "equilibrium: the closing force " << closing << " N cannot hold the faces: they would "
      << "open without bound (the film still carries " << closing + g_prev << " N at a "
      << "clearance of " << h_high << " m, " << g_prev << " N more than the closing force)";
    throw std::runtime_error(s.str());
  }
  boost::uintmax_t iterations = 200;
  const auto root = boost::math::tools::toms748_solve(
      balance, lo, hi, g_lo, g_hi, boost::math::tools::eps_tolerance<double>(45), iterations);
  eq.axial_offset = 0.5 * (root.first + root.second);
  balance(eq.axial_offset);
  eq.coning = state.coning;
  eq.film = film.loads(state);
  eq.contact = seal.contact.loads(state.apply(seal.geometry));
  eq.support_force = -seal.stator.axial_stiffness * eq.axial_offset;
  return eq;
}
SteadyWhirl solve_steady_whirl(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                               const TransientSettings &settings, const TransientState &guess)
{
  auto solve_at = [&](const double s, TransientState g, unsigned int *iterations)
  {
    FlexibleStatorSeal scaled = seal;
    scaled.runout.tilt *= s;
    scaled.rotor.angular.dynamic_misalignment *= s;
    scaled.stator.initial_misalignment *= s;
    const auto r = scaled.runout.vector(0);
    g[8] = r[0];
    g[9] = r[1];
    return StatorTransient(scaled, film, settings).steady_state(0, g, iterations);
  };
  SteadyWhirl w;
  w.state = guess;
  double s_reached = 0, ds = 0.25;
  while (s_reached < 1)
  {
    const double next = std::min(1.0, s_reached + ds);
    unsigned int iterations = 0;
    try
    {
      w.state = solve_at(next, w.state, &iterations);
      w.newton_iterations += iterations;
      ++w.continuation_steps;
      s_reached = next;
      ds = std::min(2 * ds, 0.25);
    }
    catch (NoSteadyState &)
    {
      throw;
    }
    catch (std::runtime_error &e)
    {
      ds /= 2;
      if (ds < 1e-3)
      {
        std::ostringstream m;
        m << "equilibrium: the steady whirl exists only up to " << s_reached
          << " of the runout / misalignment forcing (a fold: beyond it the response jumps; "
             "run `sealfe transient`). Last Newton failure: "
          << e.what();
        throw std::runtime_error(m.str());
      }
    }
  }
  return w;
}
} // namespace sealfe
