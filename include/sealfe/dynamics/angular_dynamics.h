// Linear angular dynamics of face seals (FMS, FMR, FMRR, FMS on a flexible rotor) with the film as
// stiffness and damping. The class is implemented by idea: matrices and eigenvalues in
// angular_dynamics.cc, the Routh-Hurwitz route in routh_hurwitz.cc, stable speed ranges and
// thresholds in stability_thresholds.cc, the forced response (and Varney & Green 2017 Appendix B)
// in forced_response.cc, time integration in linear_time_integration.cc.
#pragma once

#include <sealfe/dynamics/forced_response.h>
#include <sealfe/dynamics/ring_properties.h>
#include <sealfe/film/film_coefficients.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <complex>
#include <functional>
#include <vector>

namespace sealfe
{
/// The film coefficients at given ring speeds. film_levels.h builds one from the FilmForceModel
/// of the chosen level (closed form, table, finite element); a test may plug in any function.
/// Only the tilt block of K and D is used (axial-angular decoupling).
using FilmModel = std::function<FilmCoefficients(double rotor_speed, double stator_speed)>;

/// The rotationally invariant parts of a film's tilt block (film_coefficients.h): direct
/// stiffness k, cross-coupled stiffness c, direct damping d, cross-coupled damping e.
struct TiltFilm
{
  double k, c, d, e;
  static TiltFilm of(const FilmCoefficients &f)
  {
    return {f.tilt_direct_stiffness(), f.tilt_cross_stiffness(), f.tilt_direct_damping(),
            f.tilt_cross_damping()};
  }
};

/// M q_ddot + C q_dot + K q = f for the tilt degrees of freedom of the flexible rings, ordered
/// (stator tilt_x, stator tilt_y, rotor tilt_x, rotor tilt_y) with rigid rings left out. C holds
/// support, film and gyroscopic terms; K support, film and circulatory terms.
struct SecondOrderSystem
{
  dealii::FullMatrix<double> mass, damping, stiffness;
  /// The first-order form y = (q, q_dot), y_dot = A y + (0, M^-1 f): A = [[0, 1], [-M^-1 K,
  /// -M^-1 C]] (M is diagonal: each dof is one ring's tilt component).
  dealii::FullMatrix<double> first_order_matrix() const;
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
  /// sorted by decreasing real part. The real equations give each whirling mode as a conjugate
  /// pair +-Im(lambda); its direction (forward or backward) is in the eigenvector
  /// (whirl_modes.h). The damping ratio is -Re(lambda)/|lambda|.
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
  /// (routh_hurwitz.h hurwitz_determinants)
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

} // namespace sealfe
