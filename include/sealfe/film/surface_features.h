// SurfaceFeatures: recesses machined into one seal face (Rayleigh step pads, spiral grooves, laser
// dimples), the depth they add to the film, and the mesh lines the film's steps lie on.
#pragma once

#include <sealfe/film/annulus_mesh.h>

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>
#include <vector>

namespace sealfe
{
/// Reads subsection "Geometry/Surface features" (one feature kind at a time, on the stator or the
/// rotor face). All features are flat-bottomed recesses of depth > 0 (m) added to the film, so
/// they never bring the faces closer (the touch-down check is that of the land). Pads and spiral
/// grooves are drawn for the rotor turning in +theta relative to the stator (omega1 > omega2);
/// on the rotor face they are mirrored so that they act the same way.
class SurfaceFeatures
{
public:
  enum class Face
  {
    stator,
    rotor
  };
  enum class Kind
  {
    rayleigh_pads,
    spiral_grooves,
    dimples
  };

  /// Declares the subsection "Surface features" (call inside "Geometry").
  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Parses it (inside "Geometry"); null if no feature is switched on. Throws std::runtime_error
  /// with one line naming the problem (two kinds at once, a depth <= 0, a pad longer than its
  /// period, a band outside the dam, ...).
  static std::shared_ptr<const SurfaceFeatures> parse(dealii::ParameterHandler &prm,
                                                      const double ri, const double ro);

  /// Depth (m, >= 0) the features add to the film at (r, theta), theta in the frame of the face
  /// that carries them.
  double depth(const double r, const double theta) const;
  /// Largest depth (m).
  double max_depth() const;
  /// Cell edges the built-in mesh puts on the feature's steps (AnnulusMesh::Alignment).
  AnnulusMesh::Alignment mesh_alignment() const;
  /// Dimples: the area density the layout achieves (dimple area / band area); else 0.
  double achieved_area_density() const;
  /// Dimples: the centres (x, y in m, in the frame of the face) of all dimples, row by row; the
  /// circles of radius dimple_radius about them are the film's steps. Else empty.
  std::vector<dealii::Point<2>> dimple_centres() const;
  /// Number of features around (pads, grooves, dimples per row).
  unsigned int count() const { return number; }

  Kind kind = Kind::rayleigh_pads;
  Face face = Face::stator;

  // Rayleigh pads: per period P = 2 pi / n, from its start (phase + k P): feeding groove
  // [0, g), pocket [g, g + f L), step land [g + f L, g + L), land between pads [g + L, P).
  double pad_angle = 0;         // rad, L (pocket + step land)
  double step_fraction = 0.718; // f, pocket length / pad length (Rayleigh's optimum 0.718)
  double groove_angle = 0;      // rad, g (0: no feeding groove)
  double groove_depth = 0;      // m
  enum class GrooveSide
  {
    outer,
    inner,
    both
  } groove_side = GrooveSide::outer;

  // Spiral grooves (log spirals at constant angle alpha to the circumferential direction)
  double spiral_angle = 0.3;    // rad, alpha
  double groove_fraction = 0.5; // groove width / (groove + land width), measured around
  bool pump_inward = true;

  // Dimples (Etsion's layout: each dimple in an imaginary square cell of side 2 r1 with
  // S_p = pi r_p^2 / (2 r1)^2, in rows across the band)
  double area_density = 0;  // S_p
  double dimple_radius = 0; // m, r_p
  bool staggered = false;

  unsigned int number = 0;               // pads, grooves, or dimples per row
  double feature_depth = 0;              // m: pocket, groove or dimple depth
  double band_inner = 0, band_outer = 0; // m: radial extent of the pocket, grooves or dimples
  double phase = 0;                      // rad: where the first period starts
  double ri = 0, ro = 0;                 // m: the dam

private:
  /// Angle within a period, in [0, P), in the stator's drawing sense (mirrored on the rotor).
  double local_angle(const double theta) const;
  double spiral_shift(const double r) const;
  /// s cot(alpha) of the groove spirals theta = phase + k P + s cot(alpha) ln(r / r_in).
  double spiral_cot() const;
  /// Dimples: radius of the centres of row k, and the angle of its first centre.
  double row_radius(const unsigned int k) const;
  double row_phase(const unsigned int k) const;
  unsigned int dimple_rows = 0;
  double row_pitch = 0;
};

} // namespace sealfe
