// Annular seal model of Fleming (NASA TM X-73654), its optimisation and the `sealfe annular` run.
#include <sealfe/annular/annular_seal.h>
#include <sealfe/io/csv.h>
#include <sealfe/io/python_plot.h>
#include <sealfe/numerics/minimisation.h>
#include <sealfe/numerics/number_lists.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe::annular
{
namespace
{
constexpr double pi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string &message)
{
  throw std::runtime_error("Annular seal: " + message);
}

std::string number(double x)
{
  std::ostringstream s;
  s << std::setprecision(6) << x;
  return s.str();
}

// 8-point Gauss-Legendre rule on [-1, 1] (symmetric half).
constexpr std::array<double, 4> gauss_x = {
    {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363}};
constexpr std::array<double, 4> gauss_w = {
    {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763}};

/// A piece of the gap on which h / C2 is linear in z / L: zeta in [zeta_a, zeta_b] with
/// eta(zeta_a) = eta_a and eta(zeta_b) = eta_b.
struct Segment
{
  double zeta_a, zeta_b, eta_a, eta_b;
  double eta(double zeta) const
  {
    return zeta_b > zeta_a ? eta_a + (eta_b - eta_a) * (zeta - zeta_a) / (zeta_b - zeta_a) : eta_a;
  }
};

std::vector<Segment> segments(const DimensionlessSeal &seal)
{
  const double H = seal.clearance_ratio;
  switch (seal.geometry)
  {
  case Geometry::straight:
    return {{0, 1, 1, 1}};
  case Geometry::tapered:
    return {{0, 1, H, 1}};
  case Geometry::stepped:
  {
    const double g = seal.step_ratio;
    std::vector<Segment> s{{0, g, H, H}};
    if (g < 1)
      s.push_back({g, 1, 1, 1});
    return s;
  }
  }
  return {};
}

double inlet_eta(const DimensionlessSeal &seal)
{
  return seal.geometry == Geometry::straight ? 1.0 : seal.clearance_ratio;
}

/// Integrates fn(zeta, eta, weight) over [a, b] within one segment. The integrands are powers of
/// eta (singular at eta = 0), so the panels grow geometrically in eta by at most 1.5: the
/// singularity then lies at least five half-widths from each panel's centre and the 8-point rule
/// is exact to rounding (Bernstein ellipse rho >= 9.9, error ~ rho^-16).
template <typename Function>
void integrate(const Segment &seg, double a, double b, Function &&fn)
{
  if (!(b > a))
    return;
  const double eta_a = seg.eta(a), eta_b = seg.eta(b);
  const double ratio = std::max(eta_a, eta_b) / std::min(eta_a, eta_b);
  const unsigned int n_panels =
      std::max(1u, static_cast<unsigned int>(std::ceil(std::log(ratio) / std::log(1.5))));
  // panel ends: geometric in eta, mapped linearly back to zeta
  const auto zeta_at = [&](unsigned int k)
  {
    if (k == 0 || eta_a == eta_b)
      return a + (b - a) * k / n_panels;
    const double eta = eta_a * std::pow(eta_b / eta_a, static_cast<double>(k) / n_panels);
    return k == n_panels ? b : a + (b - a) * (eta - eta_a) / (eta_b - eta_a);
  };
  for (unsigned int p = 0; p < n_panels; ++p)
  {
    const double lo = zeta_at(p), hi = zeta_at(p + 1);
    const double centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (unsigned int q = 0; q < gauss_x.size(); ++q)
      for (const double sign : {-1.0, 1.0})
      {
        const double zeta = centre + sign * half * gauss_x[q];
        fn(zeta, seg.eta(zeta), half * gauss_w[q]);
      }
  }
}

/// Concentric values and eccentricity derivatives (h -> h + e, e = eps C2) of
///   n = int_0^1 Nhat dzeta  and  d = Nhat(1),
///   Nhat(zeta) = xi / (2 eta_1^2) + 1 / (2 eta^2) + Lambda int_0^zeta eta^-(3+s) dzeta',
/// the pressure loss (p0 - p) C2^2 / m^2 * rho of Eq. 5 (with the entrance loss). Then
/// J / ((p0 - pL) L) = -n / d and Kbar = pi/2 d(n/d)/d eps, Mbar = d^-1/2.
struct PressureIntegrals
{
  double n = 0, dn = 0, d = 0, dd = 0;
};

PressureIntegrals pressure_integrals(const DimensionlessSeal &seal)
{
  const double lambda = seal.lambda, s = seal.friction_exponent, xi = seal.entrance_loss;
  const double eta1 = inlet_eta(seal), eta_exit = 1.0;
  PressureIntegrals I;
  I.n = I.d = xi / (2 * eta1 * eta1);
  I.dn = I.dd = -xi / (eta1 * eta1 * eta1);
  I.d += 1 / (2 * eta_exit * eta_exit);
  I.dd += -1 / (eta_exit * eta_exit * eta_exit);
  for (const Segment &seg : segments(seal))
    integrate(seg, seg.zeta_a, seg.zeta_b,
              [&](double zeta, double eta, double w)
              {
                // friction loss per unit length, Lambda eta^-(3+s), and its eta-derivative
                const double friction = lambda * std::pow(eta, -(3 + s));
                const double dfriction = -(3 + s) * friction / eta;
                // int_0^1 int_0^zeta g = int_0^1 (1 - zeta) g
                I.n += w * (1 / (2 * eta * eta) + (1 - zeta) * friction);
                I.dn += w * (-1 / (eta * eta * eta) + (1 - zeta) * dfriction);
                I.d += w * friction;
                I.dd += w * dfriction;
              });
  return I;
}

DimensionlessSeal with(DimensionlessSeal seal, double H, double gamma)
{
  seal.clearance_ratio = H;
  seal.step_ratio = gamma;
  return seal;
}

double objective_value(const DimensionlessCoefficients &c, Objective objective)
{
  return objective == Objective::stiffness ? c.stiffness : c.stiffness / c.leakage;
}

double parse_number(const std::string &entry, const std::string &text)
{
  return numerics::parse_finite_number(text, "Annular seal: " + entry);
}

struct SweepRow
{
  double lambda;
  std::string configuration, objective;
  double bound, H, gamma, K, M, K_ratio, M_ratio;
};

std::vector<SweepRow> lambda_sweep(const AnnularCase &c)
{
  std::vector<SweepRow> rows;
  std::vector<double> gamma_bounds{1.0};
  if (c.bounds.step_ratio_max < 1)
    gamma_bounds.push_back(c.bounds.step_ratio_max);
  for (const double lambda : c.sweep_lambdas)
  {
    DimensionlessSeal base = c.seal.dimensionless();
    base.lambda = lambda;
    DimensionlessSeal straight = base;
    straight.geometry = Geometry::straight;
    const auto s = dimensionless_coefficients(straight);
    rows.push_back({lambda, "straight", "none", 1, 1, 1, s.stiffness, s.leakage, 1, 1});
    for (const Objective obj : {Objective::stiffness, Objective::stiffness_per_leakage})
    {
      base.geometry = Geometry::tapered;
      const Optimum t = optimise(base, obj, c.bounds);
      rows.push_back({lambda, "tapered", to_string(obj), 1, t.clearance_ratio, 1,
                      t.coefficients.stiffness, t.coefficients.leakage,
                      t.coefficients.stiffness / s.stiffness, t.coefficients.leakage / s.leakage});
      base.geometry = Geometry::stepped;
      for (const double gmax : gamma_bounds)
      {
        OptimisationBounds b = c.bounds;
        b.step_ratio_max = gmax;
        const Optimum o = optimise(base, obj, b);
        rows.push_back({lambda, "stepped", to_string(obj), gmax, o.clearance_ratio, o.step_ratio,
                        o.coefficients.stiffness, o.coefficients.leakage,
                        o.coefficients.stiffness / s.stiffness,
                        o.coefficients.leakage / s.leakage});
      }
    }
  }
  return rows;
}
} // namespace

Geometry geometry_from_string(const std::string &name)
{
  if (name == "straight")
    return Geometry::straight;
  if (name == "tapered")
    return Geometry::tapered;
  if (name == "stepped")
    return Geometry::stepped;
  fail("Geometry type must be straight, tapered or stepped (got '" + name + "')");
}

std::string to_string(Geometry geometry)
{
  switch (geometry)
  {
  case Geometry::straight:
    return "straight";
  case Geometry::tapered:
    return "tapered";
  case Geometry::stepped:
    return "stepped";
  }
  return "";
}

std::string to_string(Objective objective)
{
  return objective == Objective::stiffness ? "stiffness" : "stiffness per leakage";
}

FlemingCoefficients fleming_coefficients(Geometry geometry, double H, double gamma, double lambda)
{
  FlemingCoefficients c;
  const double L = lambda;
  if (geometry == Geometry::stepped)
  {
    const double g = gamma, H2 = H * H, H3 = H2 * H, r = 1 - g;
    c.A = H * g + L * g * (2 - g) + L * r * r * H3 + r * H3;
    c.B = g * (3 * H + 1) + 3 * L * (1 + r * r * (H2 - 1)) + r * H2 * (H + 3);
    c.E = H3 + 2 * L * (g + r * H3);
    c.G = H2 * (H + 3) + 6 * L * (g + r * H2);
  }
  else
  {
    if (geometry == Geometry::straight)
      H = 1;
    c.A = H * (H + L);
    c.B = H + c.A;
    c.E = H * (H * H + L * (H + 1));
    c.G = 2 * c.A;
  }
  return c;
}

DimensionlessCoefficients fleming_closed_form(Geometry geometry, double H, double gamma,
                                              double lambda)
{
  if (geometry == Geometry::straight)
    H = 1;
  const FlemingCoefficients c = fleming_coefficients(geometry, H, gamma, lambda);
  return {pi / (2 * c.E * c.E) * (c.B * c.E - c.A * c.G), std::sqrt(2 * H * H * H / c.E)};
}

DimensionlessCoefficients dimensionless_coefficients(const DimensionlessSeal &seal)
{
  const PressureIntegrals I = pressure_integrals(seal);
  return {0.5 * pi * (I.dn * I.d - I.n * I.dd) / (I.d * I.d), 1 / std::sqrt(I.d)};
}

std::vector<ProfilePoint> pressure_profile(const DimensionlessSeal &seal, unsigned int n_points)
{
  n_points = std::max(2u, n_points);
  const double lambda = seal.lambda, s = seal.friction_exponent;
  const double eta1 = inlet_eta(seal);
  const double entrance = seal.entrance_loss / (2 * eta1 * eta1);
  const double total = pressure_integrals(seal).d;
  const std::vector<Segment> segs = segments(seal);

  std::vector<double> zetas;
  for (unsigned int i = 0; i < n_points; ++i)
    zetas.push_back(static_cast<double>(i) / (n_points - 1));
  std::vector<ProfilePoint> profile;
  double friction_before = 0; // friction loss up to the start of the current segment
  for (std::size_t k = 0; k < segs.size(); ++k)
  {
    const Segment &seg = segs[k];
    const bool last = k + 1 == segs.size();
    // points inside this segment, and its two ends (so a step shows both sides)
    std::vector<double> here{seg.zeta_a};
    for (const double z : zetas)
      if (z > seg.zeta_a && (z < seg.zeta_b || (last && z <= seg.zeta_b)))
        here.push_back(z);
    if (here.back() < seg.zeta_b)
      here.push_back(seg.zeta_b);
    double friction = 0, zeta_prev = seg.zeta_a;
    for (const double zeta : here)
    {
      integrate(seg, zeta_prev, zeta,
                [&](double, double eta, double w)
                { friction += w * lambda * std::pow(eta, -(3 + s)); });
      zeta_prev = zeta;
      const double eta = seg.eta(zeta);
      const double loss = entrance + 1 / (2 * eta * eta) + friction_before + friction;
      profile.push_back({zeta, eta, loss / total});
    }
    friction_before += friction;
  }
  // the gap of a seal stepped at gamma = 1 narrows to C2 right at the outlet (an annular orifice)
  if (seal.geometry == Geometry::stepped && seal.step_ratio >= 1)
    profile.push_back({1.0, 1.0, 1.0});
  return profile;
}

Optimum optimise(const DimensionlessSeal &seal, Objective objective,
                 const OptimisationBounds &bounds)
{
  if (seal.geometry == Geometry::straight)
    fail("Optimise needs Geometry type = tapered or stepped (a straight seal has nothing to "
         "optimise)");
  const double H_max = bounds.clearance_ratio_max;
  const unsigned int n_H =
      std::max(41u, static_cast<unsigned int>(std::ceil((H_max - 1) / 0.1)) + 1);
  // The design objective may have several local maxima over the bounds: sample, then polish.
  const auto maximise = [](auto &&fn, double a, double b, unsigned int n_samples)
  {
    const numerics::Minimum m =
        numerics::sampled_maximum(fn, a, b, n_samples, numerics::Domain::interval);
    return std::make_pair(m.x, m.value);
  };
  const auto value = [&](double H, double gamma)
  { return objective_value(dimensionless_coefficients(with(seal, H, gamma)), objective); };

  Optimum opt;
  if (seal.geometry == Geometry::tapered)
  {
    opt.clearance_ratio = maximise([&](double H) { return value(H, 1); }, 1, H_max, n_H).first;
    opt.step_ratio = 1;
  }
  else
  {
    const double g_min = bounds.step_ratio_min, g_max = bounds.step_ratio_max;
    const auto best_H = [&](double gamma)
    { return maximise([&](double H) { return value(H, gamma); }, 1, H_max, n_H); };
    opt.step_ratio =
        g_max > g_min ? maximise([&](double g) { return best_H(g).second; }, g_min, g_max, 41).first
                      : g_max;
    opt.clearance_ratio = best_H(opt.step_ratio).first;
    opt.step_ratio_at_bound = g_max - opt.step_ratio < 1e-6;
  }
  opt.clearance_ratio_at_bound = H_max - opt.clearance_ratio < 1e-6;
  opt.coefficients = dimensionless_coefficients(with(seal, opt.clearance_ratio, opt.step_ratio));
  return opt;
}

double fully_rough_friction_factor(double relative_roughness)
{
  return 0.036 * std::pow(1 / relative_roughness, -fully_rough_friction_exponent);
}

double von_karman_friction_factor(double relative_roughness)
{
  const double inv_sqrt_f = 4 * std::log10(1 / relative_roughness) + 2.28;
  return 1 / (inv_sqrt_f * inv_sqrt_f);
}

double AnnularSeal::inlet_clearance() const
{
  return geometry == Geometry::straight ? outlet_clearance : clearance_ratio * outlet_clearance;
}

DimensionlessSeal AnnularSeal::dimensionless() const
{
  DimensionlessSeal d;
  d.geometry = geometry;
  d.clearance_ratio = geometry == Geometry::straight ? 1 : clearance_ratio;
  d.step_ratio = step_ratio;
  d.lambda = lambda();
  d.entrance_loss = entrance_loss;
  d.friction_exponent = friction_exponent;
  return d;
}

void AnnularSeal::validate() const
{
  const std::pair<const char *, double> positive[] = {{"Diameter", diameter},
                                                      {"Length", length},
                                                      {"Outlet clearance", outlet_clearance},
                                                      {"Friction factor", friction_factor},
                                                      {"Density", density},
                                                      {"Viscosity", viscosity},
                                                      {"Pressure drop", pressure_drop}};
  for (const auto &[name, value] : positive)
    if (!std::isfinite(value) || !(value > 0))
      fail(std::string(name) + " must be a positive number (got " + number(value) + ")");
  if (geometry != Geometry::straight && !(std::isfinite(clearance_ratio) && clearance_ratio >= 1))
    fail("Clearance ratio H = C1/C2 must be at least 1: the inlet clearance may not be smaller "
         "than the Outlet clearance (got H = " +
         number(clearance_ratio) + ")");
  if (geometry == Geometry::stepped && !(step_ratio > 0 && step_ratio <= 1))
    fail("Step position gamma = L1/L must lie in (0, 1] (got " + number(step_ratio) + ")");
  if (!std::isfinite(entrance_loss) || entrance_loss < 0)
    fail("Entrance loss coefficient must be zero or positive (got " + number(entrance_loss) + ")");
  if (!std::isfinite(friction_exponent) || friction_exponent < 0)
    fail("friction exponent must be zero or positive (got " + number(friction_exponent) + ")");
  if (!std::isfinite(outlet_pressure))
    fail("Outlet pressure must be a finite number");
}

AnnularResults evaluate(const AnnularSeal &seal)
{
  seal.validate();
  const DimensionlessCoefficients c = dimensionless_coefficients(seal.dimensionless());
  AnnularResults r;
  r.stiffness_dimensionless = c.stiffness;
  r.leakage_dimensionless = c.leakage;
  r.stiffness = c.stiffness * seal.pressure_drop * seal.length * seal.diameter /
                seal.outlet_clearance; // Eq. 17
  r.leakage = c.leakage * pi * seal.diameter * seal.outlet_clearance *
              std::sqrt(seal.pressure_drop * seal.density); // Eq. 20
  r.volumetric_leakage = r.leakage / seal.density;
  const double unit_flow = r.leakage / (pi * seal.diameter); // m, Eq. 19
  r.reynolds_number = 2 * unit_flow / seal.viscosity;
  return r;
}

void declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  // Physical bounds (doc/guarantees.md): no annular seal is 100 m across or long, nor has a 1 m
  // clearance; non-positive values have the messages of validate().
  const double lowest = Double::min_double_value;
  prm.enter_subsection("Annular seal");
  prm.declare_entry("Geometry type", "stepped", Selection("straight|tapered|stepped"),
                    "Clearance along the axis: straight (constant), tapered (uniform taper from "
                    "the inlet clearance C1 to the outlet clearance C2) or stepped (C1 over the "
                    "inlet length L1, C2 over the rest).");
  prm.declare_entry("Diameter", "0.076", Double(lowest, 100), "Seal diameter D (m).");
  prm.declare_entry("Length", "0.043", Double(lowest, 100), "Seal length L (m).");
  prm.declare_entry("Outlet clearance", "1.3e-4", Double(lowest, 1),
                    "Radial clearance C2 (m) at the outlet, the smallest clearance.");
  prm.declare_entry("Inlet clearance", "", Anything(),
                    "Radial clearance C1 (m) at the inlet. Give either this or Clearance ratio "
                    "(leave the other empty); ignored for straight seals and when optimising.");
  prm.declare_entry("Clearance ratio", "1.59", Anything(),
                    "H = C1/C2 >= 1. Give either this or Inlet clearance (leave the other empty); "
                    "ignored for straight seals and when optimising.");
  prm.declare_entry("Step position", "0.70", Double(),
                    "gamma = L1/L in (0, 1], the length fraction of the large (inlet) clearance of "
                    "a stepped seal; 1 puts an annular orifice at the outlet. Ignored when "
                    "optimising.");
  prm.declare_entry("Friction model", "given", Selection("given|fully rough"),
                    "given: use Friction factor. fully rough: Fleming's fit f = 0.036 "
                    "(d/e_r)^-0.29 with d = 2 C2 from Relative roughness (fully turbulent flow).");
  prm.declare_entry("Friction factor", "0.007", Double(),
                    "Fanning friction factor f at the outlet clearance (Friction model = given).");
  prm.declare_entry("Relative roughness", "0.003333333333", Double(),
                    "e_r/d, surface roughness over the hydraulic diameter d = 2 C2 "
                    "(Friction model = fully rough). The paper's example: d/e_r = 300.");
  prm.declare_entry("Friction variation", "constant", Selection("constant|fully rough"),
                    "constant: one friction factor in the whole seal (the paper's analysis). "
                    "fully rough: f(h) = f (h/C2)^-0.29, the fully rough fit applied to the local "
                    "gap (also around the eccentric seal).");
  prm.declare_entry("Density", "71", Double(), "Fluid density rho (kg/m^3).");
  prm.declare_entry("Viscosity", "1.3e-5", Double(),
                    "Dynamic viscosity (Pa s); only for the Reynolds number 2 m / mu in the "
                    "summary (the model assumes turbulent flow).");
  prm.declare_entry("Pressure specification", "pressure drop",
                    Selection("pressure drop|inlet and outlet"),
                    "pressure drop: use Pressure drop and Outlet pressure. inlet and outlet: "
                    "use Inlet pressure and Outlet pressure.");
  prm.declare_entry("Pressure drop", "136e5", Double(),
                    "p0 - pL (Pa), p0 the upstream stagnation pressure, pL the outlet pressure.");
  prm.declare_entry("Inlet pressure", "136e5", Double(),
                    "Upstream stagnation pressure p0 (Pa) (Pressure specification = inlet and "
                    "outlet).");
  prm.declare_entry("Outlet pressure", "0", Double(), "Outlet pressure pL (Pa).");
  prm.declare_entry("Entrance loss coefficient", "0", Double(),
                    "xi >= 0: the pressure falls by (1 + xi) rho V1^2/2 at the inlet. The paper "
                    "neglects entrance losses (xi = 0).");
  prm.declare_entry("Optimise", "none", Selection("none|stiffness|stiffness per leakage"),
                    "none: evaluate the seal as given. stiffness, stiffness per leakage: choose "
                    "H (and gamma for a stepped seal) that maximise K or K/M for this seal's "
                    "Lambda = f L / C2, keeping D, L and C2.");
  prm.declare_entry("Step position upper bound", "0.8", Double(),
                    "Largest gamma the optimiser may choose, in (0, 1] (the paper also reports "
                    "the bound 0.8, since gamma = 1 is not a practical design).");
  prm.declare_entry("Clearance ratio upper bound", "10", Double(),
                    "Largest H the optimiser may choose, in (1, 100].");
  prm.declare_entry("Profile points", "201", Integer(2),
                    "Number of equally spaced axial points of annular_pressure_profile.csv.");
  prm.enter_subsection("Lambda sweep");
  prm.declare_entry("Values", "", Anything(),
                    "Comma-separated list of Lambda = f L / C2 for the optimum-seal sweep "
                    "(annular_lambda_sweep.csv, like Fleming's Figs. 2-8). If empty, the range "
                    "below is used.");
  prm.declare_entry("Minimum", "0.1", Double(), "Smallest Lambda of the range.");
  prm.declare_entry("Maximum", "20", Double(), "Largest Lambda of the range.");
  prm.declare_entry("Points", "25", Integer(0), "Number of Lambdas in the range (0: no sweep).");
  prm.declare_entry("Spacing", "logarithmic", Selection("logarithmic|linear"),
                    "Spacing of the range.");
  prm.leave_subsection();
  prm.leave_subsection();
}

AnnularCase parse_case(dealii::ParameterHandler &prm)
{
  AnnularCase c;
  AnnularSeal &seal = c.seal;
  prm.enter_subsection("Annular seal");
  seal.geometry = geometry_from_string(prm.get("Geometry type"));
  seal.diameter = prm.get_double("Diameter");
  seal.length = prm.get_double("Length");
  seal.outlet_clearance = prm.get_double("Outlet clearance");
  const std::string inlet = dealii::Utilities::trim(prm.get("Inlet clearance"));
  const std::string ratio = dealii::Utilities::trim(prm.get("Clearance ratio"));
  seal.step_ratio = prm.get_double("Step position");
  const std::string friction_model = prm.get("Friction model");
  seal.friction_factor = prm.get_double("Friction factor");
  const double relative_roughness = prm.get_double("Relative roughness");
  seal.friction_exponent =
      prm.get("Friction variation") == "constant" ? 0.0 : fully_rough_friction_exponent;
  seal.density = prm.get_double("Density");
  seal.viscosity = prm.get_double("Viscosity");
  seal.outlet_pressure = prm.get_double("Outlet pressure");
  if (prm.get("Pressure specification") == "pressure drop")
    seal.pressure_drop = prm.get_double("Pressure drop");
  else
  {
    const double p0 = prm.get_double("Inlet pressure");
    if (!(p0 > seal.outlet_pressure))
      fail("Inlet pressure must exceed Outlet pressure (got " + number(p0) + " and " +
           number(seal.outlet_pressure) + " Pa)");
    seal.pressure_drop = p0 - seal.outlet_pressure;
  }
  seal.entrance_loss = prm.get_double("Entrance loss coefficient");
  const std::string optimise = prm.get("Optimise");
  c.optimise = optimise != "none";
  c.objective = optimise == "stiffness" ? Objective::stiffness : Objective::stiffness_per_leakage;
  c.bounds.step_ratio_max = prm.get_double("Step position upper bound");
  c.bounds.clearance_ratio_max = prm.get_double("Clearance ratio upper bound");
  c.profile_points = prm.get_integer("Profile points");
  prm.enter_subsection("Lambda sweep");
  const std::string values = dealii::Utilities::trim(prm.get("Values"));
  const double lambda_min = prm.get_double("Minimum"), lambda_max = prm.get_double("Maximum");
  const int n_lambda = prm.get_integer("Points");
  const bool logarithmic = prm.get("Spacing") == "logarithmic";
  prm.leave_subsection();
  prm.leave_subsection();

  // friction factor
  if (friction_model == "fully rough")
  {
    if (!(relative_roughness > 0 && relative_roughness < 1))
      fail("Relative roughness e_r/d must lie in (0, 1) (got " + number(relative_roughness) + ")");
    seal.friction_factor = fully_rough_friction_factor(relative_roughness);
  }

  // clearances: H from exactly one of Inlet clearance and Clearance ratio
  if (seal.geometry == Geometry::straight)
    seal.clearance_ratio = 1;
  else if (!c.optimise)
  {
    if (!inlet.empty() && !ratio.empty())
      fail("give either Inlet clearance or Clearance ratio, not both (leave one empty)");
    if (inlet.empty() && ratio.empty())
      fail("a " + to_string(seal.geometry) + " seal needs Inlet clearance or Clearance ratio");
    if (!inlet.empty())
    {
      const double C1 = parse_number("Inlet clearance", inlet);
      if (!(C1 > 0))
        fail("Inlet clearance must be a positive number (got " + number(C1) + ")");
      if (!(seal.outlet_clearance > 0))
        fail("Outlet clearance must be a positive number (got " + number(seal.outlet_clearance) +
             ")");
      if (C1 < seal.outlet_clearance)
        fail("Inlet clearance (" + number(C1) + " m) must not be smaller than Outlet clearance (" +
             number(seal.outlet_clearance) + " m): clearance ratio H = C1/C2 < 1");
      seal.clearance_ratio = C1 / seal.outlet_clearance;
    }
    else
      seal.clearance_ratio = parse_number("Clearance ratio", ratio);
  }
  else
    seal.clearance_ratio = 1; // chosen by the optimiser

  if (c.optimise)
  {
    if (seal.geometry == Geometry::straight)
      fail("Optimise needs Geometry type = tapered or stepped (a straight seal has nothing to "
           "optimise)");
    seal.step_ratio = c.bounds.step_ratio_max; // placeholder inside (0, 1], chosen by the optimiser
  }
  if (!(c.bounds.step_ratio_max > c.bounds.step_ratio_min && c.bounds.step_ratio_max <= 1))
    fail("Step position upper bound must lie in (" + number(c.bounds.step_ratio_min) +
         ", 1] (got " + number(c.bounds.step_ratio_max) + ")");
  if (!(c.bounds.clearance_ratio_max > 1 && c.bounds.clearance_ratio_max <= 100))
    fail("Clearance ratio upper bound must lie in (1, 100] (got " +
         number(c.bounds.clearance_ratio_max) + ")");
  seal.validate();

  // Lambda sweep
  if (!values.empty())
  {
    for (const std::string &v : dealii::Utilities::split_string_list(values, ','))
      c.sweep_lambdas.push_back(parse_number("Lambda sweep: Values", v));
  }
  else if (n_lambda > 0)
  {
    if (!(lambda_min > 0) || !(lambda_max >= lambda_min))
      fail("Lambda sweep: need 0 < Minimum <= Maximum (got " + number(lambda_min) + ", " +
           number(lambda_max) + ")");
    for (int i = 0; i < n_lambda; ++i)
    {
      const double t = n_lambda == 1 ? 0.0 : static_cast<double>(i) / (n_lambda - 1);
      c.sweep_lambdas.push_back(logarithmic ? lambda_min * std::pow(lambda_max / lambda_min, t)
                                            : lambda_min + (lambda_max - lambda_min) * t);
    }
  }
  for (const double l : c.sweep_lambdas)
    if (!(l > 0))
      fail("Lambda sweep: every Lambda must be positive (got " + number(l) + ")");
  return c;
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory)
{
  AnnularCase c = parse_case(prm);
  AnnularSeal &seal = c.seal;
  namespace fs = std::filesystem;
  const fs::path out(output_directory);

  nlohmann::json summary;
  nlohmann::json optimisation = nullptr;
  if (c.optimise)
  {
    const Optimum opt = optimise(seal.dimensionless(), c.objective, c.bounds);
    seal.clearance_ratio = opt.clearance_ratio;
    seal.step_ratio = opt.step_ratio;
    optimisation = {{"objective", to_string(c.objective)},
                    {"clearance_ratio_upper_bound", c.bounds.clearance_ratio_max},
                    {"clearance_ratio_at_bound", opt.clearance_ratio_at_bound}};
    if (seal.geometry == Geometry::stepped)
    {
      optimisation["step_ratio_upper_bound"] = c.bounds.step_ratio_max;
      optimisation["step_ratio_at_bound"] = opt.step_ratio_at_bound;
    }
  }
  const AnnularResults r = evaluate(seal);
  AnnularSeal straight = seal;
  straight.geometry = Geometry::straight;
  const AnnularResults rs = evaluate(straight);

  // concentric pressure profile
  const std::string profile_name = "annular_pressure_profile.csv";
  {
    csv::Writer f({{"z", "m"},
                   {"clearance", "m"},
                   {"pressure", "Pa"},
                   {"velocity", "m/s"},
                   {"pressure_drop_fraction", csv::dimensionless}});
    const double unit_flow = r.leakage / (pi * seal.diameter);
    const double p0 = seal.outlet_pressure + seal.pressure_drop;
    for (const ProfilePoint &p : pressure_profile(seal.dimensionless(), c.profile_points))
    {
      const double h = p.clearance_ratio * seal.outlet_clearance;
      f.add_row({p.axial_ratio * seal.length, h, p0 - seal.pressure_drop * p.pressure_drop_fraction,
                 unit_flow / (seal.density * h), p.pressure_drop_fraction});
    }
    f.write(output_directory, profile_name);
  }

  // sweep of the optimum seals over Lambda, and its plot
  nlohmann::json sweep_file = nullptr, plot_file = nullptr, plot_command = nullptr;
  if (!c.sweep_lambdas.empty())
  {
    const std::string sweep_name = "annular_lambda_sweep.csv";
    const fs::path csv_path = out / sweep_name;
    {
      const std::string none = csv::dimensionless;
      csv::Writer f({{"lambda", none},
                     {"configuration", ""},
                     {"objective", ""},
                     {"step_ratio_upper_bound", none},
                     {"clearance_ratio", none},
                     {"step_ratio", none},
                     {"stiffness_dimensionless", none},
                     {"leakage_dimensionless", none},
                     {"stiffness_ratio_to_straight", none},
                     {"leakage_ratio_to_straight", none}});
      for (const SweepRow &row : lambda_sweep(c))
        f.add_row({row.lambda, row.configuration, row.objective, row.bound, row.H, row.gamma, row.K,
                   row.M, row.K_ratio, row.M_ratio});
      f.write(output_directory, sweep_name);
    }
    sweep_file = sweep_name;
    const fs::path png = out / "annular_lambda_sweep.png";
    const PlotResult plot =
        run_plot_script("plot_annular.py", {csv_path.string(), png.string()}, png.string());
    plot_command = plot.command;
    if (plot.made)
      plot_file = png.filename().string();
    else
      report_skipped_plot("sealfe annular", plot);
  }

  const bool stepped = seal.geometry == Geometry::stepped;
  summary = {
      {"geometry_type", to_string(seal.geometry)},
      {"diameter", seal.diameter},
      {"length", seal.length},
      {"inlet_clearance", seal.inlet_clearance()},
      {"outlet_clearance", seal.outlet_clearance},
      {"clearance_ratio", seal.geometry == Geometry::straight ? 1.0 : seal.clearance_ratio},
      {"step_ratio", stepped ? nlohmann::json(seal.step_ratio) : nlohmann::json(nullptr)},
      {"friction_factor", seal.friction_factor},
      {"friction_exponent", seal.friction_exponent},
      {"lambda", seal.lambda()},
      {"entrance_loss_coefficient", seal.entrance_loss},
      {"density", seal.density},
      {"pressure_drop", seal.pressure_drop},
      {"inlet_pressure", seal.outlet_pressure + seal.pressure_drop},
      {"outlet_pressure", seal.outlet_pressure},
      {"stiffness", r.stiffness},
      {"stiffness_dimensionless", r.stiffness_dimensionless},
      {"leakage", r.leakage},
      {"leakage_dimensionless", r.leakage_dimensionless},
      {"leakage_volumetric", r.volumetric_leakage},
      {"reynolds_number", r.reynolds_number},
      {"straight_seal",
       {{"stiffness", rs.stiffness},
        {"stiffness_dimensionless", rs.stiffness_dimensionless},
        {"leakage", rs.leakage},
        {"leakage_dimensionless", rs.leakage_dimensionless}}},
      {"stiffness_ratio_to_straight", r.stiffness / rs.stiffness},
      {"leakage_ratio_to_straight", r.leakage / rs.leakage},
      {"optimisation", optimisation},
      {"files",
       {{"pressure_profile", profile_name}, {"lambda_sweep", sweep_file}, {"plot", plot_file}}},
      {"plot_command", plot_command}};
  return summary;
}

} // namespace sealfe::annular
