// FiniteElementFilm: the finite-element film (level 2) behind the dynamics' FilmForceModel: one
// Reynolds solve per load evaluation, the linearised coefficients for stiffness and damping.
#pragma once

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/film/film_force_model.h>
#include <sealfe/film/film_settings.h>

#include <deal.II/base/mpi.h>

#include <string>

namespace sealfe
{
/// Built for one seal from FilmSettings (everything beyond the FilmState: radii, C0, waviness,
/// fluid, roughness, contact, cavitation, mesh). Keeps one CoefficientSolver, whose ReynoldsSolver
/// builds the mesh, dofs and sparsity once and reuses them for every state with the same
/// discretisation (states change z, tilts, rates, speeds and pressures; a coning change remeshes
/// only when the radial grading uses it). Not thread-safe (FilmForceModel).
class FiniteElementFilm : public FilmForceModel
{
public:
  FiniteElementFilm(const FilmSettings &settings, MPI_Comm comm,
                    const CoefficientSettings &coefficient_settings = CoefficientSettings());

  FilmLevel level() const override { return FilmLevel::finite_element; }
  std::string description() const override;
  /// One finite-element solve at `state` (FilmState::apply on the settings' geometry and
  /// conditions), on the unrefined mesh of the settings.
  /// Rotor-borne surface features stand at Phase + state.rotor_angle: the film is solved in
  /// their frame (FilmState::in_feature_frame) and the moments turned back.
  FilmLoads loads(const FilmState &state) const override;
  bool turns_rotor_features() const override { return true; }
  /// K, D of CoefficientSolver (its method, by default the linearised Reynolds system) at
  /// `state`, without the error estimate. The model string names the dofs and degree; each
  /// evaluation logs one line on stderr (rank 0 of the communicator), since a level-2 sweep may
  /// take minutes: "sealfe: level-2 film coefficients #n at rotor speed ...".
  FilmCoefficients coefficients(const FilmState &state) const override;
  /// How many times coefficients() was called.
  unsigned int n_coefficient_evaluations() const { return n_evaluations; }

  /// The solver (mesh, dofs, last solution), e.g. for n_dofs() and n_setups().
  const ReynoldsSolver &reynolds() const { return solver.reynolds(); }
  /// The angle (rad) of the frame of the last solve from the stator frame: the rotor angle when
  /// rotor-borne features turned the film into their frame, else 0 (write_film_fields). After
  /// coefficients() the stored solution may be that of a perturbed state.
  double frame_angle() const { return last_frame_angle; }
  const FilmSettings &settings() const { return base; }

private:
  FilmSettings base;
  MPI_Comm comm;
  mutable CoefficientSolver solver;
  mutable unsigned int n_evaluations = 0;
  mutable double last_frame_angle = 0;
};

} // namespace sealfe
