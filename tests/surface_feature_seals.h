// Seals with surface features shared by tests/validation/surface_features.cc and
// tests/long/surface_feature_convergence.cc: a Rayleigh-pad face, a spiral-groove face and a
// laser-dimpled face, each as FilmSettings parsed from prm text (the input path users take).
#pragma once

#include <sealfe/film/film_settings.h>
#include <sealfe/film/film_summary.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

namespace sealfe::test
{
/// |Q_in + Q_out + squeeze| of a solve relative to its flow scale (film_summary.h), printed with
/// the force and the cavitated fraction under the heading `what`.
inline double relative_mass_imbalance(const ReynoldsSolver &solver, const FilmLoads &loads,
                                      const std::string &what)
{
  const double scale =
      mass_balance_flow_scale(solver.settings.geometry, solver.settings.conditions, loads);
  const double imbalance =
      std::abs(loads.leakage_inner + loads.leakage_outer + loads.squeeze_flow) / scale;
  std::cout << what << ": dofs " << solver.n_dofs() << ", force " << loads.force_z
            << " N, cavitated fraction " << loads.cavitated_fraction << ", mass balance "
            << imbalance << " of " << scale << " m^3/s\n";
  return imbalance;
}

inline FilmSettings parse_settings(const std::string &text)
{
  dealii::ParameterHandler prm;
  FilmSettings::declare_parameters(prm);
  prm.parse_input_from_string(text);
  FilmSettings s;
  s.parse_parameters(prm);
  s.estimate_error = false;
  return s;
}

/// Rayleigh pads on a flat dam 25..35 mm, land film h2 = 2 um, pocket h1 = H h2, pads from a
/// radial feeding groove 100 um deep across the dam (ambient pressure 0 on both circles) to the
/// next groove; the groove takes a tenth of the period. Rotor 100 rad/s.
struct RayleighPadSeal
{
  unsigned int pads = 40;
  double film_ratio = 1.866, step_fraction = 0.718;
  unsigned int cells_per_pad = 10, radial_cells = 8, degree = 2;
  bool align = true;

  static constexpr double ri = 0.025, ro = 0.035, h2 = 2e-6, omega = 100, mu = 1.2e-3;
  double period() const { return 2 * M_PI / pads; }
  double groove_angle() const { return 0.1 * period(); }
  double pad_angle() const { return period() - groove_angle(); }

  FilmSettings settings() const
  {
    std::ostringstream s;
    s.precision(17);
    s << "subsection Geometry\n set Inner radius = " << ri << "\n set Outer radius = " << ro
      << "\n set Clearance = " << h2 << "\n set Coning = 0\n subsection Surface features\n"
      << "  subsection Rayleigh pads\n   set Number = " << pads
      << "\n   set Step depth = " << (film_ratio - 1) * h2
      << "\n   set Step fraction = " << step_fraction
      << "\n   set Feeding groove angle = " << groove_angle()
      << "\n   set Feeding groove depth = 1e-4\n   set Feeding groove side = both\n  end\n end\n"
      << "end\nsubsection Operating conditions\n set Inner pressure = 0\n"
      << " set Outer pressure = 0\n set Rotor speed = " << omega << "\n set Viscosity = " << mu
      << "\nend\nsubsection Discretization\n set Radial cells = " << radial_cells
      << "\n set Circumferential cells = " << pads * cells_per_pad
      << "\n set Polynomial degree = " << degree << "\n set Radial grading = false\n"
      << " set Align with features = " << (align ? "true" : "false") << "\nend\n";
    return parse_settings(s.str());
  }
  /// Angle of the step of the first pad (phase 0).
  double step_angle() const { return groove_angle() + step_fraction * pad_angle(); }
};

/// Spiral grooves pumping inward on the outer band 33..40 mm of a flat dam 30..40 mm, land film
/// 3 um, groove depth 6 um, alpha = 0.3 rad, groove fraction 0.5; pi = po = 0; rotor 500 rad/s.
struct SpiralGrooveSeal
{
  unsigned int grooves = 16;
  unsigned int cells_per_groove = 8, radial_cells = 16, degree = 2;
  bool align = true;

  static constexpr double ri = 0.030, ro = 0.040, rg = 0.033, h = 3e-6, depth = 6e-6, alpha = 0.3,
                          fraction = 0.5, omega = 500, mu = 1.2e-3;

  FilmSettings settings() const
  {
    std::ostringstream s;
    s.precision(17);
    s << "subsection Geometry\n set Inner radius = " << ri << "\n set Outer radius = " << ro
      << "\n set Clearance = " << h << "\n set Coning = 0\n subsection Surface features\n"
      << "  subsection Spiral grooves\n   set Number = " << grooves << "\n   set Depth = " << depth
      << "\n   set Spiral angle = " << alpha << "\n   set Groove fraction = " << fraction
      << "\n   set Inner radius = " << rg
      << "\n   set Pumping direction = inward\n  end\n end\nend\n"
      << "subsection Operating conditions\n set Inner pressure = 0\n set Outer pressure = 0\n"
      << " set Rotor speed = " << omega << "\n set Viscosity = " << mu << "\nend\n"
      << "subsection Discretization\n set Radial cells = " << radial_cells
      << "\n set Circumferential cells = " << grooves * cells_per_groove
      << "\n set Polynomial degree = " << degree << "\n set Radial grading = false\n"
      << " set Align with features = " << (align ? "true" : "false") << "\nend\n";
    return parse_settings(s.str());
  }
};

/// Laser dimples (Etsion's layout, one row, S_p = 0.2, r_p = 1 mm, depth 4 um) on a flat dam
/// 34..40 mm with land film 2 um; ambient 1e5 Pa on both circles, p_cav = 0; rotor 300 rad/s.
struct DimpledSeal
{
  unsigned int cells_around = 512, radial_cells = 16, degree = 2;
  std::string cavitation = "jfo";
  bool staggered = false;

  double radius = 1e-3;
  /// > 0: the mesh generated by gmsh with lines on the dimple circles (cells of about this size,
  /// m), written to mesh_file and refined `refinements` times; else the built-in polar grid.
  double mesh_size = 0;
  std::string mesh_file;
  unsigned int refinements = 0;
  static constexpr double ri = 0.034, ro = 0.040, h = 2e-6, depth = 4e-6, density = 0.2,
                          omega = 300, ambient = 1e5;

  FilmSettings settings() const
  {
    std::ostringstream s;
    s.precision(17);
    s << "subsection Geometry\n set Inner radius = " << ri << "\n set Outer radius = " << ro
      << "\n set Clearance = " << h << "\n set Coning = 0\n subsection Surface features\n"
      << "  subsection Dimples\n   set Area density = " << density << "\n   set Radius = " << radius
      << "\n   set Depth = " << depth
      << "\n   set Pattern = " << (staggered ? "staggered" : "regular") << "\n  end\n end\nend\n"
      << "subsection Operating conditions\n set Inner pressure = " << ambient
      << "\n set Outer pressure = " << ambient << "\n set Reference pressure = " << ambient
      << "\n set Rotor speed = " << omega << "\nend\n"
      << "subsection Cavitation\n set Model = " << cavitation << "\nend\n"
      << "subsection Discretization\n set Radial cells = " << radial_cells
      << "\n set Circumferential cells = " << cells_around
      << "\n set Polynomial degree = " << degree << "\n set Radial grading = false\n";
    if (mesh_size > 0)
      s << " set Mesh file = " << mesh_file << "\n set Mesh size = " << mesh_size
        << "\n set Global refinements = " << refinements << "\n";
    s << "end\n";
    return parse_settings(s.str());
  }
};

} // namespace sealfe::test
