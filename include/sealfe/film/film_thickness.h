// FilmThickness: the gap h(r, theta) between the seal faces on the annular dam ri <= r <= ro,
// and its rate dh/dt from prescribed squeeze motion (doc/reynolds.md, conventions).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <memory>
#include <string>

namespace sealfe
{
class FilmExpression;  // film/film_expression.h
class SurfaceFeatures; // film/surface_features.h

/// Film thickness of a coned, tilted, wavy face pair. Reads subsection "Geometry" (shape) and
/// "Squeeze motion" (velocities of the flexible ring, for the squeeze term and damping).
///
///   h(r, theta) = C0 + z + beta (r - ri) + gamma r cos(theta - psi)
///                 + A_w cos(n_w (theta - theta_w))
///
/// The flexible ring's degrees of freedom are q = (z, tilt_x, tilt_y): its face moves axially by
/// w = z + tilt_x * y - tilt_y * x, so gamma cos(psi) = -tilt_y and gamma sin(psi) = tilt_x.
/// Optional: a user formula h_e(r, theta, x, y, t) (`Film expression`) and surface features
/// (pads, grooves, dimples: recesses of the face that carries them) are added to h; without them
/// (the default) nothing else is evaluated.
class FilmThickness
{
public:
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// Throws std::runtime_error naming the problem if the geometry is impossible (ri >= ro,
  /// C0 <= 0, ...) or the film touches down (min h <= 0, with where and by how much) unless
  /// `allow_touch_down` (rough faces with an asperity contact model carry it).
  void validate(const bool allow_touch_down = false) const;

  double value(const double r, const double theta) const
  {
    const double h = analytic_value(r, theta);
    return has_added_terms() ? h + added_value(r, theta) : h;
  }
  /// dh/dr (pointwise: surface features are piecewise constant, their steps are not in it)
  double d_dr(const double r, const double theta) const
  {
    const double d = coning + tilt * std::cos(theta - tilt_angle);
    return expression ? d + expression_d_dr(r, theta) : d;
  }
  /// dh/dtheta (pointwise, as d_dr)
  double d_dtheta(const double r, const double theta) const { return fixed_d_dtheta(r, theta); }
  /// dh/dt from the prescribed velocities (z_dot, tilt_x_dot, tilt_y_dot) of the flexible ring
  /// and the time derivative of the film expression.
  double d_dt(const double r, const double theta) const
  {
    // terms with a zero factor are skipped (the same value, without their sines and cosines:
    // the assembly evaluates the film at every quadrature point)
    const double d = tilt_rate_x == 0 && tilt_rate_y == 0
                         ? axial_velocity
                         : axial_velocity + tilt_rate_x * r * std::sin(theta) -
                               tilt_rate_y * r * std::cos(theta);
    return expression ? d + expression_d_dt(r, theta) : d;
  }

  /// The film without expression and features (coning, tilt, waviness).
  double analytic_value(const double r, const double theta) const
  {
    const double h = clearance + axial_offset + coning * (r - inner_radius) +
                     tilt * r * std::cos(theta - tilt_angle);
    return wave_amplitude == 0 ? h
                               : h + wave_amplitude * std::cos(wave_number * (theta - wave_phase));
  }
  /// dh/dtheta of the part of the film fixed in the frame of the solve (analytic + expression),
  /// the part that moves relative to the features' frame (reynolds_solver.cc, local_film).
  double fixed_d_dtheta(const double r, const double theta) const
  {
    double d = -tilt * r * std::sin(theta - tilt_angle);
    if (wave_amplitude != 0)
      d -= wave_amplitude * wave_number * std::sin(wave_number * (theta - wave_phase));
    return expression ? d + expression_d_dtheta(r, theta) : d;
  }
  bool has_added_terms() const { return expression || features; }
  /// Whether the film is the coned, tilted one alone (no waviness, expression or features): then
  /// the coned_tilted_* forms below give value(), d_dtheta() and d_dt().
  bool is_coned_tilted() const { return wave_amplitude == 0 && !has_added_terms(); }
  /// h of the coned, tilted film at the point (x, y), |(x, y)| = r, given cos and sin of the
  /// tilt angle: r cos(theta - psi) = x cos psi + y sin psi, so no sine or cosine per point (the
  /// assembly evaluates the film at every quadrature point). Equal to value() to round-off.
  double coned_tilted_value(const double x, const double y, const double r, const double cos_tilt,
                            const double sin_tilt) const
  {
    return clearance + axial_offset + coning * (r - inner_radius) +
           tilt * (x * cos_tilt + y * sin_tilt);
  }
  /// dh/dtheta of the same: -gamma r sin(theta - psi) = -gamma (y cos psi - x sin psi).
  double coned_tilted_d_dtheta(const double x, const double y, const double cos_tilt,
                               const double sin_tilt) const
  {
    return -tilt * (y * cos_tilt - x * sin_tilt);
  }
  /// dh/dt of the same: r sin(theta) = y, r cos(theta) = x in d_dt().
  double coned_tilted_d_dt(const double x, const double y) const
  {
    return tilt_rate_x == 0 && tilt_rate_y == 0
               ? axial_velocity
               : axial_velocity + tilt_rate_x * y - tilt_rate_y * x;
  }
  /// Expression + feature depths at (r, theta) (0 without them).
  double added_value(const double r, const double theta) const;
  double expression_d_dr(const double r, const double theta) const;
  double expression_d_dtheta(const double r, const double theta) const;
  double expression_d_dt(const double r, const double theta) const;

  /// Angular speed (rad/s) of the face that carries the surface features: the film equation is
  /// solved in that ring's frame, where the features stand still (0 without features: the frame
  /// of the solve is the non-rotating one, as without features).
  double feature_frame_speed(const double rotor_speed, const double stator_speed) const;
  /// Whether the surface features sit on the rotor face (they turn with it relative to the
  /// stator, FilmState::rotor_angle).
  bool features_on_rotor() const;
  /// Whether anything fixed in the stator frame breaks the film's rotational symmetry (waviness,
  /// a film expression, surface features): then the loads of a turned state are not the turned
  /// loads, and a frame that turns must be accounted for.
  bool has_angular_pattern() const { return wave_amplitude != 0 || expression || features; }

  /// The same film written in a frame turned by `angle` (rad, +theta) about the axis: the parts
  /// fixed in the old frame (tilt, tilt rate, waviness, film expression) are turned by -angle,
  /// the surface features stay where they are (they are fixed in the new frame: it is the
  /// rotor's when rotor-borne features have turned by `angle`). A point at theta in the new frame
  /// is at theta + angle in the old one, so h_new(r, theta) = h_old(r, theta + angle) for all but
  /// the features, exactly (the expression is evaluated at theta + frame_angle).
  FilmThickness turned_frame(double angle) const;

  /// Minimum of h over the dam, and where it occurs (found on a fine polar grid + analytic
  /// radial extremes: h is linear in r for fixed theta).
  struct Extremum
  {
    double value, r, theta;
  };
  Extremum minimum() const;
  Extremum maximum() const;

  double tilt_x() const { return tilt * std::sin(tilt_angle); }
  double tilt_y() const { return -tilt * std::cos(tilt_angle); }
  /// Set gamma, psi from the tilt vector (tilt_x, tilt_y) of the flexible ring.
  void set_tilt_vector(const double tilt_x, const double tilt_y);

  double inner_radius = 0.0355; // m
  double outer_radius = 0.0408; // m
  double clearance = 1e-6;      // m, C0
  double coning = 1e-3;         // rad, beta
  double tilt = 0;              // rad, gamma
  double tilt_angle = 0;        // rad, psi
  double wave_amplitude = 0;    // m
  double wave_number = 0;       // waves per revolution
  double wave_phase = 0;        // rad
  double axial_offset = 0;      // m, z of the flexible ring about the set point
  double axial_velocity = 0;    // m/s
  double tilt_rate_x = 0;       // rad/s
  double tilt_rate_y = 0;       // rad/s
  double time = 0;              // s, the t of the film expression
  /// rad: angle of the frame of this film from the frame the film expression is written in (the
  /// stator's); the expression is evaluated at theta + frame_angle (turned_frame).
  double frame_angle = 0;

  /// Geometry/Film expression (null: none) and Geometry/Surface features (null: none). Shared
  /// (immutable) between copies of the film: the perturbed and transient films copy it often.
  std::shared_ptr<const FilmExpression> expression;
  std::shared_ptr<const SurfaceFeatures> features;
};

} // namespace sealfe
