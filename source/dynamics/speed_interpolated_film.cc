#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/dynamics/speed_interpolated_film.h>
#include <sealfe/numerics/lagrange_interpolation.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
SpeedInterpolatedFilm::SpeedInterpolatedFilm(FilmModel exact,
                                             const AngularSealDynamics::SweptRing swept,
                                             const double fixed_speed, const double from,
                                             const double to, const unsigned int n_nodes)
    : state(std::make_shared<State>())
{
  if (!(to > from) || !std::isfinite(from) || !std::isfinite(to) || n_nodes < 2)
    throw std::runtime_error("Seal dynamics: the speed interpolation of the film needs 'to' > "
                             "'from' and at least 2 nodes");
  state->exact = std::move(exact);
  state->swept = swept;
  state->fixed = fixed_speed;
  state->from = from;
  state->to = to;
  state->n = n_nodes;
  state->nodes.resize(n_nodes);
}

std::vector<double> SpeedInterpolatedFilm::node_speeds() const
{
  std::vector<double> w(state->n);
  for (unsigned int i = 0; i < state->n; ++i)
    w[i] = (i + 1 == state->n) ? state->to
                               : state->from + (state->to - state->from) * i / (state->n - 1);
  return w;
}

bool SpeedInterpolatedFilm::on_line(const double rotor_speed, const double stator_speed,
                                    double &swept_speed) const
{
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  const double other = swept_rotor ? stator_speed : rotor_speed;
  swept_speed = swept_rotor ? rotor_speed : stator_speed;
  const double slack = 1e-12 * (state->to - state->from);
  return other == state->fixed && swept_speed >= state->from - slack &&
         swept_speed <= state->to + slack;
}

FilmCoefficients SpeedInterpolatedFilm::node(const unsigned int i) const
{
  if (!state->nodes[i])
  {
    const double w = node_speeds()[i];
    const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
    state->nodes[i] = std::make_unique<FilmCoefficients>(
        state->exact(swept_rotor ? w : state->fixed, swept_rotor ? state->fixed : w));
    ++state->evaluations;
  }
  return *state->nodes[i];
}

FilmCoefficients SpeedInterpolatedFilm::interpolate(const double swept_speed) const
{
  const std::vector<double> v = node_speeds();
  const double x = std::clamp(swept_speed, v.front(), v.back());
  // cubic Lagrange on the 4 nodes around x (as the coefficient table per axis)
  const LagrangeStencil stencil = lagrange_stencil(v, x, 4);
  FilmCoefficients result;
  bool have = false;
  for (unsigned int m = 0; m < stencil.weights.size(); ++m)
  {
    const double weight = stencil.weights[m];
    const FilmCoefficients c = node(stencil.first + m);
    if (!have)
    {
      result = c; // level, model
      for (auto *mat : {&result.stiffness, &result.damping})
        for (auto &row : *mat)
          row.fill(0.0);
      have = true;
    }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        result.stiffness[i][j] += weight * c.stiffness[i][j];
        result.damping[i][j] += weight * c.damping[i][j];
      }
  }
  return result;
}

FilmCoefficients SpeedInterpolatedFilm::operator()(const double rotor_speed,
                                                   const double stator_speed) const
{
  double w;
  if (!on_line(rotor_speed, stator_speed, w))
  {
    return state->off_line.get({rotor_speed, stator_speed},
                               [&]
                               {
                                 ++state->evaluations;
                                 return state->exact(rotor_speed, stator_speed);
                               });
  }
  FilmCoefficients c = interpolate(w);
  c.rotor_speed = rotor_speed;
  c.stator_speed = stator_speed;
  return c;
}

SpeedInterpolatedFilm::Check SpeedInterpolatedFilm::check(const double swept_speed,
                                                          const double outer_radius) const
{
  const std::vector<double> v = node_speeds();
  const unsigned int k = lagrange_interval(v, std::clamp(swept_speed, v.front(), v.back()));
  Check c;
  c.speed = 0.5 * (v[k] + v[k + 1]);
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  const double wr = swept_rotor ? c.speed : state->fixed, ws = swept_rotor ? state->fixed : c.speed;
  const FilmCoefficients reference = state->exact(wr, ws);
  ++state->evaluations;
  const CoefficientTable::Error e =
      CoefficientTable::compare((*this)(wr, ws), reference, outer_radius);
  c.stiffness = e.stiffness;
  c.damping = e.damping;
  return c;
}

nlohmann::json SpeedInterpolatedFilm::check_report(const std::vector<double> &swept_speeds,
                                                   const double outer_radius) const
{
  nlohmann::json checks = nlohmann::json::array();
  std::vector<double> done;
  double worst_k = 0, worst_d = 0;
  for (const double w : swept_speeds)
  {
    const Check c = check(w, outer_radius);
    if (std::find(done.begin(), done.end(), c.speed) != done.end())
      continue;
    done.push_back(c.speed);
    checks.push_back(
        {{"swept_speed", c.speed}, {"stiffness_error", c.stiffness}, {"damping_error", c.damping}});
    worst_k = std::max(worst_k, c.stiffness);
    worst_d = std::max(worst_d, c.damping);
  }
  return {{"checks", checks},
          {"max_stiffness_error", worst_k},
          {"max_damping_error", worst_d},
          {"definition", "interpolated against computed coefficients midway between the two nodes "
                         "around each speed of interest: max_ij |K~ - K| / max_ij |K| of diag(1, "
                         "1/ro, 1/ro) K diag(1, 1/ro, 1/ro); the same for D"}};
}

nlohmann::json SpeedInterpolatedFilm::to_json() const
{
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  std::ostringstream m;
  m << "finite element (level 2) at " << state->n << " equally spaced "
    << (swept_rotor ? "rotor" : "stator") << " speeds over [" << state->from << ", " << state->to
    << "] rad/s (other ring at " << state->fixed << " rad/s), "
    << (state->n == 2   ? "linear"
        : state->n == 3 ? "quadratic"
                        : "cubic")
    << " Lagrange interpolation in between (exact in full film: K affine in the mean speed, D "
       "independent of it); an FE computation at any other speed pair";
  return {{"method", m.str()},
          {"swept_speed", swept_rotor ? "rotor" : "stator"},
          {"fixed_speed", state->fixed},
          {"node_speeds", node_speeds()},
          {"nodes", state->n}};
}

} // namespace sealfe
