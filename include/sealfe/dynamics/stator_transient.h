// StatorTransient: the flexibly mounted stator of Green 2002 Eq. 26 in time — axial Z, stator
// tilt (Cartesian components), coning beta — under ramps, rotor runout, closing force, supports,
// film (any FilmForceModel) and asperity contact, integrated by SUNDIALS IDA (BDF,
// adaptive).
#pragma once

#include <sealfe/dynamics/closing_force.h>
#include <sealfe/dynamics/face_contact.h>
#include <sealfe/dynamics/operating_ramps.h>
#include <sealfe/dynamics/ring_properties.h>
#include <sealfe/dynamics/thermal_coning.h>
#include <sealfe/film/film_force_model.h>

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sealfe
{
/// The stator ring and its flexible support (subsection "Stator ring"), Green 2002 Eq. 21.
/// Table 1 gives m, K_sz, D_sz; I = m r_g^2 / 2 with r_g = ro; the angular support is not in the
/// paper (defaults assumed, doc/transient.md).
struct StatorRing
{
  double mass = 1;                       ///< kg
  double transverse_inertia = 8.3232e-4; ///< kg m^2 (m ro^2 / 2)
  double axial_stiffness = 5e5;          ///< N/m
  double axial_damping = 300;            ///< N s/m
  double angular_stiffness = 50;         ///< N m/rad
  double angular_damping = 0.005;        ///< N m s/rad
  double initial_misalignment = 0;       ///< gamma_si (rad), fixed in space
  double misalignment_angle = 0;         ///< its direction (rad)

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  void validate() const;
};

/// Rotor runout (subsection "Rotor runout"): the rotor face's tilt gamma_r, whirling with the
/// shaft angle psi_r(t) = Int omega dt (Green 2002 Eq. 19).
struct RotorRunout
{
  double tilt = 1e-3; ///< rad
  double phase = 0;   ///< rad, direction of the tilt at t = 0
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Tilt vector (tilt_x, tilt_y) of the rotor face (film_thickness.h conventions) at angle psi.
  std::array<double, 2> vector(double shaft_angle) const;
};

/// The rotor ring (subsection "Rotor ring"): rigid, its tilt the runout of "Rotor runout" turning
/// with the shaft (Green 2002), or flexible, Varney & Green 2017 Eq. 5-6 — a lumped angular rotor
/// on the shaft's stiffness K_r, with external damping D_r, rotating damping D_omega_r, gyroscopic
/// coupling I_pr omega, dynamic misalignment chi, and the runout tilt as its static misalignment
/// chi_s (the tilt the shaft holds it at, turning with it). Axially the rotor is rigid unless
/// its axial stiffness is set (Eq. 7).
struct RotorRing
{
  bool flexible = false;
  /// I_tr, I_pr, K_r (support stiffness), D_r (support damping), D_omega_r (rotating damping)
  /// and chi (dynamic misalignment) as in the linear model of `sealfe response`; Varney & Green
  /// 2017 Table 2. Its support_misalignment is not used: the shaft holds the rotor at the
  /// runout tilt (RotorRunout), which is chi_s.
  RingProperties angular{0.2, 0.1, 5e5, 20, 1, 0, 0}; // I_tr, I_pr, K_r, D_r, D_wr, -, chi
  /// Axial (Eq. 7, with a flexible rotor only): K_zr > 0 makes the rotor's axial motion a state,
  /// m_r u_zr'' + D_zr u_zr' + K_zr u_zr = -(F_f + F_c); 0 keeps it axially rigid.
  double axial_stiffness = 0; ///< K_zr (N/m)
  double axial_damping = 0;   ///< D_zr (N s/m)
  double mass = 1;            ///< m_r (kg)
  bool axially_flexible() const { return flexible && axial_stiffness > 0; }

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  void validate() const;
};

/// Subsection "Transient": end time, tolerances, output interval, initial state.
struct TransientSettings
{
  double end_time = 9;
  double relative_tolerance = 1e-5;
  double absolute_tolerance = 1e-5; ///< on the scaled state (Z/C0, tilt ro/C0, ...)
  double output_interval = 0.01;
  double initial_axial_offset = -0.65; ///< Z(0)/C0
  double initial_tilt = 0;             ///< relative tilt |a(0)| (rad), stator at rest in space
  double initial_tilt_angle = 0;       ///< its direction (rad)
  bool start_at_rest_equilibrium = false;
  double minimum_step = 1e-12;
  unsigned long maximum_steps = 2000000;
  double contact_threshold = 0.01; ///< in contact: contact force > this fraction of F_cls
  unsigned int order = 2;          ///< largest order of IDA's BDF
  std::string frame = "auto";      ///< auto | inertial | rotating (stator-tilt state)

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  void validate() const;
};

/// One output row of the transient.
struct TransientSample
{
  double time, rotor_speed, inner_pressure, outer_pressure;
  double rotor_angle; ///< rad, Int omega dt from t = 0: where rotor-borne features stand
  double axial_offset, axial_velocity;
  double stator_tilt_x, stator_tilt_y, rotor_tilt_x, rotor_tilt_y;
  double relative_tilt, coning, min_film, min_film_over_sigma, heating_film;
  double film_force, contact_force, closing_force, film_moment_x, film_moment_y;
  double contact_moment_x, contact_moment_y, leakage_inner, friction_torque, leaked_volume;
  double stator_tilt() const;
  double stator_precession() const;
};

/// The seal case shared by `sealfe equilibrium` and `sealfe transient`.
struct FlexibleStatorSeal
{
  FilmThickness geometry;         ///< ri, ro, C0 (and Coning when thermal coning is off)
  OperatingConditions conditions; ///< viscosity (and the point of `sealfe equilibrium`)
  ClosingForce closing;
  StatorRing stator;
  RotorRunout runout;
  RotorRing rotor;
  ThermalConing thermal;
  OperatingRamps ramps;
  FaceContact contact;

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  void validate() const;
  double face_area() const;
};

/// Thrown by StatorTransient::steady_state when no steady state can exist for the forcing (runout
/// and a stator misalignment together, or a frame in which the forcing is not steady), as
/// opposed to a Newton iteration that failed.
struct NoSteadyState : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// The state of the transient (physical units): Z, Z', the relative tilt a = a_s - a_r and its
/// rate, beta, the leaked volume V, the rotor tilt a_r and its rate (flexible rotor only, else 0),
/// the rotor's axial displacement u_zr toward the stator and its rate (axially flexible rotor
/// only); tilts and rates in the integration frame. The film gap is C0 + Z - u_zr + ...
using TransientState = std::array<double, 14>;

/// The state of Eq. 26 in Cartesian form (doc/transient.md): Z, Z', the relative tilt
/// a = a_s - a_r and its rate in the integration frame (turning with the shaft or fixed in
/// space, TransientSettings::frame), beta, the leaked volume V, and with a flexible rotor its
/// tilt a_r and rate (Varney & Green 2017 Eq. 5-6):
///   m Z''      = F_f + F_c - F_cls(t) - K_sz Z - D_sz Z'
///   I a_s''    = M_f + M_c - K_s (a_s - a_si) - D_s a_s'      (a_s = stator tilt vector)
///   tau beta'  = beta_ref (h_ref/h)(omega/omega_ref)^2 - beta
///   V'         = Q_inner
///   I_tr a_r'' = -M_f - M_c - I_pr omega J' a_r' - D_r a_r' - K_r (a_r - chi_s) - omega D_wr J'
///   a_r
///                + (I_tr - I_pr) chi (omega^2 u - omega' J u)        (flexible rotor; J' = -J)
/// with the film and contact evaluated at the relative tilt a = a_s - a_r(psi_r(t)), integrated
/// by SUNDIALS IDA (variable-order BDF, dense Newton with a difference Jacobian).
class StatorTransient
{
public:
  StatorTransient(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                  const TransientSettings &settings);

  /// A crossing of the contact threshold (contact force = Contact threshold x F_cls), located by
  /// IDA's root finding between steps (to the integrator's time resolution, not the output rows).
  struct ContactEvent
  {
    double time, rotor_speed;
    bool lift_off; ///< true: the contact force falls below the threshold; false: touch-down
  };

  struct Result
  {
    std::vector<TransientSample> samples;
    std::vector<ContactEvent> contact_events;
    bool complete = false;
    std::string stop_reason;
    unsigned long film_evaluations = 0;
    unsigned long steps = 0;
    unsigned long error_test_failures = 0, convergence_failures = 0, jacobian_setups = 0;
  };
  /// Integrates from the initial state to the end time. A failure of the integrator (step size
  /// collapse, film out of range), or a stop asked for by a signal (interrupt::requested(),
  /// checked before each output row), stops the run: the samples so far are kept, complete = false.
  Result run() const;

  /// Called with each output time right after its row is sampled (the film has just been
  /// evaluated at that state: a finite-element film holds its fields), e.g. to write them.
  std::function<void(double time)> after_output;

  /// The full sample (loads included) for the physical state y at time t.
  TransientSample sample(double t, const TransientState &y) const;
  /// The steady state of these equations at time t's conditions, held constant: every rate zero
  /// in the integration frame — the frame turning with the shaft when runout (or a flexible
  /// rotor's dynamic misalignment) forces the seal, the inertial one when only the stator's
  /// initial misalignment does. Unknowns: Z, the relative tilt, beta (first-order lag), the
  /// flexible rotor's tilt; Newton with a central-difference Jacobian from `guess` (its rates
  /// are ignored). Throws std::runtime_error (one line) when both forcings are present (no
  /// steady state exists: NoSteadyState) or Newton does not converge. `iterations` gets
  /// Newton's count.
  TransientState steady_state(double t, const TransientState &guess,
                              unsigned int *iterations = nullptr) const;
  /// The film's state at (t, y): tilts in the integration frame with their inertial rates, the
  /// coning in use, the ramps' speeds and pressures (no film evaluation). Throws
  /// std::runtime_error for a non-finite state or faces opened beyond 1000 C0.
  FilmState film_state(double t, const TransientState &y) const;
  /// Contact force minus Contact threshold x F_cls at the state (N): > 0 in contact. Contact
  /// only (no film evaluation).
  double contact_margin(double t, const TransientState &y) const;
  /// The initial state (TransientState), a the relative tilt; a flexible rotor at its runout.
  TransientState initial_state() const;

private:
  struct Evaluation;
  Evaluation evaluate(double t, const TransientState &y) const;
  TransientState rate(double t, const TransientState &y) const;
  /// The state `s` (integration frame) as the film and contact models take it. A film with an
  /// angular pattern (waviness, a film formula, surface features) is written in the stator
  /// frame, with rotor-borne features turned by the shaft angle: `s` turned into the stator
  /// frame, rotor_angle = shaft_angle. An axisymmetric film gets `s` itself (its loads turn with
  /// its state, and the turning frame keeps a steady whirl steady, doc/transient.md).
  FilmState film_frame(const FilmState &s, double shaft_angle) const;
  /// The film's and the contact's loads at `s` (integration frame), moments in the integration
  /// frame.
  FilmLoads film_loads(const FilmState &s, double shaft_angle) const;
  FaceContact::Loads contact_loads(const FilmState &s, double shaft_angle) const;
  /// The rotor's tilt vector in the integration frame at the shaft angle psi.
  std::array<double, 2> rotor_tilt(double shaft_angle) const;

  const FlexibleStatorSeal &seal;
  const FilmForceModel &film;
  TransientSettings settings;
  TransientState scale;
  bool rotating; ///< stator-tilt state (y[2..5]) in the frame turning with the shaft
  mutable unsigned long evaluations = 0;
};
} // namespace sealfe
