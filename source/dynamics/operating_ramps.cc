#include <sealfe/dynamics/operating_ramps.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
double Ramp::value(const double t) const
{
  if (t < 0 || t > t3)
    return rest;
  if (t < t1)
    return rest + (steady - rest) * t / t1;
  if (t <= t2)
    return steady;
  return rest + (steady - rest) * (t3 - t) / (t3 - t2);
}

double Ramp::rate(const double t) const
{
  if (t < 0 || t >= t3 || steady == rest)
    return 0;
  if (t < t1)
    return (steady - rest) / t1;
  if (t < t2)
    return 0;
  return -(steady - rest) / (t3 - t2);
}

std::vector<double> Ramp::corners() const
{
  std::vector<double> c;
  if (steady == rest)
    return c;
  for (const double t : {t1, t2, t3})
    if (t > 0 && std::isfinite(t) && t < 1e299)
      c.push_back(t);
  return c;
}

double Ramp::integral(const double t) const
{
  // Int_0^t of value(): rest * t plus the trapezoid's part (closed form per piece)
  const double d = steady - rest;
  double s = rest * std::max(t, 0.0);
  if (t <= 0)
    return 0;
  const double a = std::min(t, t1);
  if (t1 > 0)
    s += d * a * a / (2 * t1);
  if (t > t1)
    s += d * (std::min(t, t2) - t1);
  if (t > t2 && t3 > t2)
  {
    const double b = std::min(t, t3);
    // Int_t2^b (t3 - s)/(t3 - t2) ds
    s += d * ((t3 - t2) * (t3 - t2) - (t3 - b) * (t3 - b)) / (2 * (t3 - t2));
  }
  return s;
}

void Ramp::validate(const std::string &what) const
{
  std::ostringstream s;
  if (!std::isfinite(rest) || !std::isfinite(steady))
    s << "Ramps: " << what << " values must be finite";
  else if (!(t1 >= 0 && t1 <= t2 && t2 <= t3))
    s << "Ramps: " << what << " times must satisfy 0 <= t1 <= t2 <= t3 (got t1 = " << t1
      << ", t2 = " << t2 << ", t3 = " << t3 << " s)";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

namespace
{
const char *names[] = {"Speed", "Outer pressure", "Inner pressure"};
}

void OperatingRamps::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  const OperatingRamps d;
  const Ramp *ramps[] = {&d.speed, &d.outer_pressure, &d.inner_pressure};
  const char *units[] = {"rad/s", "Pa", "Pa"};
  prm.enter_subsection("Ramps");
  for (int i = 0; i < 3; ++i)
  {
    const std::string n = names[i];
    auto str = [](double v)
    {
      std::ostringstream s;
      s << v;
      return s.str();
    };
    prm.declare_entry(n + " rest value", str(ramps[i]->rest), Double(),
                      n + " (" + units[i] +
                          ") before t = 0 and after t3 (Green 2002 Eq. 17 "
                          "has 0; a pressure drop ramped from zero is rest = the other pressure).");
    prm.declare_entry(n + " steady value", str(ramps[i]->steady), Double(),
                      n + " (" + units[i] + ") between t1 and t2 (V of Eq. 17).");
    prm.declare_entry(n + " t1", str(ramps[i]->t1), Double(0), "End of the ramp up (s).");
    prm.declare_entry(n + " t2", str(ramps[i]->t2), Double(0), "Start of the ramp down (s).");
    prm.declare_entry(n + " t3", str(ramps[i]->t3), Double(0),
                      "End of the ramp down (s); 1e300: held after t2.");
  }
  prm.leave_subsection();
}

void OperatingRamps::parse_parameters(dealii::ParameterHandler &prm)
{
  Ramp *ramps[] = {&speed, &outer_pressure, &inner_pressure};
  prm.enter_subsection("Ramps");
  for (int i = 0; i < 3; ++i)
  {
    const std::string n = names[i];
    ramps[i]->rest = prm.get_double(n + " rest value");
    ramps[i]->steady = prm.get_double(n + " steady value");
    ramps[i]->t1 = prm.get_double(n + " t1");
    ramps[i]->t2 = prm.get_double(n + " t2");
    ramps[i]->t3 = prm.get_double(n + " t3");
  }
  prm.leave_subsection();
}

void OperatingRamps::validate() const
{
  speed.validate("Speed");
  outer_pressure.validate("Outer pressure");
  inner_pressure.validate("Inner pressure");
}

std::vector<double> OperatingRamps::corners() const
{
  std::vector<double> c;
  for (const Ramp *r : {&speed, &outer_pressure, &inner_pressure})
    for (const double t : r->corners())
      c.push_back(t);
  std::sort(c.begin(), c.end());
  c.erase(std::unique(c.begin(), c.end()), c.end());
  return c;
}
} // namespace sealfe
