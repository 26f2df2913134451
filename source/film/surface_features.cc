#include <sealfe/film/surface_features.h>
#include <sealfe/numerics/number_lists.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

namespace
{
[[noreturn]] void fail(const std::string &what)
{
  throw std::runtime_error("Geometry/Surface features: " + what);
}

void declare_band(ParameterHandler &prm, const std::string &what)
{
  prm.declare_entry("Inner radius", "0", Patterns::Double(0),
                    "Inner radius (m) of the " + what + " (0: the dam's inner radius).");
  prm.declare_entry("Outer radius", "0", Patterns::Double(0),
                    "Outer radius (m) of the " + what + " (0: the dam's outer radius).");
  prm.declare_entry("Phase", "0", Patterns::Double(),
                    "Angle (rad) at which the first period starts, in the frame of the face.");
}
} // namespace

void SurfaceFeatures::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Surface features");
  prm.declare_entry("Face", "stator", Patterns::Selection("stator|rotor"),
                    "Face that carries the features. The film is solved in that ring's frame, "
                    "where the features stand still (exact for the full film at every instant; "
                    "quasi-steady for a cavity, doc/textures.md).");
  prm.enter_subsection("Rayleigh pads");
  prm.declare_entry("Number", "0", Patterns::Integer(0, 100000),
                    "Number of Rayleigh step pads around the face (0: none). Each period "
                    "2 pi / Number holds, in the sense of the rotor's motion relative to the "
                    "stator: the feeding groove, the pocket, the step land, the land.");
  prm.declare_entry("Pad angle", "0", Patterns::Double(0),
                    "Angle (rad) of a pad: pocket + step land (0: the period minus the groove).");
  prm.declare_entry("Step fraction", "0.718", Patterns::Double(0, 1),
                    "Pocket length / pad length (the step's position; Rayleigh's optimum 0.718).");
  prm.declare_entry("Step depth", "0", Patterns::Double(0), "Depth of the pocket (m).");
  prm.declare_entry("Feeding groove angle", "0", Patterns::Double(0),
                    "Angle (rad) of the radial feeding groove ahead of each pocket (0: none).");
  prm.declare_entry("Feeding groove depth", "0", Patterns::Double(0),
                    "Depth (m) of the feeding groove.");
  prm.declare_entry("Feeding groove side", "outer", Patterns::Selection("outer|inner|both"),
                    "Boundary the feeding groove runs to from the pocket (both: across the dam).");
  declare_band(prm, "pockets");
  prm.leave_subsection();

  prm.enter_subsection("Spiral grooves");
  prm.declare_entry("Number", "0", Patterns::Integer(0, 100000),
                    "Number of logarithmic spiral grooves (0: none).");
  prm.declare_entry("Spiral angle", "0.3", Patterns::Double(0, M_PI / 2),
                    "Angle alpha (rad) between a groove and the circumferential direction.");
  prm.declare_entry("Depth", "0", Patterns::Double(0), "Groove depth (m).");
  prm.declare_entry("Groove fraction", "0.5", Patterns::Double(0, 1),
                    "Groove width / (groove + land width), measured around (groove/land ratio "
                    "= f / (1 - f)).");
  prm.declare_entry("Pumping direction", "inward", Patterns::Selection("inward|outward"),
                    "Direction in which the grooves pump for the rotor turning in +theta "
                    "relative to the stator.");
  declare_band(prm, "grooved band");
  prm.leave_subsection();

  prm.enter_subsection("Dimples");
  prm.declare_entry("Area density", "0", Patterns::Double(0, 0.78),
                    "Dimpled area fraction S_p = pi r_p^2 / (2 r1)^2 of Etsion's square cells of "
                    "side 2 r1 (0: none; below pi/4 so that dimples do not overlap).");
  prm.declare_entry("Radius", "0", Patterns::Double(0), "Dimple radius r_p (m).");
  prm.declare_entry("Depth", "0", Patterns::Double(0), "Dimple depth (m), flat bottomed.");
  prm.declare_entry("Pattern", "regular", Patterns::Selection("regular|staggered"),
                    "regular: rows aligned; staggered: every other row shifted by half a pitch.");
  declare_band(prm, "textured band");
  prm.leave_subsection();
  prm.leave_subsection();
}

std::shared_ptr<const SurfaceFeatures> SurfaceFeatures::parse(ParameterHandler &prm,
                                                              const double ri, const double ro)
{
  auto f = std::make_shared<SurfaceFeatures>();
  f->ri = ri;
  f->ro = ro;
  prm.enter_subsection("Surface features");
  f->face = prm.get("Face") == "rotor" ? Face::rotor : Face::stator;
  unsigned int kinds = 0;
  auto band = [&](const std::string &what)
  {
    const double a = prm.get_double("Inner radius"), b = prm.get_double("Outer radius");
    f->band_inner = a > 0 ? a : ri;
    f->band_outer = b > 0 ? b : ro;
    f->phase = prm.get_double("Phase");
    if (!(f->band_inner >= ri && f->band_outer <= ro && f->band_inner < f->band_outer))
    {
      std::ostringstream s;
      s << what << ": the band " << f->band_inner << " .. " << f->band_outer
        << " m must lie within the dam " << ri << " .. " << ro << " m (Inner < Outer radius)";
      fail(s.str());
    }
  };
  prm.enter_subsection("Rayleigh pads");
  if (prm.get_integer("Number") > 0)
  {
    ++kinds;
    f->kind = Kind::rayleigh_pads;
    f->number = prm.get_integer("Number");
    f->feature_depth = prm.get_double("Step depth");
    f->step_fraction = prm.get_double("Step fraction");
    f->groove_angle = prm.get_double("Feeding groove angle");
    f->groove_depth = prm.get_double("Feeding groove depth");
    const std::string side = prm.get("Feeding groove side");
    f->groove_side = side == "inner"  ? GrooveSide::inner
                     : side == "both" ? GrooveSide::both
                                      : GrooveSide::outer;
    const double period = 2 * M_PI / f->number;
    f->pad_angle = prm.get_double("Pad angle");
    if (f->pad_angle == 0)
      f->pad_angle = period - f->groove_angle;
    band("Rayleigh pads");
    if (!(f->feature_depth > 0))
      fail("Rayleigh pads: Step depth must be positive (the pocket is a recess)");
    if (f->groove_angle > 0 && !(f->groove_depth > 0))
      fail("Rayleigh pads: Feeding groove depth must be positive when Feeding groove angle > 0");
    if (!(f->pad_angle > 0) || f->groove_angle + f->pad_angle > period * (1 + 1e-12))
    {
      std::ostringstream s;
      s << "Rayleigh pads: Feeding groove angle + Pad angle (" << f->groove_angle + f->pad_angle
        << " rad) must be positive and fit in the period 2 pi / Number = " << period << " rad";
      fail(s.str());
    }
  }
  prm.leave_subsection();
  prm.enter_subsection("Spiral grooves");
  if (prm.get_integer("Number") > 0)
  {
    ++kinds;
    f->kind = Kind::spiral_grooves;
    f->number = prm.get_integer("Number");
    f->spiral_angle = prm.get_double("Spiral angle");
    f->feature_depth = prm.get_double("Depth");
    f->groove_fraction = prm.get_double("Groove fraction");
    f->pump_inward = prm.get("Pumping direction") == "inward";
    band("Spiral grooves");
    if (!(f->feature_depth > 0))
      fail("Spiral grooves: Depth must be positive (a groove is a recess)");
    if (!(f->spiral_angle > 0 && f->spiral_angle < M_PI / 2))
      fail("Spiral grooves: Spiral angle must lie in (0, pi/2) rad");
    if (!(f->groove_fraction > 0 && f->groove_fraction < 1))
      fail("Spiral grooves: Groove fraction must lie in (0, 1)");
  }
  prm.leave_subsection();
  prm.enter_subsection("Dimples");
  if (prm.get_double("Area density") > 0)
  {
    ++kinds;
    f->kind = Kind::dimples;
    f->area_density = prm.get_double("Area density");
    f->dimple_radius = prm.get_double("Radius");
    f->feature_depth = prm.get_double("Depth");
    f->staggered = prm.get("Pattern") == "staggered";
    band("Dimples");
    if (!(f->feature_depth > 0) || !(f->dimple_radius > 0))
      fail("Dimples: Radius and Depth must be positive");
    // Etsion's cell: side 2 r1 = r_p sqrt(pi / S_p); rows across the band, the same number of
    // dimples in every row (so the pattern repeats 'number' times around).
    const double side = f->dimple_radius * std::sqrt(M_PI / f->area_density);
    const double band_width = f->band_outer - f->band_inner;
    f->dimple_rows = std::max(1u, static_cast<unsigned int>(std::lround(band_width / side)));
    f->row_pitch = band_width / f->dimple_rows;
    const double r_mid = 0.5 * (f->band_inner + f->band_outer);
    f->number = std::max(1u, static_cast<unsigned int>(std::lround(2 * M_PI * r_mid / side)));
    const double pitch_inner = 2 * M_PI * (f->band_inner + 0.5 * f->row_pitch) / f->number;
    if (2 * f->dimple_radius >= std::min(f->row_pitch, pitch_inner))
    {
      std::ostringstream s;
      s << "Dimples: dimples of radius " << f->dimple_radius << " m overlap (row pitch "
        << f->row_pitch << " m, pitch around " << pitch_inner
        << " m on the inner row); lower Area density or widen the band";
      fail(s.str());
    }
  }
  prm.leave_subsection();
  prm.leave_subsection();
  if (kinds == 0)
    return nullptr;
  if (kinds > 1)
    fail("switch on one kind of feature at a time (Rayleigh pads, Spiral grooves or Dimples)");
  return f;
}

double SurfaceFeatures::local_angle(const double theta) const
{
  const double period = 2 * M_PI / number;
  double a = theta - phase;
  if (face == Face::rotor)
    a = -a; // mirrored: the stator moves in -theta relative to the rotor
  a -= period * std::floor(a / period);
  return a >= period ? 0.0 : a;
}

double SurfaceFeatures::spiral_cot() const
{
  // theta = phase + k P + s cot(alpha) ln(r / r_in): moving in +theta along a groove goes
  // outward if s > 0, so the fluid dragged in +theta is pumped outward (drawn on the stator).
  const double s = (pump_inward ? -1.0 : 1.0) * (face == Face::rotor ? -1.0 : 1.0);
  return s / std::tan(spiral_angle);
}

double SurfaceFeatures::spiral_shift(const double r) const
{
  // the mesh lines' own formula (AnnulusMesh::Alignment::shift), so grooves and lines coincide
  AnnulusMesh::Alignment spiral;
  spiral.spiral_cot = spiral_cot();
  spiral.spiral_r0 = band_inner;
  spiral.spiral_r1 = band_outer;
  return spiral.shift(r);
}

double SurfaceFeatures::depth(const double r, const double theta) const
{
  switch (kind)
  {
  case Kind::rayleigh_pads:
  {
    const double a = local_angle(theta);
    if (a < groove_angle)
    {
      const bool in_groove = groove_side == GrooveSide::both    ? true
                             : groove_side == GrooveSide::outer ? r >= band_inner
                                                                : r <= band_outer;
      if (in_groove)
        return groove_depth;
    }
    if (r < band_inner || r > band_outer)
      return 0;
    if (a >= groove_angle && a < groove_angle + step_fraction * pad_angle)
      return feature_depth;
    return 0;
  }
  case Kind::spiral_grooves:
  {
    if (r < band_inner || r > band_outer)
      return 0;
    const double period = 2 * M_PI / number;
    double a = theta - phase - spiral_shift(r);
    a -= period * std::floor(a / period);
    return a < groove_fraction * period ? feature_depth : 0.0;
  }
  case Kind::dimples:
  {
    if (r < band_inner - dimple_radius || r > band_outer + dimple_radius)
      return 0;
    const double pitch = 2 * M_PI / number;
    const int row = static_cast<int>(std::floor((r - band_inner) / row_pitch));
    for (int k = std::max(row - 1, 0); k <= std::min(row + 1, int(dimple_rows) - 1); ++k)
    {
      const double rc = row_radius(k);
      const double t0 = row_phase(k);
      const double j = std::round((theta - t0) / pitch);
      const double dt = theta - t0 - j * pitch;
      const double d2 = r * r + rc * rc - 2 * r * rc * std::cos(dt);
      if (d2 < dimple_radius * dimple_radius)
        return feature_depth;
    }
    return 0;
  }
  }
  return 0;
}

double SurfaceFeatures::row_radius(const unsigned int k) const
{
  return band_inner + (k + 0.5) * row_pitch;
}

double SurfaceFeatures::row_phase(const unsigned int k) const
{
  return phase + (staggered && k % 2 == 1 ? M_PI / number : 0.0);
}

std::vector<dealii::Point<2>> SurfaceFeatures::dimple_centres() const
{
  std::vector<dealii::Point<2>> centres;
  if (kind != Kind::dimples)
    return centres;
  for (unsigned int k = 0; k < dimple_rows; ++k)
    for (unsigned int j = 0; j < number; ++j)
    {
      const double r = row_radius(k), t = row_phase(k) + 2 * M_PI * j / number;
      centres.emplace_back(r * std::cos(t), r * std::sin(t));
    }
  return centres;
}

double SurfaceFeatures::max_depth() const
{
  return std::max(feature_depth, kind == Kind::rayleigh_pads ? groove_depth : 0.0);
}

double SurfaceFeatures::achieved_area_density() const
{
  if (kind != Kind::dimples)
    return 0;
  const double dimples = double(dimple_rows) * number * M_PI * dimple_radius * dimple_radius;
  return dimples / (M_PI * (band_outer * band_outer - band_inner * band_inner));
}

AnnulusMesh::Alignment SurfaceFeatures::mesh_alignment() const
{
  AnnulusMesh::Alignment a;
  a.periods = number;
  a.phase = phase;
  auto mirror = [&](std::vector<double> breaks)
  {
    // on the rotor the drawing runs in -theta: a break at fraction b is at 1 - b
    if (face == Face::rotor)
      for (double &b : breaks)
        b = b > 0 ? 1 - b : 0;
    return breaks;
  };
  const double period = 2 * M_PI / number;
  switch (kind)
  {
  case Kind::rayleigh_pads:
  {
    std::vector<double> b{0.0, (groove_angle + step_fraction * pad_angle) / period,
                          (groove_angle + pad_angle) / period};
    if (groove_angle > 0)
      b.push_back(groove_angle / period);
    for (double &x : b)
      if (x >= 1 - 1e-12)
        x = 0;
    a.theta_breaks = mirror(b);
    a.radial_breaks = {band_inner, band_outer};
    break;
  }
  case Kind::spiral_grooves:
    a.theta_breaks = {0.0, groove_fraction};
    a.radial_breaks = {band_inner, band_outer};
    a.spiral_cot = spiral_cot();
    a.spiral_r0 = band_inner;
    a.spiral_r1 = band_outer;
    break;
  case Kind::dimples:
    // circles are not mesh lines of a polar grid: only the band edges and the period; the
    // generated gmsh mesh follows the circles
    a.theta_breaks = {0.0};
    a.radial_breaks = {band_inner, band_outer};
    a.circle_centres = dimple_centres();
    a.circle_radius = dimple_radius;
    break;
  }
  // drop breaks that coincide (within round-off) with 0 or each other
  std::sort(a.theta_breaks.begin(), a.theta_breaks.end());
  a.theta_breaks.erase(std::unique(a.theta_breaks.begin(), a.theta_breaks.end(),
                                   [](double x, double y) { return std::abs(x - y) < 1e-12; }),
                       a.theta_breaks.end());
  return a;
}

} // namespace sealfe
