// The dynamics area in one include: linear angular dynamics of face seals (FMS, FMR, FMRR, FMS on
// a flexible rotor) fed by the film of the chosen level — eigenvalues, Routh-Hurwitz, stability
// thresholds, forced response, time integration, and the parameter-file input.
#pragma once

#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/film_levels.h>
#include <sealfe/dynamics/forced_response.h>
#include <sealfe/dynamics/linear_time_integration.h>
#include <sealfe/dynamics/ring_properties.h>
#include <sealfe/dynamics/routh_hurwitz.h>
#include <sealfe/dynamics/seal_dynamics_input.h>
#include <sealfe/dynamics/speed_interpolated_film.h>
#include <sealfe/dynamics/stability_thresholds.h>
