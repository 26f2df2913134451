// Narrow-groove theory (Muijderman 1966) of a flat seal face with a band of logarithmic spiral
// grooves: the limit of infinitely many grooves, where the pressure is axisymmetric.
#pragma once

namespace sealfe::closed_form
{
/// Infinitely many spiral grooves at angle alpha to the circumferential direction, groove
/// fraction a (measured around), land film h, groove film h + d, on the band rgi..rgo of the dam
/// ri..ro (plain dam elsewhere). Averaging over a groove period (pressure gradient along the
/// grooves continuous, flux across them continuous) gives the radial flow per unit circumference
///
///   q_r = -k p'/(12 mu) + sigma (V/2) sin(alpha) cos(alpha) Delta,   V = (w_other - w_F) r,
///   k = <h^3> sin^2 + cos^2 / <h^-3>,   Delta = <h> - <h^-2> / <h^-3>,
///
/// (<.> the groove/land average), sigma = +1 for outward pumping; on the plain dam k = h^3,
/// Delta = 0. 2 pi r q_r = Q is the same on every circle: the pressure in each zone is
/// A + B r^2 + C ln r, and Q follows from p(ri) = pi, p(ro) = po.
struct NarrowGrooveSeal
{
  double ri, ro, rgi, rgo; // m
  double film, depth;      // m: land film h (flat faces) and groove depth d
  double groove_fraction;  // a
  double spiral_angle;     // rad
  bool pump_inward = true;
  double viscosity;      // Pa s
  double relative_speed; // rad/s, speed of the plain face relative to the grooved one
  double inner_pressure, outer_pressure, reference_pressure = 0; // Pa

  struct Result
  {
    double force;          // N, int (p - p_ref) dA
    double leakage_outer;  // m^3/s out through r = ro (= -leakage_inner)
    double p_groove_inner; // Pa at r = rgi
    double p_groove_outer; // Pa at r = rgo
  };
  Result solve() const;
  /// Pressure (Pa) at radius r, from a solved Q.
  double pressure(const double r) const;
};

} // namespace sealfe::closed_form
