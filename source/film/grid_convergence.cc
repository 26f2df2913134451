#include <sealfe/film/grid_convergence.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sealfe
{
namespace
{
std::string number(const double x)
{
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}
} // namespace

nlohmann::json GridConvergence::to_json() const
{
  nlohmann::json j = {{"estimate", estimate},
                      {"asymptotic", asymptotic},
                      {"expected_order", expected_order},
                      {"order_used", order_used},
                      {"convergence", convergence},
                      {"two_mesh_estimate", two_mesh_estimate},
                      {"safety_factor", safety_factor},
                      {"reason", reason}};
  j["observed_order"] = std::isfinite(observed_order) ? nlohmann::json(observed_order) : nullptr;
  return j;
}

bool deserves_warning(const GridConvergence &verdict, const double scale)
{
  // Faster than expected: the estimate at the expected order with Fs = 3 is conservative.
  const bool faster =
      verdict.convergence == "non-asymptotic" && verdict.observed_order > verdict.expected_order;
  // The earlier two-mesh figure (order k) still above the widened GCI: the data do not
  // contradict it (e.g. observed 3.4 where 2k = 4 is expected); a missing third mesh always counts.
  const bool widened =
      verdict.convergence == "two-mesh" || verdict.estimate > verdict.two_mesh_estimate;
  return !verdict.asymptotic && !faster && widened && verdict.estimate > 1e-3 * scale;
}

double expected_load_order(const unsigned int degree, const bool cavitating)
{
  return cavitating ? 1.0 : 2.0 * degree;
}

GridConvergence grid_convergence(const double fine, const double coarse,
                                 const std::optional<double> coarsest, const double expected_order,
                                 const double two_mesh_estimate, const double noise,
                                 const std::string &why_two_mesh)
{
  GridConvergence g;
  g.expected_order = expected_order;
  g.two_mesh_estimate = two_mesh_estimate;
  const double e21 = fine - coarse;
  auto gci = [&](double Fs, double p, double difference)
  {
    g.safety_factor = Fs;
    g.order_used = p;
    return Fs * std::abs(difference) / (std::pow(2.0, p) - 1);
  };
  double estimate = 0;
  if (!coarsest)
  {
    g.convergence = "two-mesh";
    estimate = gci(3, expected_order, e21);
    g.reason = "no third mesh (" + why_two_mesh + "): the observed order is unknown, Fs = 3 at " +
               "the expected order " + number(expected_order);
  }
  else
  {
    const double e32 = coarse - *coarsest;
    const bool small21 = std::abs(e21) <= noise, small32 = std::abs(e32) <= noise;
    if (small21 && small32)
    {
      g.convergence = "round-off";
      g.asymptotic = true;
      g.safety_factor = 1;
      g.order_used = expected_order;
      g.reason = "the three meshes agree to round-off";
    }
    else if (small21 || small32 || (e21 > 0) != (e32 > 0))
    {
      // The differences change sign (or one vanishes by accident): the error is not a power of
      // h on these meshes; bound it by the larger difference at the lowest credible order.
      g.convergence = "non-monotone";
      g.observed_order = small21 || small32 ? std::numeric_limits<double>::quiet_NaN()
                                            : std::log2(std::abs(e32) / std::abs(e21));
      estimate = gci(3, 0.5, std::max(std::abs(e21), std::abs(e32)));
      g.reason = std::string(small21 || small32 ? "one difference between the meshes is at "
                                                  "round-off and the other is not"
                                                : "the differences between the meshes change "
                                                  "sign") +
                 " (q_h - q_2h = " + number(e21) + ", q_2h - q_4h = " + number(e32) +
                 "): 3 x the larger one at order 0.5";
    }
    else
    {
      const double p = std::log2(std::abs(e32) / std::abs(e21));
      g.observed_order = p;
      g.asymptotic = std::abs(p - expected_order) <= 0.1 * expected_order;
      if (g.asymptotic)
      {
        g.convergence = "asymptotic";
        estimate = gci(1.25, expected_order, e21);
        g.reason = "observed order " + number(p) + " within 10 % of the expected " +
                   number(expected_order) + ": Fs = 1.25";
      }
      else
      {
        g.convergence = "non-asymptotic";
        estimate = gci(3, std::clamp(p, 0.5, expected_order), e21);
        g.reason = "observed order " + number(p) + " departs from the expected " +
                   number(expected_order) + " by more than 10 %: Fs = 3 at order " +
                   number(g.order_used) +
                   (p > expected_order ? " (faster than expected: conservative)"
                                       : " (slower than expected: the error may be larger)");
      }
    }
  }
  g.estimate = std::max(estimate, two_mesh_estimate);
  return g;
}

} // namespace sealfe
