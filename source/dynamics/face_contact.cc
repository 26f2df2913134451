#include <sealfe/dynamics/face_contact.h>
#include <sealfe/film/flow_factors.h>

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>

namespace sealfe
{
void FaceContact::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  AsperityContact::declare_parameters(prm);
  FlowFactors::declare_parameters(prm);
  prm.enter_subsection("Face contact");
  prm.declare_entry("Model", "gw-ceb", Selection("gw-ceb|none"),
                    "Asperity contact of the transient and the equilibrium (Green 2002 Eq. 1-10 "
                    "with the parameters of subsection Contact and Roughness/Composite "
                    "roughness), integrated with the local film. Contact/Model is the finite-"
                    "element film's own contact and should stay none here (no double count).");
  prm.declare_entry("Radial points", "8", Integer(1), "Gauss-Legendre points across the dam.");
  prm.declare_entry("Angular points", "96", Integer(8),
                    "Trapezoid points around the face (the contact patch of a tilted face is "
                    "a few per cent of the circumference wide).");
  prm.leave_subsection();
}

void FaceContact::parse_parameters(dealii::ParameterHandler &prm, const double inner_radius,
                                   const double outer_radius)
{
  AsperityContact c;
  c.parse_parameters(prm);
  prm.enter_subsection("Face contact");
  const bool on = prm.get("Model") == "gw-ceb";
  const unsigned int nr = prm.get_integer("Radial points"), nt = prm.get_integer("Angular points");
  prm.leave_subsection();
  *this = FaceContact(
      AsperityContact(on ? AsperityContact::Model::gw_ceb : AsperityContact::Model::none,
                      c.parameters()),
      inner_radius, outer_radius, nr, nt);
  if (on)
    contact_.validate();
}

FaceContact::FaceContact(const AsperityContact &contact, const double inner_radius,
                         const double outer_radius, const unsigned int radial_points,
                         const unsigned int angular_points)
    : contact_(contact), ri(inner_radius), ro(outer_radius)
{
  build(radial_points, angular_points);
}

void FaceContact::build(const unsigned int nr, const unsigned int nt)
{
  const dealii::QGauss<1> q(nr);
  r_.clear();
  wr_.clear();
  for (unsigned int i = 0; i < q.size(); ++i)
  {
    r_.push_back(ri + (ro - ri) * q.point(i)[0]);
    wr_.push_back((ro - ri) * q.weight(i));
  }
  theta_.resize(nt);
  cos_.resize(nt);
  sin_.resize(nt);
  for (unsigned int j = 0; j < nt; ++j)
  {
    theta_[j] = 2 * M_PI * j / nt;
    cos_[j] = std::cos(theta_[j]);
    sin_[j] = std::sin(theta_[j]);
  }
  wtheta_ = 2 * M_PI / nt;
}

FaceContact::Loads FaceContact::loads(const FilmThickness &film) const
{
  Loads out;
  out.min_film = INFINITY;
  const double sigma = composite_roughness();
  // the dissipation-mean film ignores where the faces interfere: h is floored at sigma / 10
  const double floor = 0.1 * sigma;
  double r2 = 0, r2_over_h = 0, area = 0;
  for (unsigned int j = 0; j < theta_.size(); ++j)
    for (unsigned int i = 0; i < r_.size(); ++i)
    {
      const double r = r_[i], dA = r * wr_[i] * wtheta_;
      const double h =
          film.clearance + film.axial_offset + film.coning * (r - ri) +
          film.tilt * r * std::cos(theta_[j] - film.tilt_angle) +
          film.wave_amplitude * std::cos(film.wave_number * (theta_[j] - film.wave_phase));
      out.min_film = std::min(out.min_film, h);
      r2 += r * r * dA;
      r2_over_h += r * r * dA / std::max(h, floor);
      area += dA;
      if (contact_.enabled())
      {
        const double p = contact_.contact_pressure(h).value;
        out.force += p * dA;
        out.moment_x += p * r * sin_[j] * dA;
        out.moment_y -= p * r * cos_[j] * dA;
        out.area_fraction += contact_.real_contact_area_fraction(h) * dA;
      }
    }
  out.heating_film = r2 / r2_over_h;
  out.area_fraction /= area;
  return out;
}
} // namespace sealfe
