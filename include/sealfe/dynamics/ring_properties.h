// The rings of a face seal and their supports: which rings are flexibly mounted
// (SealConfiguration), their inertias, support stiffness/damping and misalignments, and their
// parameter-file subsections.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sealfe
{
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

/// Declares the subsection `name` ("Rotor ring", "Stator ring") with `defaults`; `what` says
/// which ring it is in the entries' documentation.
void declare_ring_parameters(dealii::ParameterHandler &prm, const std::string &name,
                             const RingProperties &defaults, const std::string &what);
/// Reads the subsection `name` declared by declare_ring_parameters.
RingProperties parse_ring_parameters(dealii::ParameterHandler &prm, const std::string &name);

} // namespace sealfe
