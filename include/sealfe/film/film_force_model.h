// FilmForceModel: what the ring dynamics asks of the film — the loads (force, moments, leakage,
// friction, contact) and optionally the stiffness and damping for a ring state — behind one
// interface that every film level (closed form, table, finite element) implements.
#pragma once

#include <sealfe/film/film_coefficients.h>
#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <array>
#include <string>

namespace sealfe
{
/// The fidelity of the film (doc/reynolds.md, Levels): 0 closed forms of the narrow seal,
/// 1 interpolation in a table of finite-element results made beforehand, 2 a finite-element
/// Reynolds solve at each evaluation.
enum class FilmLevel
{
  closed_form = 0,
  table = 1,
  finite_element = 2
};
/// "closed form", "table", "finite element".
std::string to_string(FilmLevel level);
/// Inverse of to_string; throws std::runtime_error (one line naming the accepted values).
FilmLevel film_level_from_string(const std::string &name);
/// The prm pattern of the three names, "closed form|table|finite element".
std::string film_level_pattern();

/// The state of the face pair that the dynamics changes in time: position and velocity of the
/// flexibly mounted ring's face relative to its mate (conventions of film_thickness.h: the face
/// moves axially by w = z + tilt_x y - tilt_y x), the coning, the ring speeds and the sealed
/// pressures. Everything else (radii, C0, waviness, viscosity, roughness, mesh) belongs to the
/// model and is fixed when it is built. SI units.
struct FilmState
{
  double axial_offset = 0;   ///< z (m): the film at r = ri on the tilt's neutral line is C0 + z
  double tilt_x = 0;         ///< rad, relative tilt vector of the face pair
  double tilt_y = 0;         ///< rad
  double axial_velocity = 0; ///< dz/dt (m/s)
  double tilt_rate_x = 0;    ///< rad/s
  double tilt_rate_y = 0;    ///< rad/s
  double coning = 0;         ///< beta (rad), positive: the film opens towards ro
  double rotor_speed = 0;    ///< rad/s
  double stator_speed = 0;   ///< rad/s
  double inner_pressure = 0; ///< Pa
  double outer_pressure = 0; ///< Pa
  double time = 0;           ///< s, the t of a film expression
  /// rad: how far the rotor has turned relative to the stator since t = 0, Int (w1 - w2) dt. Moves
  /// rotor-borne surface features to Phase + rotor_angle in the stator frame (the frame of the
  /// state's vectors and of the film's waviness and expression); nothing else depends on it.
  double rotor_angle = 0;

  /// The state of a film and an operating point (time 0).
  static FilmState from(const FilmThickness &film, const OperatingConditions &conditions);
  /// `base` with this state's position, velocity, coning and time written into it.
  FilmThickness apply(FilmThickness base) const;
  /// `base` with this state's speeds and pressures written into it.
  OperatingConditions apply(OperatingConditions base) const;
  /// The state of the face pair turned about the axis by `angle` (tilt and tilt rate turned).
  FilmState turned(double angle) const;
  /// The angle (rad) of the frame in which a film model solves `base` at this state, the frame
  /// of its surface features, from the stator frame: rotor_angle when the features sit on the
  /// rotor, else 0.
  double feature_frame_angle(const FilmThickness &base) const;
  /// `base` with this state applied (apply), written in the features' frame
  /// (FilmThickness::turned_frame by feature_frame_angle): the film a model solves; its moments
  /// are turned back by turned_back.
  FilmThickness in_feature_frame(const FilmThickness &base) const;
  /// Loads computed in the features' frame (in_feature_frame) with their moments turned back
  /// into the stator frame.
  FilmLoads turned_back(FilmLoads loads, const FilmThickness &base) const;
};

/// The tilt, tilt-rate or moment vector (x, y) turned about the axis by `angle` (rad,
/// counter-clockwise: the sense of the shaft). An axisymmetric seal turned as a whole turns its
/// moments with its tilt.
std::array<double, 2> turned(const std::array<double, 2> &v, double angle);

/// The tilt vector (tilt_x, tilt_y) of a tilt `magnitude` whose film is thickest at `angle`
/// (film_thickness.h: tilt_x = gamma sin psi, tilt_y = -gamma cos psi; the inverse of
/// FilmThickness::set_tilt_vector).
std::array<double, 2> tilt_vector(double magnitude, double angle);

/// The film seen by the ring dynamics. An implementation is built for one seal (geometry beyond
/// the state, fluid, roughness, discretisation) and may keep caches, factorisations or meshes
/// between calls, so calls are not thread-safe.
class FilmForceModel
{
public:
  virtual ~FilmForceModel() = default;
  virtual FilmLevel level() const = 0;
  /// Short description for summaries ("narrow seal, half-Sommerfeld", "table file.csv, cubic").
  virtual std::string description() const = 0;
  /// Loads of the film (and asperity contact, if the model has it) on the flexibly mounted ring
  /// at `state` (film_loads.h for signs and units). Throws std::runtime_error with a one-line
  /// reason when the state is outside what the model can evaluate.
  virtual FilmLoads loads(const FilmState &state) const = 0;
  /// Whether loads() places rotor-borne surface features at FilmState::rotor_angle (the models
  /// that solve the film at each state). A model that holds loads computed beforehand (a table)
  /// holds them at one rotor angle only.
  virtual bool turns_rotor_features() const { return false; }
  /// Whether coefficients() is available.
  virtual bool provides_coefficients() const { return true; }
  /// Stiffness and damping of the film about `state` (film_coefficients.h).
  virtual FilmCoefficients coefficients(const FilmState &state) const = 0;
};

/// Stiffness and damping of any FilmForceModel by central differences of its loads about `state`:
/// position steps dz = 1e-3 min_film (tilts dz / outer_radius), rate steps that move the face by
/// the same amount in 1 ms. The linearisation at the actual state, where a model's own
/// coefficients() may be taken about a reference state (the closed forms: at clearance C0).
FilmCoefficients central_difference_coefficients(const FilmForceModel &film, const FilmState &state,
                                                 double min_film, double outer_radius);

} // namespace sealfe
