// FaceContact: the GW/CEB asperity contact of Green 2002 Eq. 1–10 integrated over the seal face
// with the local film h(r, theta), so that contact carries force and both moments (resists tilt).
#pragma once

#include <sealfe/film/asperity_contact.h>
#include <sealfe/film/film_thickness.h>

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace sealfe
{
/// A fixed polar quadrature of the dam (Gauss-Legendre in r, periodic trapezoid in theta) on
/// which the contact pressure p_c(h(r, theta)) and the viscous-heating film of the thermal coning
/// are integrated. Subsection "Face contact": Model (gw-ceb | none; the asperity parameters are
/// those of subsection "Contact" and Roughness/Composite roughness), Radial points, Angular
/// points.
class FaceContact
{
public:
  struct Loads
  {
    double force = 0;         ///< N, opening
    double moment_x = 0;      ///< N m, Int p_c y dA (film_loads.h conventions)
    double moment_y = 0;      ///< N m, -Int p_c x dA
    double min_film = 0;      ///< m, smallest h on the quadrature points
    double heating_film = 0;  ///< m, Int r^2 dA / Int r^2/h dA (dissipation-mean film)
    double area_fraction = 0; ///< real contact area / nominal area
  };

  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Reads "Face contact", "Contact" and "Roughness".
  void parse_parameters(dealii::ParameterHandler &prm, double inner_radius, double outer_radius);
  FaceContact() = default;
  FaceContact(const AsperityContact &contact, double inner_radius, double outer_radius,
              unsigned int radial_points = 8, unsigned int angular_points = 96);

  bool enabled() const { return contact_.enabled(); }
  double composite_roughness() const { return contact_.parameters().composite_roughness; }
  const AsperityContact &model() const { return contact_; }
  /// Loads of the asperities on the flexible ring for the film shape `film` (its position,
  /// tilt and coning; h may be <= 0 where the faces interfere: the GW/CEB formulas hold there).
  Loads loads(const FilmThickness &film) const;

private:
  void build(unsigned int radial_points, unsigned int angular_points);
  AsperityContact contact_;
  double ri = 0, ro = 0;
  std::vector<double> r_, wr_, theta_, cos_, sin_;
  double wtheta_ = 0;
};
} // namespace sealfe
