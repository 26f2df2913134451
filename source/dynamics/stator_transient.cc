#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/dynamics/equilibrium.h>
#include <sealfe/dynamics/stator_transient.h>
#include <sealfe/film/cavitation.h>
#include <sealfe/numerics/number_lists.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using State = TransientState;
using Vector2 = std::array<double, 2>;

namespace
{
/// J v, the quarter turn counter-clockwise (the sense of the shaft's rotation)
Vector2 quarter_turn(const Vector2 &v)
{
  return {{-v[1], v[0]}};
}
} // namespace

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
  return tilt_vector(tilt, shaft_angle + phase);
}

void RotorRing::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  using numerics::to_prm_string;
  const RotorRing d;
  prm.enter_subsection("Rotor ring");
  prm.declare_entry("Model", "rigid", Selection("rigid|flexible"),
                    "rigid: the rotor face tilts by the runout of `Rotor runout`, turning with the "
                    "shaft (Green 2002). flexible: Varney & Green 2017 Eq. 5-6, the angular rotor "
                    "on the shaft's stiffness, held at the runout tilt as its static misalignment "
                    "chi_s (axially rigid).");
  prm.declare_entry("Transverse inertia", to_prm_string(d.angular.transverse_inertia), Double(),
                    "I_tr (kg m^2), > 0 (Varney & Green 2017 Table 2).");
  prm.declare_entry("Polar inertia", to_prm_string(d.angular.polar_inertia), Double(0),
                    "I_pr (kg m^2): gyroscopic coupling I_pr omega.");
  prm.declare_entry("Angular stiffness", to_prm_string(d.angular.support_stiffness), Double(0),
                    "K_r (N m/rad), the shaft's.");
  prm.declare_entry("Angular damping", to_prm_string(d.angular.support_damping), Double(0),
                    "D_r (N m s/rad), external damping.");
  prm.declare_entry("Rotating damping", to_prm_string(d.angular.rotating_damping), Double(0),
                    "D_omega_r (N m s/rad): damping that turns with the rotor (circulatory "
                    "stiffness omega D_omega_r).");
  prm.declare_entry("Dynamic misalignment", to_prm_string(d.angular.dynamic_misalignment),
                    Double(0),
                    "chi (rad): principal axes against the spin axis; forces (I_tr - I_pr) chi "
                    "omega^2 (Varney & Green 2017 Appendix A).");
  prm.declare_entry("Axial stiffness", to_prm_string(d.axial_stiffness), Double(0),
                    "K_zr (N/m) of Varney & Green 2017 Eq. 7: > 0 makes the flexible rotor's "
                    "axial motion a state (the film gap is C0 + Z - u_zr); 0: axially rigid.");
  prm.declare_entry("Axial damping", to_prm_string(d.axial_damping), Double(0), "D_zr (N s/m).");
  prm.declare_entry("Mass", to_prm_string(d.mass), Double(0),
                    "m_r (kg), > 0 when Axial stiffness > 0.");
  prm.leave_subsection();
}

void RotorRing::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Rotor ring");
  flexible = prm.get("Model") == "flexible";
  angular.transverse_inertia = prm.get_double("Transverse inertia");
  angular.polar_inertia = prm.get_double("Polar inertia");
  angular.support_stiffness = prm.get_double("Angular stiffness");
  angular.support_damping = prm.get_double("Angular damping");
  angular.rotating_damping = prm.get_double("Rotating damping");
  angular.dynamic_misalignment = prm.get_double("Dynamic misalignment");
  axial_stiffness = prm.get_double("Axial stiffness");
  axial_damping = prm.get_double("Axial damping");
  mass = prm.get_double("Mass");
  prm.leave_subsection();
}

void RotorRing::validate() const
{
  if (!flexible)
    return;
  std::ostringstream s;
  if (!(angular.transverse_inertia > 0) || !std::isfinite(angular.transverse_inertia))
    s << "Rotor ring: Transverse inertia must be > 0, got " << angular.transverse_inertia
      << " kg m^2";
  else
    for (const double v :
         {angular.polar_inertia, angular.support_stiffness, angular.support_damping,
          angular.rotating_damping, angular.dynamic_misalignment, axial_stiffness, axial_damping})
      if (!(v >= 0) || !std::isfinite(v))
      {
        s << "Rotor ring: inertia, stiffness, damping and misalignment must be finite and >= 0, "
             "got "
          << v;
        break;
      }
  if (s.str().empty() && axial_stiffness > 0 && !(mass > 0 && std::isfinite(mass)))
    s << "Rotor ring: Mass must be > 0 with an Axial stiffness, got " << mass << " kg";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

void TransientSettings::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Transient");
  prm.declare_entry("End time", "9", Double(), "t_end (s), > 0.");
  prm.declare_entry("Relative tolerance", "1e-5", Double(), "IDA (BDF) relative tolerance.");
  prm.declare_entry("Absolute tolerance", "1e-5", Double(),
                    "IDA absolute tolerance on the scaled state (Z/C0, tilts ro/C0, coning "
                    "ro/C0, rates times 1 ms, leaked volume / 1 mm^3).");
  prm.declare_entry("Output interval", "0.01", Double(), "Time between rows of transient.csv (s).");
  prm.declare_entry("Initial state", "given", Selection("given|rest equilibrium"),
                    "given: Z(0) = Initial axial offset * C0, stator aligned with the rotor "
                    "(Green 2002: Z(0) = -0.65 C0, gamma_s(0) = gamma_r); rest equilibrium: Z(0) "
                    "from the axial balance at t = 0.");
  prm.declare_entry("Initial axial offset", "-0.65", Double(),
                    "Z(0)/C0 for Initial state = given.");
  prm.declare_entry("Initial tilt", "0", Double(),
                    "Relative tilt of the stator to the rotor at t = 0 (rad), the stator at rest "
                    "in space (0: aligned, as Green 2002).");
  prm.declare_entry("Initial tilt angle", "0", Double(), "Direction of the initial tilt (rad).");
  prm.declare_entry("Minimum step", "1e-12", Double(0),
                    "Smallest step (s); a step size collapse below it stops the run.");
  prm.declare_entry("Maximum steps per output", "200000", Integer(1),
                    "Steps allowed between two output times before the run is stopped.");
  prm.declare_entry("Contact threshold", "0.01", Double(0),
                    "In contact while the contact force exceeds this fraction of the closing "
                    "force (lift-off / touch-down times in summary.json).");
  prm.declare_entry("Order", "2", Integer(1, 5),
                    "Largest order of IDA's variable-order BDF. 2: BDF1-2 are A-stable; at orders "
                    "3-5 the film's lightly damped half-frequency whirl (eigenvalues near the "
                    "imaginary axis) made the step size erratic (order 5: 93-9809 steps for "
                    "the 9-s cycle, not monotone in the tolerance; doc/transient.md).");
  prm.declare_entry("Frame", "auto", Selection("auto|inertial|rotating"),
                    "Frame of the stator-tilt state. rotating: turns with the shaft, so a "
                    "steady whirl under rotor runout is a constant state and the integrator "
                    "takes long steps; inertial: fixed in space (steady under a stator "
                    "misalignment without runout). auto: rotating unless there is no runout "
                    "and a stator misalignment (doc/transient.md).");
  prm.declare_entry("Film level", "closed form", Selection(film_level_pattern()),
                    "closed form (level 0): narrow seal, none or half-Sommerfeld (Green 2002); "
                    "table (level 1): FE loads interpolated in Table file, the squeeze part "
                    "from its damping; finite element (level 2): an FE solve at each "
                    "evaluation (subsections Discretization, Cavitation, Roughness; any "
                    "cavitation model; Contact/Model must stay none).");
  prm.declare_entry("Table file", "", Anything(),
                    "Film level = table: the CSV of `sealfe table` with load columns, over the "
                    "clearance, coning, tilt, speed and pressure the transient visits.");
  prm.declare_entry("Table interpolation", "cubic", Selection("cubic|linear"),
                    "Film level = table: cubic Lagrange (4 nodes per axis) or multilinear.");
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
  initial_tilt = prm.get_double("Initial tilt");
  initial_tilt_angle = prm.get_double("Initial tilt angle");
  minimum_step = prm.get_double("Minimum step");
  maximum_steps = prm.get_integer("Maximum steps per output");
  contact_threshold = prm.get_double("Contact threshold");
  order = prm.get_integer("Order");
  frame = prm.get("Frame");
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
  RotorRing::declare_parameters(prm);
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
  rotor.parse_parameters(prm);
  thermal.parse_parameters(prm);
  ramps.parse_parameters(prm);
  contact.parse_parameters(prm, geometry.inner_radius, geometry.outer_radius);
}

void FlexibleStatorSeal::validate() const
{
  conditions.validate();
  closing.validate();
  stator.validate();
  rotor.validate();
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
  FilmState state; ///< the film's state, tilts in the integration frame
  FilmLoads film;
  FaceContact::Loads contact;
  double closing_force, heating_film;
  double shaft_angle;
};

StatorTransient::StatorTransient(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                                 const TransientSettings &settings)
    : seal(seal), film(film), settings(settings)
{
  // a library caller gets the same refusals as the prm (an end time of -inf once looped forever)
  settings.validate();
  const double C0 = seal.geometry.clearance, ro = seal.geometry.outer_radius;
  const double rate = 1e3; // 1/s: velocities are scaled as displacements per ms
  scale = {{C0, C0 * rate, C0 / ro, C0 / ro, C0 / ro * rate, C0 / ro * rate, C0 / ro, 1e-9, C0 / ro,
            C0 / ro, C0 / ro * rate, C0 / ro * rate, C0, C0 * rate}};
  // the frame in which the forcing is steady: the rotor's runout is fixed in the rotating
  // frame, the stator's initial misalignment in the inertial one
  rotating = settings.frame == "rotating" ||
             (settings.frame == "auto" &&
              !(seal.runout.tilt == 0 && seal.stator.initial_misalignment > 0));
}

FilmState StatorTransient::film_state(const double t, const State &y) const
{
  for (const double v : y)
    if (!std::isfinite(v))
      throw std::runtime_error("the state is not finite: the faces opened without bound or the "
                               "integration diverged");
  if (y[0] > 1e3 * seal.geometry.clearance)
  {
    std::ostringstream m;
    m << "the faces opened without bound (Z = " << y[0] / seal.geometry.clearance << " C0)";
    throw std::runtime_error(m.str());
  }
  const double omega = seal.ramps.speed.value(t);
  FilmState s;
  // y[2..3] is the relative tilt a = a_s - a_r in the integration frame, y[4..5] its rate
  // there. The film needs the inertial rate: in the rotating frame that is a' + omega J a.
  s.tilt_x = y[2];
  s.tilt_y = y[3];
  s.tilt_rate_x = rotating ? y[4] - omega * y[3] : y[4];
  s.tilt_rate_y = rotating ? y[5] + omega * y[2] : y[5];
  // the gap: stator Z less the rotor's axial displacement (0 unless the rotor is axially flexible)
  s.axial_offset = y[0] - y[12];
  s.axial_velocity = y[1] - y[13];
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
    s.coning = quasi_static_coning(seal, film_frame(s, seal.ramps.speed.integral(t)));
  return s;
}

FilmState StatorTransient::film_frame(const FilmState &s, const double shaft_angle) const
{
  if (!seal.geometry.has_angular_pattern())
    return s;
  FilmState f = s.turned(rotating ? shaft_angle : 0.0);
  f.rotor_angle = shaft_angle; // the stator does not spin
  return f;
}

FilmLoads StatorTransient::film_loads(const FilmState &s, const double shaft_angle) const
{
  FilmLoads l = film.loads(film_frame(s, shaft_angle));
  if (rotating && seal.geometry.has_angular_pattern())
  {
    const auto m = turned({{l.moment_x, l.moment_y}}, -shaft_angle);
    const auto c = turned({{l.contact_moment_x, l.contact_moment_y}}, -shaft_angle);
    l.moment_x = m[0];
    l.moment_y = m[1];
    l.contact_moment_x = c[0];
    l.contact_moment_y = c[1];
  }
  return l;
}

FaceContact::Loads StatorTransient::contact_loads(const FilmState &s,
                                                  const double shaft_angle) const
{
  FaceContact::Loads c = seal.contact.loads(film_frame(s, shaft_angle).apply(seal.geometry));
  if (rotating && seal.geometry.has_angular_pattern())
  {
    const auto m = turned({{c.moment_x, c.moment_y}}, -shaft_angle);
    c.moment_x = m[0];
    c.moment_y = m[1];
  }
  return c;
}

StatorTransient::Evaluation StatorTransient::evaluate(const double t, const State &y) const
{
  Evaluation e;
  e.state = film_state(t, y);
  e.shaft_angle = seal.ramps.speed.integral(t);
  const FilmState &s = e.state;
  e.contact = contact_loads(s, e.shaft_angle);
  e.heating_film = seal.thermal.film == ThermalConing::Film::minimum
                       ? std::max(e.contact.min_film, 0.1 * seal.contact.composite_roughness())
                   : seal.thermal.film == ThermalConing::Film::centerline
                       ? seal.geometry.clearance + s.axial_offset
                       : e.contact.heating_film;
  ++evaluations;
  e.film = film_loads(s, e.shaft_angle);
  e.closing_force = seal.closing.value(seal.geometry.inner_radius, seal.geometry.outer_radius,
                                       s.inner_pressure, s.outer_pressure);
  return e;
}

double StatorTransient::contact_margin(const double t, const State &y) const
{
  const FilmState s = film_state(t, y);
  const double closing = seal.closing.value(seal.geometry.inner_radius, seal.geometry.outer_radius,
                                            s.inner_pressure, s.outer_pressure);
  return contact_loads(s, seal.ramps.speed.integral(t)).force -
         settings.contact_threshold * closing;
}

std::array<double, 2> StatorTransient::rotor_tilt(const double shaft_angle) const
{
  return seal.runout.vector(rotating ? 0.0 : shaft_angle);
}

State StatorTransient::rate(const double t, const State &y) const
{
  const Evaluation e = evaluate(t, y);
  const StatorRing &ring = seal.stator;
  const double omega = e.state.rotor_speed, omega_rate = seal.ramps.speed.rate(t);
  // the integration frame turns at w = omega (rotating) or stands still (inertial); a vector u
  // given in it has the inertial rate u' + w J u and the inertial acceleration
  // A = u'' + 2 w J u' + w' J u - w^2 u (all in frame components)
  const double w = rotating ? omega : 0.0, w_rate = rotating ? omega_rate : 0.0;
  auto inertial_rate = [&](const Vector2 &u, const Vector2 &du) {
    return Vector2{{du[0] - w * u[1], du[1] + w * u[0]}};
  };
  auto frame_acceleration = [&](const Vector2 &A, const Vector2 &u, const Vector2 &du)
  {
    return Vector2{{A[0] + 2 * w * du[1] + w_rate * u[1] + w * w * u[0],
                    A[1] - 2 * w * du[0] - w_rate * u[0] + w * w * u[1]}};
  };
  const Vector2 film_moment{
      {e.film.moment_x + e.contact.moment_x, e.film.moment_y + e.contact.moment_y}};

  // the rotor: its tilt r, frame rate dr and frame acceleration ddr
  const Vector2 runout = rotor_tilt(e.shaft_angle);
  Vector2 r, dr, ddr;
  if (!seal.rotor.flexible)
  {
    // turning with the shaft: fixed in the rotating frame, r' = omega J r in the inertial one
    r = runout;
    const Vector2 Jr = quarter_turn(r);
    dr = rotating ? Vector2{} : Vector2{{omega * Jr[0], omega * Jr[1]}};
    ddr = rotating ? Vector2{}
                   : Vector2{{omega_rate * Jr[0] - omega * omega * r[0],
                              omega_rate * Jr[1] - omega * omega * r[1]}};
  }
  else
  {
    // Varney & Green 2017 Eq. 5-6: the film and contact moments act on the rotor with the
    // opposite sign; the shaft holds it at the runout chi_s (turning with it)
    const RingProperties &rotor = seal.rotor.angular;
    r = {{y[8], y[9]}};
    dr = {{y[10], y[11]}};
    const Vector2 v = inertial_rate(r, dr), Jv = quarter_turn(v), Jr = quarter_turn(r);
    const Vector2 u = tilt_vector(1.0, (rotating ? 0.0 : e.shaft_angle) + seal.runout.phase),
                  Ju = quarter_turn(u);
    const double unbalance =
        (rotor.transverse_inertia - rotor.polar_inertia) * rotor.dynamic_misalignment;
    Vector2 A;
    for (unsigned int i = 0; i < 2; ++i)
      A[i] =
          (-film_moment[i] + rotor.polar_inertia * omega * Jv[i] - rotor.support_damping * v[i] -
           rotor.support_stiffness * (r[i] - runout[i]) + omega * rotor.rotating_damping * Jr[i] +
           unbalance * (omega * omega * u[i] - omega_rate * Ju[i])) /
          rotor.transverse_inertia;
    ddr = frame_acceleration(A, r, dr);
  }

  // the stator: tilt a_s = a + r; its support acts on the inertial tilt and rate; the initial
  // misalignment g is fixed in space
  Vector2 g = tilt_vector(ring.initial_misalignment, ring.misalignment_angle);
  if (rotating)
    g = turned(g, -e.shaft_angle);
  const Vector2 a_s{{y[2] + r[0], y[3] + r[1]}}, da_s{{y[4] + dr[0], y[5] + dr[1]}};
  const Vector2 v_s = inertial_rate(a_s, da_s);
  Vector2 A_s;
  for (unsigned int i = 0; i < 2; ++i)
    A_s[i] = (film_moment[i] - ring.angular_stiffness * (a_s[i] - g[i]) -
              ring.angular_damping * v_s[i]) /
             ring.transverse_inertia;
  const Vector2 dda_s = frame_acceleration(A_s, a_s, da_s);

  State d{};
  d[0] = y[1];
  d[1] = (e.film.force_z + e.contact.force - e.closing_force - ring.axial_stiffness * y[0] -
          ring.axial_damping * y[1]) /
         ring.mass;
  d[2] = y[4];
  d[3] = y[5];
  d[4] = dda_s[0] - ddr[0];
  d[5] = dda_s[1] - ddr[1];
  d[6] = (seal.thermal.enabled() && seal.thermal.time_constant > 0)
             ? seal.thermal.rate(y[6], e.heating_film, e.state.rotor_speed)
             : 0.0;
  d[7] = e.film.leakage_inner;
  if (seal.rotor.flexible)
  {
    d[8] = y[10];
    d[9] = y[11];
    d[10] = ddr[0];
    d[11] = ddr[1];
  }
  if (seal.rotor.axially_flexible())
  {
    // Varney & Green 2017 Eq. 7: the film and contact push the rotor away from the stator
    d[12] = y[13];
    d[13] = (-(e.film.force_z + e.contact.force) - seal.rotor.axial_stiffness * y[12] -
             seal.rotor.axial_damping * y[13]) /
            seal.rotor.mass;
  }
  return d;
}

State StatorTransient::initial_state() const
{
  // the stator at rest in space, tilted by the initial relative tilt a(0) (0: resting aligned
  // on the rotor, Green 2002); a_s' = 0 gives a' = -omega J a_r in the inertial frame and
  // a' = -omega J (a + a_r) in the turning one (psi = 0)
  State y{};
  const auto r = seal.runout.vector(0);
  const double omega = seal.ramps.speed.value(0);
  y[0] = settings.initial_axial_offset * seal.geometry.clearance;
  const auto a0 = tilt_vector(settings.initial_tilt, settings.initial_tilt_angle);
  y[2] = a0[0];
  y[3] = a0[1];
  const double bx = rotating ? y[2] + r[0] : r[0], by = rotating ? y[3] + r[1] : r[1];
  y[4] = omega * by;
  y[5] = -omega * bx;
  y[6] = seal.thermal.initial_coning;
  if (seal.rotor.flexible)
  {
    // the rotor starts where the shaft holds it, turning with the shaft
    y[8] = r[0];
    y[9] = r[1];
    y[10] = rotating ? 0.0 : -omega * r[1];
    y[11] = rotating ? 0.0 : omega * r[0];
  }
  if (settings.start_at_rest_equilibrium)
  {
    const Evaluation e = evaluate(0, y);
    y[0] = solve_equilibrium(seal, film, e.state).axial_offset;
  }
  if (seal.rotor.axially_flexible())
  {
    // y[0] so far is the gap's offset: the rotor starts at rest, deflected by the film and
    // contact at that gap, and the stator sits that much further
    const Evaluation e = evaluate(0, y);
    y[12] = -(e.film.force_z + e.contact.force) / seal.rotor.axial_stiffness;
    y[0] += y[12];
  }
  return y;
}

TransientSample StatorTransient::sample(const double t, const State &y) const
{
  const Evaluation e = evaluate(t, y);
  const double psi = rotating ? e.shaft_angle : 0.0;
  // outputs in the inertial frame
  const Vector2 r = seal.rotor.flexible ? Vector2{{y[8], y[9]}} : rotor_tilt(e.shaft_angle);
  const auto stator = turned({{y[2] + r[0], y[3] + r[1]}}, psi);
  const auto film_moment = turned({{e.film.moment_x, e.film.moment_y}}, psi);
  const auto contact_moment = turned({{e.contact.moment_x, e.contact.moment_y}}, psi);
  const auto rotor = turned(r, psi);
  TransientSample s;
  s.time = t;
  s.rotor_speed = e.state.rotor_speed;
  s.rotor_angle = e.shaft_angle;
  s.inner_pressure = e.state.inner_pressure;
  s.outer_pressure = e.state.outer_pressure;
  s.axial_offset = y[0];
  s.axial_velocity = y[1];
  s.stator_tilt_x = stator[0];
  s.stator_tilt_y = stator[1];
  s.rotor_tilt_x = rotor[0];
  s.rotor_tilt_y = rotor[1];
  s.relative_tilt = std::hypot(e.state.tilt_x, e.state.tilt_y);
  s.coning = e.state.coning;
  s.min_film = film_frame(e.state, e.shaft_angle).apply(seal.geometry).minimum().value;
  s.min_film_over_sigma = s.min_film / seal.contact.composite_roughness();
  s.heating_film = e.heating_film;
  s.film_force = e.film.force_z;
  s.contact_force = e.contact.force;
  s.closing_force = e.closing_force;
  s.film_moment_x = film_moment[0];
  s.film_moment_y = film_moment[1];
  s.contact_moment_x = contact_moment[0];
  s.contact_moment_y = contact_moment[1];
  s.leakage_inner = e.film.leakage_inner;
  s.friction_torque = e.film.friction_torque;
  s.leaked_volume = y[7];
  return s;
}
} // namespace sealfe
