// Linear angular dynamics of face seals (FMS, FMR, FMRR, FMS on a flexible rotor) with the film as
// stiffness and damping: eigenvalues, Routh-Hurwitz, stability thresholds and forced response.
#pragma once

#include <sealfe/film/film_coefficients.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/full_matrix.h>

#include <array>
#include <complex>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sealfe
{
class CoefficientTable;

/// Which rings are flexibly mounted (the others are rigid, their tilt prescribed).
///   FMS:  flexible stator ring, rigid rotor ring (Green & Etsion)
///   FMR:  rigid stator ring, flexible rotor ring (Green)
///   FMRR: both flexible, both may spin (Wileman & Green, Wileman & Green)
///   FMS with flexible rotor: both flexible, stator not spinning; the rotor ring is the shaft and
///         seat (Varney & Green, Varney & Green (2017)). The equations are those of FMRR.
enum class SealConfiguration
{
  fms,
  fmr,
  fmrr,
  fms_flexible_rotor
};
std::string to_string(SealConfiguration c);
/// "FMS", "FMR", "FMRR", "FMS with flexible rotor"; throws std::runtime_error otherwise.
SealConfiguration configuration_from_string(const std::string &name);

/// Angular properties of a ring and its support. The support moment on a ring spinning at omega
/// with tilt vector t = (tilt_x, tilt_y) is
///   -support_stiffness t - support_damping t_dot - omega rotating_damping J t,  J = [[0,1],[-1,0]]
/// so rotating_damping is the part of the support damping that turns with the ring: it adds the
/// circulatory stiffness omega d (Wileman & Green: D_n = ... + omega_n d_sn, i.e. rotating_damping
/// = support_damping; Varney & Green (2017)'s rotor: support_damping = D_r, rotating_damping =
/// D_omega_r).
struct RingProperties
{
  double transverse_inertia = 0; // I_t, kg m^2
  double polar_inertia = 0;      // I_p (J), kg m^2
  double support_stiffness = 0;  // N m/rad
  double support_damping = 0;    // N m s/rad
  double rotating_damping = 0;   // N m s/rad
  /// Static misalignment of the support (rad): the tilt the support holds the ring at, about the
  /// x axis at t = 0 and turning with the ring (fixed in space if the ring does not spin). For a
  /// rigid ring it is the ring's own tilt (run-out). Varney & Green (2017): gamma_si (stator),
  /// chi_s (rotor).
  double support_misalignment = 0;
  /// Dynamic misalignment chi (rad): angle between the ring's principal axes and its spin axis;
  /// forces (I_t - I_p) chi omega^2 (Varney & Green (2017) Appendix A). Only for a flexible
  /// spinning ring.
  double dynamic_misalignment = 0;
};

/// The film coefficients at given ring speeds: any level (closed form, table, finite element)
/// can be plugged in. Only the tilt block of K and D is used (axial-angular decoupling).
using FilmModel = std::function<FilmCoefficients(double rotor_speed, double stator_speed)>;

/// A producer of film coefficients for a whole seal and operating point (the speeds are those of
/// `conditions`). The finite-element level (CoefficientSolver, in the FE library that this light
/// module cannot link) reaches the dynamics through this hook: the application supplies it.
using FilmCoefficientProvider = std::function<FilmCoefficients(
    const FilmThickness &film, const OperatingConditions &conditions)>;

/// M q_ddot + C q_dot + K q = f for the tilt degrees of freedom of the flexible rings, ordered
/// (stator tilt_x, stator tilt_y, rotor tilt_x, rotor tilt_y) with rigid rings left out. C holds
/// support, film and gyroscopic terms; K support, film and circulatory terms.
struct SecondOrderSystem
{
  dealii::FullMatrix<double> mass, damping, stiffness;
};

/// Tilt (or relative tilt) of a ring in complex notation g = tilt_x + i tilt_y, as a sum of
/// harmonics g(t) = sum forward e^{i W t} + backward e^{-i W t} (W = frequency >= 0; a static
/// part has W = 0 and backward = 0). forward alone is a forward circular whirl.
struct HarmonicTilt
{
  double frequency = 0;
  std::complex<double> forward = 0, backward = 0;
};

/// Steady-state response to the misalignments at one pair of ring speeds.
struct ForcedResponse
{
  double rotor_speed = 0, stator_speed = 0;
  std::vector<HarmonicTilt> stator_tilt, rotor_tilt, relative_tilt;
  /// Largest magnitude over time (sum of |forward| + |backward| of all harmonics: reached when
  /// their frequencies are incommensurate, exact for one harmonic).
  static double max_magnitude(const std::vector<HarmonicTilt> &h);
  /// The harmonic at frequency W (zero if there is none).
  static HarmonicTilt at_frequency(const std::vector<HarmonicTilt> &h, double W);
};

/// Angular dynamics of one or two rings coupled by the film (Wileman & Green Eq. 2, Varney & Green
/// (2017) Eq. 24-27). The film coefficients describe the stator ring's face relative to the rotor
/// ring's face; they are the same the other way round (film_coefficients.h), so "ring 2" of Wileman
/// & Green (speed omega2, swept in Table 1) is the stator ring here and "ring 1" the rotor ring.
class AngularSealDynamics
{
public:
  AngularSealDynamics(SealConfiguration configuration, const RingProperties &rotor_ring,
                      const RingProperties &stator_ring, FilmModel film);

  SealConfiguration configuration() const { return config; }
  bool rotor_is_flexible() const;
  bool stator_is_flexible() const;
  unsigned int n_dofs() const;
  const RingProperties &rotor_ring() const { return rotor; }
  const RingProperties &stator_ring() const { return stator; }
  FilmCoefficients film_coefficients(double rotor_speed, double stator_speed) const
  {
    return film(rotor_speed, stator_speed);
  }

  /// Throws std::runtime_error (one line, naming the ring and property) for impossible rings.
  void validate() const;

  SecondOrderSystem matrices(double rotor_speed, double stator_speed) const;

  /// Eigenvalues lambda of the free motion q = A e^{lambda t} (LAPACK on the first-order form),
  /// sorted by decreasing real part. Im(lambda) is a whirl frequency (> 0 forward), the damping
  /// ratio is -Re(lambda)/|lambda|.
  std::vector<std::complex<double>> eigenvalues(double rotor_speed, double stator_speed) const;
  /// max Re(lambda) (1/s): the growth rate of the least stable mode.
  double growth_rate(double rotor_speed, double stator_speed) const;
  /// max Re(lambda) < -1e-12 max |lambda| (a marginal mode counts as unstable).
  bool is_stable(double rotor_speed, double stator_speed) const;

  /// Routh-Hurwitz route (Wileman & Green): the real characteristic polynomial sum a_k lambda^k,
  /// coefficients a_0..a_n (n = 8 with two flexible rings, 4 with one), obtained by multiplying
  /// the complex characteristic equation (Eq. 3) by its conjugate. For two flexible rings the
  /// a_k are those of Wileman & Green Appendix B. Needs an isotropic tilt block without
  /// cross-coupled damping (else std::runtime_error).
  std::vector<double> hurwitz_polynomial(double rotor_speed, double stator_speed) const;
  /// The same coefficients by multiplying the complex polynomial det(Eq. 3) by its conjugate
  /// numerically (an independent route to check Appendix B).
  std::vector<double> hurwitz_polynomial_by_product(double rotor_speed, double stator_speed) const;
  /// Leading principal minors Delta_1..Delta_n of the Hurwitz matrix of a polynomial given low to
  /// high (after scaling lambda so that the coefficients are balanced: signs are unchanged).
  static std::vector<double> hurwitz_determinants(const std::vector<double> &coefficients);
  /// a_n > 0 and all Hurwitz determinants > 0.
  bool is_stable_routh_hurwitz(double rotor_speed, double stator_speed) const;

  enum class SweptRing
  {
    rotor,
    stator
  };
  enum class Criterion
  {
    eigenvalues,
    routh_hurwitz
  };
  struct SpeedInterval
  {
    double low, high;
    bool low_at_search_limit, high_at_search_limit;
  };
  /// The intervals of the swept ring's speed in [from, to] over which the seal is stable, the
  /// other ring at fixed_speed: stability is evaluated on n_grid equally spaced speeds and every
  /// change of verdict is refined by bisection to |dw| < 1e-10 max(1, |w|). Intervals narrower
  /// than the grid spacing can be missed.
  std::vector<SpeedInterval> stable_speed_intervals(SweptRing swept, double fixed_speed,
                                                    double from, double to, unsigned int n_grid,
                                                    Criterion criterion) const;

  /// Closed-form stability thresholds without support damping (Wileman & Green Eq. 17, and its
  /// one-ring forms -I psi^2 + J omega psi + k11 + k_s = 0 for FMS/FMR): the swept speeds at which
  /// the seal, with its support damping removed, has a neutral mode precessing at psi = (omega1 +
  /// omega2)/2. Real roots only, ascending. Needs a film whose cross-coupled stiffness is (omega1 +
  /// omega2)/2 times its damping (level 0); the film coefficients are taken at the speeds
  /// (fixed_speed, fixed_speed) — k11 and d11 do not depend on speed there.
  std::vector<double> undamped_threshold_speeds(SweptRing swept, double fixed_speed) const;

  /// Steady-state response to the rings' misalignments (support_misalignment,
  /// dynamic_misalignment) by a direct complex solve of the real equations, one solve per
  /// forcing frequency (0, the rotor speed, the stator speed).
  ForcedResponse forced_response(double rotor_speed, double stator_speed) const;

  /// Varney & Green (Varney & Green (2017)) Appendix B, Eq. B3-B5, for the FMS with flexible rotor:
  /// the synchronous amplitudes (Gamma_xi_s, Gamma_eta_s, Gamma_xi_r, Gamma_eta_r) of the response
  /// gamma = Re(Gamma e^{i omega_r t}) to the rotor's misalignments, with the paper's typos fixed
  /// (S1: -D_omega_r in the K_f term; Delta carries the opposite overall sign). Needs the
  /// level-0 film relation c = omega_r/2 D_f.
  std::array<std::complex<double>, 4> varney_green_synchronous_response(double rotor_speed) const;

  /// Time integration (SUNDIALS ARKode, implicit) of the same linear equations with the
  /// misalignment forcing, from rest at t = 0 to t_end. Returns the tilt vector (stator x, y,
  /// rotor x, y; a rigid ring's prescribed tilt included) at the requested output times.
  struct TimeSample
  {
    double time;
    std::array<double, 4> tilts;
  };
  std::vector<TimeSample> integrate(double rotor_speed, double stator_speed, double t_end,
                                    const std::vector<double> &output_times,
                                    double relative_tolerance = 1e-9,
                                    double absolute_tolerance = 1e-14) const;

private:
  /// Complex forcing vectors per frequency, and the prescribed tilts of rigid rings.
  struct Harmonic
  {
    double frequency;
    std::vector<std::complex<double>> force;          // per dof: f = Re(force e^{i W t})
    std::array<std::complex<double>, 4> prescribed{}; // rigid rings' tilts (x, y) per ring
  };
  std::vector<Harmonic> forcing(double rotor_speed, double stator_speed) const;
  std::vector<unsigned int> dof_slots() const; // which of the 4 slots are dofs

  SealConfiguration config;
  RingProperties rotor, stator;
  FilmModel film;
};

/// Film coefficients along one line of ring speeds — one ring's speed swept over [from, to], the
/// other ring held at fixed_speed — interpolated between n_nodes >= 2 equally spaced evaluations
/// of an expensive model (level 2): Lagrange interpolation on the 4 nodes around the speed
/// (cubic; linear with 2 nodes, quadratic with 3), as the coefficient table does per axis.
///
/// In full film the interpolation is exact: the Reynolds equation is linear in p, the ring speeds
/// enter only through the Couette source (omega1 + omega2)/2 dh/dtheta, so K is affine in the
/// mean speed (the hydrostatic part constant, the hydrodynamic part proportional) and D does not
/// depend on it; any degree >= 1 reproduces that. With cavitation in the linearised state the
/// dependence is not affine and the interpolation error is reported by check().
///
/// A node is evaluated when it is first needed and kept; copies share the nodes. Speeds off the
/// line (the fixed ring at another speed) or outside [from, to] go to the exact model.
class SpeedInterpolatedFilm
{
public:
  SpeedInterpolatedFilm(FilmModel exact, AngularSealDynamics::SweptRing swept, double fixed_speed,
                        double from, double to, unsigned int n_nodes);

  FilmCoefficients operator()(double rotor_speed, double stator_speed) const;

  AngularSealDynamics::SweptRing swept() const { return state->swept; }
  double fixed_speed() const { return state->fixed; }
  /// The swept speeds of the nodes (rad/s).
  std::vector<double> node_speeds() const;
  /// Exact evaluations made so far (nodes and off-line speeds).
  unsigned int n_exact_evaluations() const { return state->evaluations; }

  /// Interpolation error at the midpoint of the node interval that contains `swept_speed`
  /// (clamped to [from, to]): one exact evaluation there, compared entry-wise as by
  /// CoefficientTable::compare (max |K~ - K| / max |K| of the dimensionally uniform matrices with
  /// outer radius ro; the same for D).
  struct Check
  {
    double speed = 0;     // swept speed of the check (rad/s)
    double stiffness = 0; // relative error of K
    double damping = 0;   // relative error of D
  };
  Check check(double swept_speed, double outer_radius) const;
  /// check() at each of the speeds (duplicate intervals checked once) as summary JSON:
  /// {"checks": [{"swept_speed", "stiffness_error", "damping_error"}, ...],
  ///  "max_stiffness_error", "max_damping_error", "definition"}.
  nlohmann::json check_report(const std::vector<double> &swept_speeds, double outer_radius) const;

  /// {"method": ..., "swept_speed": "rotor"|"stator", "fixed_speed", "node_speeds", ...}
  nlohmann::json to_json() const;

private:
  bool on_line(double rotor_speed, double stator_speed, double &swept_speed) const;
  FilmCoefficients node(unsigned int i) const;
  FilmCoefficients interpolate(double swept_speed) const;

  struct State
  {
    FilmModel exact;
    AngularSealDynamics::SweptRing swept;
    double fixed, from, to;
    unsigned int n;
    std::vector<std::unique_ptr<FilmCoefficients>> nodes;
    std::map<std::pair<double, double>, FilmCoefficients> off_line;
    unsigned int evaluations = 0;
  };
  std::shared_ptr<State> state;
};

/// The film a sweep of one ring's speed uses (SealDynamicsInput::sweep_film).
struct SweepFilm
{
  FilmModel model;
  /// Level 2 with Film speed nodes >= 2: the interpolation behind `model` (else null).
  std::shared_ptr<const SpeedInterpolatedFilm> interpolation;
  /// How the coefficients depend on the swept speed, for the summary ("film_speed_dependence").
  nlohmann::json description;
};

/// Everything a dynamics run reads from a parameter file: subsection "Seal dynamics" (declared
/// here) plus "Geometry" and "Operating conditions" (declared by the application). Kept as plain
/// data so that a parameter study can change one entry and build() again.
struct SealDynamicsInput
{
  SealConfiguration configuration = SealConfiguration::fms_flexible_rotor;
  RingProperties rotor, stator;
  FilmThickness geometry;
  OperatingConditions operating;
  std::string film_model = "closed form"; // "closed form" | "table" | "finite element"
  /// Level 1: the CSV written by `sealfe table` (path as given, relative to the working
  /// directory) and its interpolation ("cubic" | "linear").
  std::string table_file;
  std::string table_interpolation = "cubic";
  /// Level 2: number of swept speeds at which the FE coefficients are computed for a sweep
  /// (SpeedInterpolatedFilm); 0 = an FE computation at every speed the sweep asks for.
  unsigned int film_speed_nodes = 9;
  /// Level 2: the FE producer, supplied by the application (not read from the prm).
  FilmCoefficientProvider finite_element;

  /// Declares subsection "Seal dynamics" with its subsections "Rotor ring" and "Stator ring".
  /// Defaults: the FMS seal on a flexible rotor of Varney & Green (Varney & Green (2017) Tables
  /// 1-2).
  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Reads "Seal dynamics", "Geometry" and "Operating conditions".
  void parse_parameters(dealii::ParameterHandler &prm);
  /// One-line std::runtime_error naming the parameter for impossible input, for configurations
  /// whose speeds do not fit (FMS with flexible rotor: the stator does not spin), for a table
  /// that cannot be read or is not this seal's, and for level 2 without a producer. Makes no FE
  /// solve.
  void validate() const;
  int film_model_level() const;
  /// The film model of the chosen level at any pair of ring speeds: level 0
  /// GreenEtsionCoefficients, level 1 CoefficientTable lookups (the table read once and shared
  /// by copies of this input), level 2 the finite_element producer, one computation per speed
  /// pair (kept for repeated pairs).
  FilmModel film() const;
  /// The film for a sweep of one ring's speed over [from, to] (the other at fixed_speed): film()
  /// for levels 0 and 1 (level 1: both ends of the sweep are checked to lie in the table, with a
  /// one-line error otherwise); level 2 with film_speed_nodes >= 2 a SpeedInterpolatedFilm over
  /// film(), else film() itself.
  SweepFilm sweep_film(AngularSealDynamics::SweptRing swept, double fixed_speed, double from,
                       double to) const;
  AngularSealDynamics build() const;
  AngularSealDynamics build(FilmModel film_model) const;
  /// Relative tilt at which the faces touch: min(C0/ri, (C0 + beta (ro - ri))/ro), i.e. C0/ri
  /// for a seal coned open outward (Varney & Green (2017): gamma*_cr = C0/ri).
  double contact_tilt() const;
  /// Set a named scalar (a "Second parameter" of the stability sweep); see the list in
  /// parameter_names(). "Clearance" keeps beta* ro/C0 if hold_normalized_coning.
  void set(const std::string &name, double value, bool hold_normalized_coning);
  static std::string parameter_names();

private:
  /// The level-1 table, read once (by film() or validate()) and shared by copies.
  std::shared_ptr<const CoefficientTable> table() const;
  mutable std::shared_ptr<const CoefficientTable> table_cache;
  mutable std::string table_cache_key;
};

} // namespace sealfe
