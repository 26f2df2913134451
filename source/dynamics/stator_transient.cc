#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/dynamics/equilibrium.h>
#include <sealfe/dynamics/stator_transient.h>
#include <sealfe/film/cavitation.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/sundials/arkode.h>

#include <arkode/arkode_arkstep.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using State = std::array<double, 8>; // Z, Z', a_sx, a_sy, a_sx', a_sy', beta, leaked volume

// ------------------------------------------------------------------------------------------------
// parameters

void StatorRing::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Stator ring");
  prm.declare_entry("Mass", "1", Double(), "m (kg), > 0 (Green 2002 Table 1).");
  prm.declare_entry("Transverse inertia", "8.3232e-4", Double(),
                    "I (kg m^2), > 0; Green 2002: m r_g^2 / 2 with r_g = ro.");
  prm.declare_entry("Axial stiffness", "5e5", Double(0), "K_sz (N/m) of the support.");
  prm.declare_entry("Axial damping", "300", Double(0), "D_sz (N s/m) of the support.");
  prm.declare_entry("Angular stiffness", "50", Double(0),
                    "K_s (N m/rad) of the support (not given by Green 2002; assumed).");
  prm.declare_entry("Angular damping", "0.005", Double(0),
                    "D_s (N m s/rad) of the support (not given by Green 2002; assumed).");
  prm.declare_entry("Initial misalignment", "0", Double(0),
                    "gamma_si (rad): the support's rest tilt, fixed in space (Eq. 21).");
  prm.declare_entry("Misalignment angle", "0", Double(), "Direction of gamma_si (rad).");
  prm.leave_subsection();
}

void StatorRing::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Stator ring");
  mass = prm.get_double("Mass");
  transverse_inertia = prm.get_double("Transverse inertia");
  axial_stiffness = prm.get_double("Axial stiffness");
  axial_damping = prm.get_double("Axial damping");
  angular_stiffness = prm.get_double("Angular stiffness");
  angular_damping = prm.get_double("Angular damping");
  initial_misalignment = prm.get_double("Initial misalignment");
  misalignment_angle = prm.get_double("Misalignment angle");
  prm.leave_subsection();
}

void StatorRing::validate() const
{
  std::ostringstream s;
  if (!(mass > 0) || !std::isfinite(mass))
    s << "Stator ring: Mass must be > 0, got " << mass << " kg";
  else if (!(transverse_inertia > 0) || !std::isfinite(transverse_inertia))
    s << "Stator ring: Transverse inertia must be > 0, got " << transverse_inertia << " kg m^2";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

void RotorRunout::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Rotor runout");
  prm.declare_entry("Tilt", "1e-3", Double(0), "gamma_r (rad), Green 2002 Table 1.");
  prm.declare_entry("Phase", "0", Double(), "Direction of gamma_r at t = 0 (rad).");
  prm.leave_subsection();
}

void RotorRunout::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Rotor runout");
  tilt = prm.get_double("Tilt");
  phase = prm.get_double("Phase");
  prm.leave_subsection();
}

std::array<double, 2> RotorRunout::vector(const double shaft_angle) const
{
  // film_thickness.h: the film is thickest at psi with tilt_x = gamma sin psi, tilt_y = -gamma cos
  // psi
  const double psi = shaft_angle + phase;
  return {{tilt * std::sin(psi), -tilt * std::cos(psi)}};
}

void TransientSettings::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Transient");
  prm.declare_entry("End time", "9", Double(), "t_end (s), > 0.");
  prm.declare_entry("Relative tolerance", "1e-6", Double(), "ARKode relative tolerance.");
  prm.declare_entry("Absolute tolerance", "1e-6", Double(),
                    "ARKode absolute tolerance on the scaled state (Z/C0, tilts ro/C0, coning "
                    "ro/C0, rates times 1 ms, leaked volume / 1 mm^3).");
  prm.declare_entry("Output interval", "2e-3", Double(), "Time between rows of transient.csv (s).");
  prm.declare_entry("Initial state", "given", Selection("given|rest equilibrium"),
                    "given: Z(0) = Initial axial offset * C0, stator aligned with the rotor "
                    "(Green 2002: Z(0) = -0.65 C0, gamma_s(0) = gamma_r); rest equilibrium: Z(0) "
                    "from the axial balance at t = 0.");
  prm.declare_entry("Initial axial offset", "-0.65", Double(),
                    "Z(0)/C0 for Initial state = given.");
  prm.declare_entry("Minimum step", "1e-12", Double(0),
                    "Smallest step (s); a step size collapse below it stops the run.");
  prm.declare_entry("Maximum steps per output", "200000", Integer(1),
                    "Steps allowed between two output times before the run is stopped.");
  prm.declare_entry("Contact threshold", "0.01", Double(0),
                    "In contact while the contact force exceeds this fraction of the closing "
                    "force (lift-off / touch-down times in summary.json).");
  prm.declare_entry("Order", "3", Integer(2, 5), "Order of ARKode's implicit (DIRK) method.");
  prm.declare_entry("Film level", "closed form", Selection(film_level_pattern()),
                    "closed form: narrow seal (level 0). table and finite element are not "
                    "available in this version of the transient.");
  prm.leave_subsection();
}

void TransientSettings::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Transient");
  end_time = prm.get_double("End time");
  relative_tolerance = prm.get_double("Relative tolerance");
  absolute_tolerance = prm.get_double("Absolute tolerance");
  output_interval = prm.get_double("Output interval");
  start_at_rest_equilibrium = prm.get("Initial state") == "rest equilibrium";
  initial_axial_offset = prm.get_double("Initial axial offset");
  minimum_step = prm.get_double("Minimum step");
  maximum_steps = prm.get_integer("Maximum steps per output");
  contact_threshold = prm.get_double("Contact threshold");
  order = prm.get_integer("Order");
  prm.leave_subsection();
}

void TransientSettings::validate() const
{
  std::ostringstream s;
  if (!(end_time > 0) || !std::isfinite(end_time))
    s << "Transient: End time must be > 0, got " << end_time;
  else if (!(relative_tolerance > 0) || !(absolute_tolerance > 0))
    s << "Transient: tolerances must be > 0";
  else if (!(output_interval > 0) || end_time / output_interval > 1e7)
    s << "Transient: Output interval must be > 0 and give at most 1e7 rows";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

void FlexibleStatorSeal::declare_parameters(dealii::ParameterHandler &prm)
{
  ClosingForce::declare_parameters(prm);
  StatorRing::declare_parameters(prm);
  RotorRunout::declare_parameters(prm);
  ThermalConing::declare_parameters(prm);
  OperatingRamps::declare_parameters(prm);
  FaceContact::declare_parameters(prm);
  CavitationSettings::declare_parameters(prm);
  // Green 2002 handles cavitation by half-Sommerfeld: that is this sub-command's default
  prm.enter_subsection("Cavitation");
  prm.declare_entry("Model", "half-sommerfeld",
                    dealii::Patterns::Selection("none|half-sommerfeld|reynolds|jfo"),
                    "none: full film. half-sommerfeld: p < p_cav set to p_cav in the loads (Green "
                    "2002). reynolds, jfo: finite-element film only.");
  prm.leave_subsection();
  NarrowSealQuadrature::declare_parameters(prm);
}

void FlexibleStatorSeal::parse_parameters(dealii::ParameterHandler &prm)
{
  geometry.parse_parameters(prm);
  conditions.parse_parameters(prm);
  closing.parse_parameters(prm);
  stator.parse_parameters(prm);
  runout.parse_parameters(prm);
  thermal.parse_parameters(prm);
  ramps.parse_parameters(prm);
  contact.parse_parameters(prm, geometry.inner_radius, geometry.outer_radius);
}

void FlexibleStatorSeal::validate() const
{
  conditions.validate();
  closing.validate();
  stator.validate();
  thermal.validate();
  ramps.validate();
  if (!(geometry.inner_radius > 0 && geometry.outer_radius > geometry.inner_radius &&
        geometry.clearance > 0))
    throw std::runtime_error("Geometry: need 0 < Inner radius < Outer radius and Clearance > 0");
}

double FlexibleStatorSeal::face_area() const
{
  return M_PI * (std::pow(geometry.outer_radius, 2) - std::pow(geometry.inner_radius, 2));
}

double TransientSample::stator_tilt() const
{
  return std::hypot(stator_tilt_x, stator_tilt_y);
}
double TransientSample::stator_precession() const
{
  return std::atan2(stator_tilt_x, -stator_tilt_y);
}

// ------------------------------------------------------------------------------------------------
// dynamics

struct StatorTransient::Evaluation
{
  FilmState state;
  FilmLoads film;
  FaceContact::Loads contact;
  double closing_force, heating_film;
  std::array<double, 2> rotor_tilt;
};

StatorTransient::StatorTransient(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                                 const TransientSettings &settings)
    : seal(seal), film(film), settings(settings)
{
  const double C0 = seal.geometry.clearance, ro = seal.geometry.outer_radius;
  const double rate = 1e3; // 1/s: velocities are scaled as displacements per ms
  scale = {{C0, C0 * rate, C0 / ro, C0 / ro, C0 / ro * rate, C0 / ro * rate, C0 / ro, 1e-9}};
}

StatorTransient::Evaluation StatorTransient::evaluate(const double t, const State &y) const
{
  Evaluation e;
  const double omega = seal.ramps.speed.value(t);
  const double shaft = seal.ramps.speed.integral(t);
  e.rotor_tilt = seal.runout.vector(shaft);
  // d/dt of the rotor tilt vector: omega x (gamma cos, gamma sin)
  const std::array<double, 2> rotor_rate = {{-omega * e.rotor_tilt[1], omega * e.rotor_tilt[0]}};
  FilmState &s = e.state;
  s.axial_offset = y[0];
  s.axial_velocity = y[1];
  s.tilt_x = y[2] - e.rotor_tilt[0];
  s.tilt_y = y[3] - e.rotor_tilt[1];
  s.tilt_rate_x = y[4] - rotor_rate[0];
  s.tilt_rate_y = y[5] - rotor_rate[1];
  s.rotor_speed = omega;
  s.stator_speed = 0;
  s.inner_pressure = seal.ramps.inner_pressure.value(t);
  s.outer_pressure = seal.ramps.outer_pressure.value(t);
  s.time = t;
  if (!seal.thermal.enabled())
    s.coning = seal.geometry.coning;
  else if (seal.thermal.time_constant > 0)
    s.coning = y[6];
  else
    s.coning = quasi_static_coning(seal, s);
  e.contact = seal.contact.loads(s.apply(seal.geometry));
  e.heating_film = seal.thermal.film == ThermalConing::Film::minimum
                       ? std::max(e.contact.min_film, 0.1 * seal.contact.composite_roughness())
                   : seal.thermal.film == ThermalConing::Film::centerline
                       ? seal.geometry.clearance + y[0]
                       : e.contact.heating_film;
  ++evaluations;
  e.film = film.loads(s);
  e.closing_force = seal.closing.value(seal.geometry.inner_radius, seal.geometry.outer_radius,
                                       s.inner_pressure, s.outer_pressure);
  return e;
}

State StatorTransient::rate(const double t, const State &y) const
{
  const Evaluation e = evaluate(t, y);
  const StatorRing &ring = seal.stator;
  const double gx = ring.initial_misalignment * std::sin(ring.misalignment_angle);
  const double gy = -ring.initial_misalignment * std::cos(ring.misalignment_angle);
  State d{};
  d[0] = y[1];
  d[1] = (e.film.force_z + e.contact.force - e.closing_force - ring.axial_stiffness * y[0] -
          ring.axial_damping * y[1]) /
         ring.mass;
  d[2] = y[4];
  d[3] = y[5];
  d[4] = (e.film.moment_x + e.contact.moment_x - ring.angular_stiffness * (y[2] - gx) -
          ring.angular_damping * y[4]) /
         ring.transverse_inertia;
  d[5] = (e.film.moment_y + e.contact.moment_y - ring.angular_stiffness * (y[3] - gy) -
          ring.angular_damping * y[5]) /
         ring.transverse_inertia;
  d[6] = (seal.thermal.enabled() && seal.thermal.time_constant > 0)
             ? seal.thermal.rate(y[6], e.heating_film, e.state.rotor_speed)
             : 0.0;
  d[7] = e.film.leakage_inner;
  return d;
}

State StatorTransient::initial_state() const
{
  State y{};
  const auto rotor = seal.runout.vector(0);
  y[0] = settings.initial_axial_offset * seal.geometry.clearance;
  y[2] = rotor[0];
  y[3] = rotor[1];
  y[6] = seal.thermal.initial_coning;
  if (settings.start_at_rest_equilibrium)
  {
    const Evaluation e = evaluate(0, y);
    y[0] = solve_equilibrium(seal, film, e.state).axial_offset;
  }
  return y;
}

TransientSample StatorTransient::sample(const double t, const State &y) const
{
  const Evaluation e = evaluate(t, y);
  TransientSample s;
  s.time = t;
  s.rotor_speed = e.state.rotor_speed;
  s.inner_pressure = e.state.inner_pressure;
  s.outer_pressure = e.state.outer_pressure;
  s.axial_offset = y[0];
  s.axial_velocity = y[1];
  s.stator_tilt_x = y[2];
  s.stator_tilt_y = y[3];
  s.rotor_tilt_x = e.rotor_tilt[0];
  s.rotor_tilt_y = e.rotor_tilt[1];
  s.relative_tilt = std::hypot(e.state.tilt_x, e.state.tilt_y);
  s.coning = e.state.coning;
  s.min_film = std::min(e.contact.min_film, e.film.min_film > 0 ? e.film.min_film : INFINITY);
  s.min_film_over_sigma = s.min_film / seal.contact.composite_roughness();
  s.heating_film = e.heating_film;
  s.film_force = e.film.force_z;
  s.contact_force = e.contact.force;
  s.closing_force = e.closing_force;
  s.film_moment_x = e.film.moment_x;
  s.film_moment_y = e.film.moment_y;
  s.contact_moment_x = e.contact.moment_x;
  s.contact_moment_y = e.contact.moment_y;
  s.leakage_inner = e.film.leakage_inner;
  s.friction_torque = e.film.friction_torque;
  s.leaked_volume = y[7];
  return s;
}
} // namespace sealfe
