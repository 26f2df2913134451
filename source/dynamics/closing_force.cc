#include <sealfe/dynamics/closing_force.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
void ClosingForce::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Closing force");
  prm.declare_entry("Balance ratio", "0.75", Double(),
                    "B in (0, 1] of Green 2002 Eq. 22: the fraction of the face area on which "
                    "the higher of the two sealed pressures closes the seal (the lower one acts "
                    "on 1 - B).");
  prm.declare_entry("Spring force", "20", Double(), "Spring preset F_spr (N), >= 0.");
  prm.leave_subsection();
}

void ClosingForce::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Closing force");
  balance_ratio = prm.get_double("Balance ratio");
  spring_force = prm.get_double("Spring force");
  prm.leave_subsection();
}

void ClosingForce::validate() const
{
  std::ostringstream s;
  if (!(balance_ratio > 0 && balance_ratio <= 1))
    s << "Closing force: Balance ratio must be in (0, 1], got " << balance_ratio;
  else if (!(spring_force >= 0) || !std::isfinite(spring_force))
    s << "Closing force: Spring force must be finite and >= 0, got " << spring_force << " N";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

double ClosingForce::value(const double ri, const double ro, const double pi_,
                           const double po) const
{
  const double high = std::max(pi_, po), low = std::min(pi_, po);
  return M_PI * (ro * ro - ri * ri) * (balance_ratio * high + (1 - balance_ratio) * low) +
         spring_force;
}
} // namespace sealfe
