#include <sealfe/film/asperity_contact.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace gw_ceb
{
double asperity_height_density(const double z, const double s)
{
  return std::exp(-0.5 * z * z / (s * s)) / (std::sqrt(2. * M_PI) * s);
}

ValueAndSlope plastic_integral(const double a, const double s, const double w)
{
  const double a1 = a + 0.5 * w, a2 = a + w;
  const double tail = std::erfc(a2 / (std::sqrt(2.) * s));
  const double value = std::sqrt(2. / M_PI) * s * std::exp(-0.5 * a2 * a2 / (s * s)) - a1 * tail;
  // A tail integral of a non-negative integrand: round-off below zero is not physics.
  return {std::max(value, 0.), -w * asperity_height_density(a2, s) - tail};
}

ValueAndSlope elastic_integral(const double a, const double s, const double w)
{
  const double a1 = a + 0.5 * w;
  const double value = std::pow(0.5, 1.5) * std::pow(w, 2.5) * asperity_height_density(a1, s);
  return {value, -a1 / (s * s) * value};
}

double elastic_area_integral(const double a, const double s, const double w)
{
  return 0.5 * w * w * asperity_height_density(a + 0.5 * w, s);
}
} // namespace gw_ceb

// ---------------------------------------------------------------------------------------------

AsperityContact::AsperityContact(const Model model, const AsperityContactParameters &parameters)
    : model_(model), p(parameters)
{
  validate();
}

void AsperityContact::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Contact");
  prm.declare_entry("Model", "none", Selection("none|gw-ceb"),
                    "Asperity contact: none, or gw-ceb (Greenwood-Williamson elastic / "
                    "Chang-Etsion-Bogy plastic asperities, closed form of Green 2002 Eq. 1-10). "
                    "sigma is the Roughness subsection's Composite roughness.");
  prm.declare_entry("Asperity radius", "1.7e-6", Double(0), "R (m), asperity tip radius.");
  prm.declare_entry("Asperity density", "4.16e11", Double(0),
                    "eta (1/m^2), asperities per unit nominal area.");
  prm.declare_entry("Plasticity index", "6.6167", Anything(),
                    "Psi, sets the critical interference omega_c = sigma_s/Psi^2 (Green 2002 "
                    "Table 1: 6.6167). 'auto' computes the CEB value "
                    "(2E/(pi K H)) sqrt(sigma_s/R) from the other entries.");
  prm.declare_entry("Elastic modulus", "24.07e9", Double(0),
                    "E (Pa), composite: 1/E = (1-nu1^2)/E1 + (1-nu2^2)/E2.");
  prm.declare_entry("Hardness", "1e9", Double(0), "H (Pa) of the softer face.");
  prm.declare_entry("Maximum contact pressure factor", "0.6", Double(0),
                    "K of CEB (0.454 + 0.41 nu).");
  prm.declare_entry("Asperity height deviation ratio", "1", Double(0),
                    "sigma_s/sigma: standard deviation of the asperity heights over that of the "
                    "surface heights (not listed in Green 2002; 1 per its remark sigma*_s ~ 1).");
  prm.declare_entry("Asperity mean offset", "0", Double(),
                    "y_s/sigma: distance from the mean of the surface heights up to the mean of "
                    "the asperity heights (not listed in Green 2002).");
  prm.leave_subsection();
}

void AsperityContact::parse_parameters(dealii::ParameterHandler &prm)
{
  // sigma is the Roughness subsection's (one roughness for both models).
  double sigma = 0;
  try
  {
    prm.enter_subsection("Roughness");
    sigma = prm.get_double("Composite roughness");
    prm.leave_subsection();
  }
  catch (...)
  {
    throw std::runtime_error("Contact: sigma is read from 'Roughness/Composite roughness', which "
                             "is not declared (call FlowFactors::declare_parameters)");
  }

  parse_parameters(prm, sigma);
}

void AsperityContact::parse_parameters(dealii::ParameterHandler &prm,
                                       const double composite_roughness)
{
  prm.enter_subsection("Contact");
  model_ = (prm.get("Model") == "gw-ceb") ? Model::gw_ceb : Model::none;
  p.asperity_radius = prm.get_double("Asperity radius");
  p.asperity_density = prm.get_double("Asperity density");
  p.elastic_modulus = prm.get_double("Elastic modulus");
  p.hardness = prm.get_double("Hardness");
  p.pressure_factor = prm.get_double("Maximum contact pressure factor");
  p.asperity_deviation_ratio = prm.get_double("Asperity height deviation ratio");
  p.asperity_offset = prm.get_double("Asperity mean offset");
  const std::string psi = prm.get("Plasticity index");
  prm.leave_subsection();
  p.composite_roughness = composite_roughness;

  if (psi == "auto")
    p.plasticity_index =
        ceb_plasticity_index(p.elastic_modulus, p.hardness, p.pressure_factor, p.asperity_radius,
                             p.asperity_deviation_ratio * p.composite_roughness);
  else
  {
    std::size_t used = 0;
    try
    {
      p.plasticity_index = std::stod(psi, &used);
    }
    catch (...)
    {
      used = 0;
    }
    if (used == 0 || psi.find_first_not_of(" \t", used) != std::string::npos)
      throw std::runtime_error("Contact: Plasticity index must be a number or 'auto' (got '" + psi +
                               "')");
  }
  validate();
}

void AsperityContact::validate() const
{
  const std::pair<const char *, double> positive[] = {
      {"Composite roughness", p.composite_roughness},
      {"Asperity radius", p.asperity_radius},
      {"Asperity density", p.asperity_density},
      {"Plasticity index", p.plasticity_index},
      {"Elastic modulus", p.elastic_modulus},
      {"Hardness", p.hardness},
      {"Maximum contact pressure factor", p.pressure_factor},
      {"Asperity height deviation ratio", p.asperity_deviation_ratio}};
  if (!std::isfinite(p.asperity_offset))
    throw std::runtime_error("Contact: Asperity mean offset is not a finite number");
  if (model_ == Model::none)
    return;
  for (const auto &[name, value] : positive)
    if (!(value > 0) || !std::isfinite(value))
    {
      std::ostringstream s;
      s << "Contact: " << name << " must be a positive number (got " << value << ")";
      throw std::runtime_error(s.str());
    }
}

double AsperityContact::asperity_parameter() const
{
  return p.asperity_density * p.asperity_radius * p.composite_roughness;
}

double AsperityContact::critical_interference() const
{
  return p.asperity_deviation_ratio / (p.plasticity_index * p.plasticity_index);
}

double AsperityContact::ceb_plasticity_index(const double elastic_modulus, const double hardness,
                                             const double pressure_factor,
                                             const double asperity_radius,
                                             const double asperity_height_deviation)
{
  // omega_c = (pi K H/(2E))^2 R (CEB) and Psi^2 = sigma_s/omega_c.
  return 2. * elastic_modulus / (M_PI * pressure_factor * hardness) *
         std::sqrt(asperity_height_deviation / asperity_radius);
}

double AsperityContact::separation(const double h) const
{
  return h / p.composite_roughness - p.asperity_offset;
}

ValueAndSlope AsperityContact::elastic_contact_pressure(const double h) const
{
  if (!enabled())
    return {0., 0.};
  // Eq. 1a: p_ce = 4/3 beta sqrt(sigma/R) E I_e.
  const double scale = 4. / 3. * asperity_parameter() *
                       std::sqrt(p.composite_roughness / p.asperity_radius) * p.elastic_modulus;
  const ValueAndSlope I =
      gw_ceb::elastic_integral(separation(h), p.asperity_deviation_ratio, critical_interference());
  return {scale * I.value, scale * I.d_dh / p.composite_roughness};
}

ValueAndSlope AsperityContact::plastic_contact_pressure(const double h) const
{
  if (!enabled())
    return {0., 0.};
  // Eq. 1b: p_cp = beta pi K H I_p.
  const double scale = asperity_parameter() * M_PI * p.pressure_factor * p.hardness;
  const ValueAndSlope I =
      gw_ceb::plastic_integral(separation(h), p.asperity_deviation_ratio, critical_interference());
  return {scale * I.value, scale * I.d_dh / p.composite_roughness};
}

ValueAndSlope AsperityContact::contact_pressure(const double h) const
{
  const ValueAndSlope e = elastic_contact_pressure(h), pl = plastic_contact_pressure(h);
  return {e.value + pl.value, e.d_dh + pl.d_dh};
}

double AsperityContact::elastic_contact_area_fraction(const double h) const
{
  if (!enabled())
    return 0.;
  return M_PI * asperity_parameter() *
         gw_ceb::elastic_area_integral(separation(h), p.asperity_deviation_ratio,
                                       critical_interference());
}

double AsperityContact::plastic_contact_area_fraction(const double h) const
{
  if (!enabled())
    return 0.;
  return M_PI * asperity_parameter() *
         gw_ceb::plastic_integral(separation(h), p.asperity_deviation_ratio,
                                  critical_interference())
             .value;
}

double AsperityContact::real_contact_area_fraction(const double h) const
{
  return elastic_contact_area_fraction(h) + plastic_contact_area_fraction(h);
}

} // namespace sealfe
