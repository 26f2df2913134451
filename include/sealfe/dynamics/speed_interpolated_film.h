// SpeedInterpolatedFilm: expensive (level-2) film coefficients along a swept ring speed,
// computed at a few nodes and interpolated in between; SweepFilm: the film a speed sweep uses.
#pragma once

#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/shared_cache.h>

#include <nlohmann/json.hpp>

#include <memory>
#include <utility>
#include <vector>

namespace sealfe
{
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
    SharedCache<std::pair<double, double>, FilmCoefficients> off_line;
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

} // namespace sealfe
