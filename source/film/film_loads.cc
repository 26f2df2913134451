#include <sealfe/film/film_loads.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/surface_features.h>

#include <sealfe/numerics/ordered_batches.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>

namespace sealfe
{
namespace
{
/// d(dh/dt) of a perturbation in the frame of the solve: its own rate, plus, when the equation
/// is solved in the frame of a rotating textured face (reynolds_solver.cc, local_film), the
/// motion of the perturbed film relative to that frame, w_F d(dh)/dtheta (centred difference).
double perturbation_squeeze(const FilmPerturbation &p, const double r, const double theta,
                            const double w_frame)
{
  double dh_t = p.dh_dt ? p.dh_dt(r, theta) : 0.0;
  if (w_frame != 0 && p.dh)
  {
    const double step = 1e-6;
    dh_t += w_frame * (p.dh(r, theta + step) - p.dh(r, theta - step)) / (2 * step);
  }
  return dh_t;
}
/// The weights of force_z, moment_x and moment_y in the pressure at x (doc/coefficients.md: F_z =
/// int p dA, M_x = int p y dA, M_y = -int p x dA): one definition for the loads
/// (add_pressure_loads) and the adjoint's load functionals (generalized_force_functionals).
std::array<double, 3> generalized_force_weights(const dealii::Point<2> &x)
{
  return {{1.0, x[1], -x[0]}};
}

} // namespace

nlohmann::json FilmLoads::to_json() const
{
  return {{"force_z", force_z},
          {"moment_x", moment_x},
          {"moment_y", moment_y},
          {"moment_restoring", moment_restoring},
          {"moment_transverse", moment_transverse},
          {"leakage_inner", leakage_inner},
          {"leakage_outer", leakage_outer},
          {"friction_torque", friction_torque},
          {"min_film", min_film},
          {"max_pressure", max_pressure},
          {"min_pressure", min_pressure},
          {"cavitated_fraction", cavitated_fraction},
          {"area", area},
          {"squeeze_flow", squeeze_flow},
          {"contact_force", contact_force},
          {"contact_moment_x", contact_moment_x},
          {"contact_moment_y", contact_moment_y},
          {"contact_area_fraction", contact_area_fraction},
          {"min_film_over_sigma", std::isfinite(min_film_over_sigma)
                                      ? nlohmann::json(min_film_over_sigma)
                                      : nlohmann::json(nullptr)}};
}

// ------------------------------------------------------------------------------------------------
// LoadIntegrator

using namespace dealii;

/// The solved state at one quadrature point.
struct LoadIntegrator::PointState
{
  Point<2> x;
  ReynoldsSolver::LocalFilm f;
  double JxW, p, v, indicator, tau;
  Tensor<1, 2> grad_p, grad_v;
};

/// One perturbation direction at one quadrature point (direction == nullptr: the solved state).
struct LoadIntegrator::PointPerturbation
{
  const FilmPerturbation *direction = nullptr;
  double dh = 0, dh_t = 0, dp = 0, dv = 0;
  Tensor<1, 2> grad_dp, grad_dv;
};

LoadIntegrator::LoadIntegrator(const ReynoldsSolver &solver)
    : solver(solver), clip(solver.cavitation.model == Cavitation::half_sommerfeld),
      jfo(solver.cavitation.model == Cavitation::jfo), p_cav(solver.cavitation.pressure),
      p_ref(solver.conditions.reference_pressure), cos_psi(std::cos(solver.film.tilt_angle)),
      sin_psi(std::sin(solver.film.tilt_angle)), mu(solver.conditions.viscosity)
{
}

FilmLoads LoadIntegrator::loads() const
{
  if (uses_assembled_sums())
    return affine_loads();
  return integrate({nullptr}, {}, {})[0];
}

bool LoadIntegrator::uses_assembled_sums() const
{
  return affine_applies() && solver.affine_loads.valid;
}

bool LoadIntegrator::affine_applies() const
{
  // half-Sommerfeld clips p in the loads; reynolds and jfo are nonlinear. Rough faces keep the
  // point-by-point integration, so that the run's count of flow-factor evaluations held at their
  // validity limit (summary.json; reset at each run) includes the loads' pass as before.
  return solver.cavitation.model == Cavitation::none && solver.flow_factors.is_smooth();
}

LoadIntegrator::VectorType LoadIntegrator::cavitation_indicator() const
{
  // Below this the film counts as cavitated (pressure at p_cav, or void fraction above zero).
  const double p_tol = 1e-9 * std::max(solver.pressure_scale, 1.0);
  VectorType owned(solver.locally_owned_dofs, solver.mpi_communicator);
  for (const auto i : solver.locally_owned_dofs)
    owned[i] = (jfo ? solver.locally_relevant_void[i] > 0
                    : solver.locally_relevant_solution[i] <= p_cav + p_tol)
                   ? 1.0
                   : 0.0;
  owned.compress(VectorOperation::insert);
  VectorType indicator(solver.locally_owned_dofs, solver.locally_relevant_dofs,
                       solver.mpi_communicator);
  indicator = owned;
  return indicator;
}

// Sums: 0 F, 1 Mx, 2 My, 3 Mr, 4 Mt, 5 residual inner, 6 residual outer, 7 friction, 8 area,
// 9 cavitated area, 10 squeeze flow, 11 contact force, 12 contact Mx, 13 contact My, 14 real
// contact area, 15 undershoot force int min(p - p_cav, 0) dA.
constexpr unsigned int n_sums = 16;

void AffineLoadSums::reset(const bool gather, const std::size_t n_relevant_dofs,
                           const unsigned int dofs_per_cell)
{
  valid = false; // until the assembly loop has finished (ReynoldsSolver::assemble_system)
  if (!gather)
  {
    // release the memory (the weights are 6 doubles a dof)
    std::vector<double>().swap(constant);
    std::vector<double>().swap(weight);
    std::vector<double>().swap(cell_weight);
    return;
  }
  constant.assign(n_sums, 0.0);
  weight.assign(n_linear * n_relevant_dofs, 0.0);
  cell_weight.assign(n_linear * dofs_per_cell, 0.0);
}

void AffineLoadSums::add_cell(const std::vector<unsigned int> &relevant_index)
{
  for (unsigned int i = 0; i < relevant_index.size(); ++i)
    for (unsigned int m = 0; m < n_linear; ++m)
    {
      weight[std::size_t(n_linear) * relevant_index[i] + m] += cell_weight[n_linear * i + m];
      cell_weight[n_linear * i + m] = 0;
    }
}

template <typename Values, typename Film>
void LoadIntegrator::add_affine_point(AffineLoadSums &sums, const Values &fe_values,
                                      const unsigned int q, const Film &f) const
{
  // The sums at p = p_ref (uniform: zero gradient) by the same point functions as integrate(),
  // so that the pressure parts of the force and moments vanish here and affine_loads() dots the
  // weights with p - p_ref: no cancellation of sum w_j p_j against p_ref A when p_ref is near
  // the boundary pressures (exact: the shape functions sum to one, their gradients to zero).
  PointState x;
  x.x = fe_values.quadrature_point(q);
  x.f = f;
  x.JxW = fe_values.JxW(q);
  x.p = p_ref;
  x.v = x.indicator = x.tau = 0;
  const PointPerturbation none;
  add_pressure_loads(x, none, sums.constant);
  add_friction_and_squeeze(x, none, sums.constant);
  // and their slopes in p: load_p = p - p_ref + contact_p in the force and moments
  // (add_pressure_loads, not clipped in a full film); the Poiseuille part of the friction,
  // -tau_p(h, dp/dx) r with tau_p linear in dp/dx = dp/dtheta / r (add_friction_and_squeeze).
  const double X = x.x[0], Y = x.x[1], JxW = x.JxW;
  const double w[5] = {JxW, Y * JxW, -X * JxW, -(X * cos_psi + Y * sin_psi) * JxW,
                       (Y * cos_psi - X * sin_psi) * JxW};
  const double friction =
      -solver.flow_factors.rotor_shear_stress(std::max(f.h, 1e-300), mu, 0.0, 0.0, 1.0) *
      friction_face() * JxW;
  const unsigned int n = fe_values.get_fe().n_dofs_per_cell();
  double *cell_weight = sums.cell_weight.data();
  // r e_theta . grad phi is the same in the frame of a polar row's first cell (PolarCellValues:
  // its gradients need not be turned)
  constexpr bool polar = std::is_same_v<Values, PolarCellValues>;
  Point<2> xg = x.x;
  if constexpr (polar)
    xg = fe_values.reference_point(q);
  for (unsigned int i = 0; i < n; ++i, cell_weight += AffineLoadSums::n_linear)
  {
    const double phi = fe_values.shape_value(i, q);
    for (unsigned int m = 0; m < 5; ++m)
      cell_weight[m] += w[m] * phi;
    Tensor<1, 2> g;
    if constexpr (polar)
      g = fe_values.reference_shape_grad(i, q);
    else
      g = fe_values.shape_grad(i, q);
    cell_weight[5] += friction * (-xg[1] * g[0] + xg[0] * g[1]);
  }
}
template void LoadIntegrator::add_affine_point<FEValues<2>, ReynoldsSolver::LocalFilm>(
    AffineLoadSums &, const FEValues<2> &, unsigned int, const ReynoldsSolver::LocalFilm &) const;
template void LoadIntegrator::add_affine_point<PolarCellValues, ReynoldsSolver::LocalFilm>(
    AffineLoadSums &, const PolarCellValues &, unsigned int,
    const ReynoldsSolver::LocalFilm &) const;

std::vector<bool> LoadIntegrator::leakage_cells() const
{
  // vertices on a boundary face of an owned or ghost cell (the ghost layer holds every cell that
  // shares a vertex with an owned one), then the owned cells that touch one
  const auto &tria = solver.dof_handler.get_triangulation();
  std::vector<bool> boundary_vertex(tria.n_vertices(), false);
  for (const auto &cell : tria.active_cell_iterators())
    if (!cell->is_artificial() && cell->at_boundary())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          for (const unsigned int v : cell->face(f)->vertex_indices())
            boundary_vertex[cell->face(f)->vertex_index(v)] = true;
  std::vector<bool> leakage_cell(tria.n_active_cells(), false);
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->is_locally_owned())
      for (const unsigned int v : cell->vertex_indices())
        if (boundary_vertex[cell->vertex_index(v)])
          leakage_cell[cell->active_cell_index()] = true;
  return leakage_cell;
}

bool LoadIntegrator::polar_assembly() const
{
  // ReynoldsSolver::assemble_system (full film, also solved for half-Sommerfeld) and the cell
  // matrices of the JFO and reynolds systems (ReynoldsSolver::compute_cell_matrices) take the
  // values of PolarCellValues on the built-in annulus.
  return solver.assembles_on_polar_rows();
}

void LoadIntegrator::add_leakages(const std::vector<types::global_dof_index> &dofs,
                                  const Vector<double> &local_residual,
                                  std::vector<double> &sum) const
{
  for (unsigned int i = 0; i < dofs.size(); ++i)
  {
    if (solver.inner_boundary_dofs.is_element(dofs[i]))
      sum[5] += local_residual(i);
    if (solver.outer_boundary_dofs.is_element(dofs[i]))
      sum[6] += local_residual(i);
  }
}

double LoadIntegrator::friction_face() const
{
  // Surface features on the rotor: its face has step walls whose pressure the shear integral
  // misses. By the torque balance of the film the torque resisting the rotor is the one that
  // drags the smooth stator face, whose Poiseuille shear has the opposite sign.
  return solver.film.features && solver.film.features->face == SurfaceFeatures::Face::rotor ? -1.0
                                                                                            : 1.0;
}

FilmLoads LoadIntegrator::affine_loads() const
{
  const ReynoldsSolver &s = solver;
  const AffineLoadSums &a = s.affine_loads;
  std::vector<double> sums = a.constant;
  std::vector<double> p(s.locally_relevant_dofs.n_elements());
  {
    std::size_t k = 0;
    for (const auto i : s.locally_relevant_dofs)
      p[k++] = s.locally_relevant_solution[i];
  }
  double linear[AffineLoadSums::n_linear] = {};
  for (std::size_t k = 0; k < p.size(); ++k)
    for (unsigned int m = 0; m < AffineLoadSums::n_linear; ++m)
      linear[m] += a.weight[AffineLoadSums::n_linear * k + m] * (p[k] - p_ref);
  for (unsigned int m = 0; m < AffineLoadSums::n_linear; ++m)
    sums[AffineLoadSums::linear_sums[m]] += linear[m];

  // Leakages: the residual in the cells with a vertex on a circle (as in integrate()); the
  // pressure range at the quadrature points of every cell (the same sums as
  // FEValues::get_function_values: the values of FE_Q's shape functions do not depend on the
  // cell) and at the nodes.
  const QGauss<2> quadrature(s.polynomial_degree + 2);
  FEValues<2> fe_values(*s.mapping, *s.fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), dofs_per_cell = s.fe->n_dofs_per_cell();
  FullMatrix<double> shape(dofs_per_cell, n_q);
  for (unsigned int i = 0; i < dofs_per_cell; ++i)
    for (unsigned int q = 0; q < n_q; ++q)
      shape(i, q) = s.fe->shape_value(i, quadrature.point(q));
  const std::vector<bool> leakage_cell = leakage_cells();
  std::optional<PolarCellValues> polar;
  if (polar_assembly())
    polar.emplace(*s.mapping, *s.fe, quadrature);
  std::vector<double> p_q(n_q);
  std::vector<Tensor<1, 2>> grad_p(n_q), shape_grad(dofs_per_cell);
  std::vector<double> shape_value(dofs_per_cell);
  std::vector<types::global_dof_index> dofs(dofs_per_cell);
  Vector<double> cell_p(dofs_per_cell), local_residual(dofs_per_cell);
  double p_min = std::numeric_limits<double>::max(), p_max = -p_min, p_min_nodal = p_min;
  for (const auto &cell : s.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        cell_p(i) = p[s.locally_relevant_dofs.index_within_set(dofs[i])];
      std::fill(p_q.begin(), p_q.end(), 0.0);
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        for (unsigned int q = 0; q < n_q; ++q)
          p_q[q] += cell_p(i) * shape(i, q);
      for (unsigned int q = 0; q < n_q; ++q)
      {
        p_min = std::min(p_min, p_q[q]);
        p_max = std::max(p_max, p_q[q]);
      }
      if (!leakage_cell[cell->active_cell_index()])
        continue;
      // the values the assembly took for this cell (see polar_assembly)
      const bool turned = polar && polar->reinit(cell);
      if (turned)
        polar->get_function_gradients(cell_p, grad_p);
      else
      {
        fe_values.reinit(cell);
        fe_values.get_function_gradients(s.locally_relevant_solution, grad_p);
      }
      local_residual = 0;
      PointState x;
      x.v = x.indicator = x.tau = 0;
      const PointPerturbation none;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        x.x = turned ? polar->quadrature_point(q) : fe_values.quadrature_point(q);
        // the film the assembly took there (film_matrices: the row's radius and angle)
        x.f = turned ? s.local_film(x.x, polar->radius(q), polar->angle(q), cos_psi, sin_psi)
                     : s.local_film(x.x);
        x.JxW = turned ? polar->JxW(q) : fe_values.JxW(q);
        x.p = p_q[q];
        x.grad_p = grad_p[q];
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          shape_grad[i] = turned ? polar->shape_grad(i, q) : fe_values.shape_grad(i, q);
          shape_value[i] = turned ? polar->shape_value(i, q) : fe_values.shape_value(i, q);
        }
        add_residual(x, none, shape_grad, shape_value, local_residual);
      }
      add_leakages(dofs, local_residual, sums);
    }
  for (const auto i : s.locally_owned_dofs)
  {
    p_min_nodal = std::min(p_min_nodal, s.locally_relevant_solution[i]);
    p_max = std::max(p_max, s.locally_relevant_solution[i]);
  }
  p_min = std::min(p_min, p_min_nodal);
  return finish(sums, true, p_min, p_max, p_min_nodal);
}

void LoadIntegrator::add_pressure_loads(const PointState &x, const PointPerturbation &d,
                                        std::vector<double> &sum) const
{
  // Pressure in the loads: half-Sommerfeld clips it (and freezes the clipped region in the
  // linearisation); the other models use the solved field. The asperity contact pressure (zero
  // without a contact model) adds to it.
  const ReynoldsSolver::LocalFilm &f = x.f;
  const bool perturbed = d.direction != nullptr;
  const double JxW = x.JxW, X = x.x[0], Y = x.x[1];
  const bool clipped = clip && x.p < p_cav;
  const double contact_p = perturbed ? f.dcontact_dh * d.dh : f.contact_pressure;
  const double load_p =
      (perturbed ? (clipped ? 0.0 : d.dp) : (clipped ? p_cav : x.p) - p_ref) + contact_p;
  const std::array<double, 3> weight = generalized_force_weights(x.x);
  for (unsigned int i = 0; i < 3; ++i)
    sum[i] += load_p * weight[i] * JxW;
  sum[3] += -load_p * (X * cos_psi + Y * sin_psi) * JxW;
  sum[4] += load_p * (Y * cos_psi - X * sin_psi) * JxW;
  sum[8] += JxW;
  sum[11] += contact_p * JxW;
  sum[12] += contact_p * Y * JxW;
  sum[13] += -contact_p * X * JxW;
  if (!perturbed && solver.contact.enabled())
    sum[14] += solver.contact.real_contact_area_fraction(f.h) * JxW;
  // Cavitated area: half-Sommerfeld where the clipped pressure applies; reynolds and jfo where
  // the interpolated nodal cavitation indicator is at least 1/2 (nodal, so that the overshoot of
  // higher-order interpolants at the cavity edge does not count).
  if (clipped || (solver.cavitation.is_nonlinear() && x.indicator >= 0.5))
    sum[9] += JxW;
}

void LoadIntegrator::add_friction_and_squeeze(const PointState &x, const PointPerturbation &d,
                                              std::vector<double> &sum) const
{
  // Shear on the rotor face, as a torque resisting the rotor, -r tau_1: Couette part (carried by
  // the liquid fraction) and Poiseuille part; with roughness the Patir-Cheng shear-stress factors
  // (FlowFactors::rotor_shear_stress).
  const ReynoldsSolver::LocalFilm &f = x.f;
  const double r = f.r, h = f.h, JxW = x.JxW;
  const double liquid = 1 - x.v;
  const double face = friction_face(); // the face the shear is integrated on (see there)
  const double dp_dtheta = face * (-x.x[1] * x.grad_p[0] + x.x[0] * x.grad_p[1]);
  const double liquid_clamped = std::clamp(liquid, 0.0, 1.0);
  const double u1 = solver.conditions.rotor_speed * r, u2 = solver.conditions.stator_speed * r;
  const FlowFactors &flow = solver.flow_factors;
  auto couette = [&](double hh)
  { return -flow.rotor_shear_stress(std::max(hh, 1e-300), mu, u1, u2, 0.0) * r; };
  auto poiseuille = [&](double hh, double dpdx)
  { return -flow.rotor_shear_stress(std::max(hh, 1e-300), mu, 0.0, 0.0, dpdx) * r; };
  if (!d.direction)
  {
    sum[7] += (liquid_clamped * couette(h) + poiseuille(h, dp_dtheta / r)) * JxW;
    sum[10] += liquid * f.squeeze * JxW;
  }
  else
  {
    const double ddp_dtheta = face * (-x.x[1] * d.grad_dp[0] + x.x[0] * d.grad_dp[1]);
    const double eps = 1e-7 * h;
    const double dcouette = (couette(h + eps) - couette(h - eps)) / (2 * eps);
    const double dpois =
        (poiseuille(h + eps, dp_dtheta / r) - poiseuille(h - eps, dp_dtheta / r)) / (2 * eps);
    sum[7] += (-d.dv * couette(h) + liquid * dcouette * d.dh + dpois * d.dh +
               poiseuille(h, ddp_dtheta / r)) *
              JxW;
    sum[10] += (-d.dv * f.squeeze + liquid * f.dsqueeze_dht * d.dh_t) * JxW;
  }
}

void LoadIntegrator::add_residual(const PointState &x, const PointPerturbation &d,
                                  const std::vector<Tensor<1, 2>> &shape_grad,
                                  const std::vector<double> &shape_value,
                                  Vector<double> &local_residual) const
{
  // Residual of the unconstrained weak form in m^3/s (its linearisation with a perturbation):
  //   R_i = int (K grad p - s c) . grad phi_i + s dh_T/dt phi_i - tau div(v c) (u . grad phi_i).
  const ReynoldsSolver::LocalFilm &f = x.f;
  const double liquid = 1 - x.v, tau = x.tau;
  Tensor<1, 2> flux;
  double volume, streamline;
  if (!d.direction)
  {
    flux = f.K * x.grad_p - liquid * f.c;
    volume = liquid * f.squeeze;
    streamline = -tau * (f.c * x.grad_v + x.v * f.c_div);
  }
  else
  {
    const double dh = d.dh;
    flux = f.K * d.grad_dp + dh * (f.dK_dh * x.grad_p) - (liquid * dh * f.dc_dh - d.dv * f.c);
    volume = liquid * f.dsqueeze_dht * d.dh_t - d.dv * f.squeeze;
    const double step = 1e-6;
    const FilmPerturbation &p = *d.direction;
    const double ddh_dtheta =
        p.dh ? (p.dh(f.r, f.theta + step) - p.dh(f.r, f.theta - step)) / (2 * step) : 0.0;
    // (second derivatives of the flow factors in h are neglected here)
    streamline = -tau * (f.c * d.grad_dv + d.dv * f.c_div + dh * (f.dc_dh * x.grad_v) +
                         x.v * f.dc_div_factor * ddh_dtheta);
  }
  for (unsigned int i = 0; i < local_residual.size(); ++i)
    local_residual(i) +=
        (flux * shape_grad[i] + volume * shape_value[i] + streamline * (f.u * shape_grad[i])) *
        x.JxW;
}

std::vector<FilmLoads>
LoadIntegrator::integrate(const std::vector<const FilmPerturbation *> &perturbations,
                          const std::vector<const VectorType *> &dp_nodal,
                          const std::vector<const VectorType *> &dv_nodal) const
{
  // One cell loop for the solved state (perturbations = {nullptr}) or for all perturbation
  // directions at once (the film data at each quadrature point are computed once).
  const ReynoldsSolver &s = solver;
  const unsigned int n_k = perturbations.size();
  const bool base = n_k == 1 && perturbations[0] == nullptr;
  const double w_frame =
      s.film.feature_frame_speed(s.conditions.rotor_speed, s.conditions.stator_speed);
  const QGauss<2> quadrature(s.polynomial_degree + 2); // the assembly's rule (see there)
  const unsigned int n_q = quadrature.size(), dofs_per_cell = s.fe->n_dofs_per_cell();
  const bool nonlinear = s.cavitation.is_nonlinear();
  const VectorType indicator_nodal = base && nonlinear ? cavitation_indicator() : VectorType();
  // reynolds and jfo keep the nodes at or above p_cav. The interpolant can dip below it only in
  // the cells at the cavity edge: some node or quadrature point within p_near of p_cav and some
  // node above it (in a cell whose nodes all sit at p_cav it stays there to round-off).
  const bool undershoot = base && nonlinear;
  const double p_near = p_cav + 1e-9 * std::max(s.pressure_scale, 1.0);
  const std::vector<bool> leakage_cell = leakage_cells();
  // the threads' lookups (add_leakages) in compressed sets: IndexSet::compress, which a lookup
  // calls, writes the set
  s.inner_boundary_dofs.compress();
  s.outer_boundary_dofs.compress();
  // Every cell with the values its system was assembled with (polar_assembly): in the cells on
  // the circles the leakages of the solved p are then its round-off, not the difference of two
  // cell geometries' round-off times the flow; and a polar row's cells take their values from the
  // row's first cell instead of a mapping of their own (0.82-0.89 s instead of 1.13-1.45 s for
  // the loads of the tilted seal's JFO solution at 1.05e6 unknowns, doc/performance.md "Session
  // 21"). The rows are found here, in the order of the cells, before the threads copy them.
  std::optional<PolarCellValues> polar_rows;
  if (polar_assembly())
    polar_rows.emplace(*s.mapping, *s.fe, quadrature);
  const std::vector<DoFHandler<2>::active_cell_iterator> cells =
      owned_cells_finding_rows(s.dof_handler, polar_rows);

  // The cells in chunks of a fixed size, each chunk's sums taken from zero in the order of its
  // cells on one of deal.II's threads, the chunks' sums then added in their order: the same bits
  // on any number of threads (the chunks do not depend on it), within the sums' round-off of one
  // loop over the cells.
  struct Chunk
  {
    std::vector<std::vector<double>> sums; // [k][m]
    double p_min = 0, p_max = 0;
    std::vector<DoFHandler<2>::active_cell_iterator> near_cavity; // in the order of the cells
  };
  // what a thread needs to evaluate its cells: values at the n_q points (p, v, the indicator and
  // the n_k perturbations'), the shapes and residuals of the n dofs
  struct Scratch
  {
    Scratch(const ReynoldsSolver &s, const Quadrature<2> &quadrature,
            const std::optional<PolarCellValues> &rows, const unsigned int n_k)
        : fe_values(*s.mapping, *s.fe, quadrature,
                    update_values | update_gradients | update_quadrature_points |
                        update_JxW_values),
          polar(rows), p(quadrature.size()), v(quadrature.size(), 0.0),
          indicator(quadrature.size(), 0.0), shape_value(s.fe->n_dofs_per_cell()),
          grad_p(quadrature.size()), grad_v(quadrature.size()), shape_grad(s.fe->n_dofs_per_cell()),
          dp_k(n_k, std::vector<double>(quadrature.size(), 0.0)), dv_k(dp_k),
          grad_dp_k(n_k, std::vector<Tensor<1, 2>>(quadrature.size())), grad_dv_k(grad_dp_k),
          dofs(s.fe->n_dofs_per_cell()), cell_p(s.fe->n_dofs_per_cell()),
          cell_d(s.fe->n_dofs_per_cell()),
          local_residual_k(n_k, Vector<double>(s.fe->n_dofs_per_cell()))
    {
    }
    FEValues<2> fe_values;
    std::optional<PolarCellValues> polar;
    std::vector<double> p, v, indicator, shape_value;
    std::vector<Tensor<1, 2>> grad_p, grad_v, shape_grad;
    std::vector<std::vector<double>> dp_k, dv_k;
    std::vector<std::vector<Tensor<1, 2>>> grad_dp_k, grad_dv_k;
    std::vector<types::global_dof_index> dofs;
    Vector<double> cell_p, cell_d;
    std::vector<Vector<double>> local_residual_k;
  };
  Threads::ThreadLocalStorage<std::unique_ptr<Scratch>> scratch;
  // the sums of the cells [first, last) of `cells` into `chunk`
  auto integrate_cells = [&](const std::size_t first, const std::size_t last, Chunk &chunk)
  {
    std::unique_ptr<Scratch> &own = scratch.get();
    if (!own)
      own = std::make_unique<Scratch>(s, quadrature, polar_rows, n_k);
    Scratch &w = *own;
    FEValues<2> &fe_values = w.fe_values;
    std::optional<PolarCellValues> &polar = w.polar;
    std::vector<std::vector<double>> &sums = chunk.sums;
    sums.assign(n_k, std::vector<double>(n_sums, 0.0));
    chunk.near_cavity.clear();
    double p_min = std::numeric_limits<double>::max(), p_max = -p_min;
    // values and gradients at the quadrature points of a nodal vector in the current cell
    auto evaluate = [&](const bool turned, const auto &cell, const VectorType &nodal,
                        std::vector<double> &values, std::vector<Tensor<1, 2>> *gradients)
    {
      if (turned)
      {
        cell->get_dof_values(nodal, w.cell_d);
        polar->get_function_values(w.cell_d, values);
        if (gradients)
          polar->get_function_gradients(w.cell_d, *gradients);
      }
      else
      {
        fe_values.get_function_values(nodal, values);
        if (gradients)
          fe_values.get_function_gradients(nodal, *gradients);
      }
    };
    for (std::size_t c = first; c < last; ++c)
    {
      const auto &cell = cells[c];
      const bool turned = polar && polar->reinit(cell);
      if (!turned)
        fe_values.reinit(cell);
      evaluate(turned, cell, s.locally_relevant_solution, w.p, &w.grad_p);
      if (jfo)
        evaluate(turned, cell, s.locally_relevant_void, w.v, &w.grad_v);
      for (unsigned int k = 0; k < n_k; ++k)
      {
        if (k < dp_nodal.size() && dp_nodal[k])
          evaluate(turned, cell, *dp_nodal[k], w.dp_k[k], &w.grad_dp_k[k]);
        if (k < dv_nodal.size() && dv_nodal[k])
          evaluate(turned, cell, *dv_nodal[k], w.dv_k[k], &w.grad_dv_k[k]);
        w.local_residual_k[k] = 0;
      }
      if (base && nonlinear)
        evaluate(turned, cell, indicator_nodal, w.indicator, nullptr);
      auto JxW = [&](const unsigned int q) { return turned ? polar->JxW(q) : fe_values.JxW(q); };
      if (undershoot)
      {
        cell->get_dof_values(s.locally_relevant_solution, w.cell_p);
        const bool edge = std::min(*std::min_element(w.p.begin(), w.p.end()),
                                   *std::min_element(w.cell_p.begin(), w.cell_p.end())) <= p_near &&
                          *std::max_element(w.cell_p.begin(), w.cell_p.end()) > p_near;
        if (edge)
          chunk.near_cavity.push_back(cell);
        else
          for (unsigned int q = 0; q < n_q; ++q)
            sums[0][15] += std::min(w.p[q] - p_cav, 0.0) * JxW(q);
      }
      PointState x;
      x.tau = jfo ? s.streamline_tau(cell) : 0.0;
      // the residual enters the sums only through the leakages (leakage_cells)
      const bool on_circle = leakage_cell[cell->active_cell_index()];
      cell->get_dof_indices(w.dofs);
      for (unsigned int q = 0; q < n_q; ++q)
      {
        if (turned)
        {
          // the film the assembly took there (film_matrices: the row's radius and angle)
          x.x = polar->quadrature_point(q);
          x.f = s.local_film(x.x, polar->radius(q), polar->angle(q), cos_psi, sin_psi);
        }
        else
        {
          x.x = fe_values.quadrature_point(q);
          x.f = s.local_film(x.x);
        }
        x.JxW = JxW(q);
        x.p = w.p[q];
        x.v = w.v[q];
        x.indicator = w.indicator[q];
        x.grad_p = w.grad_p[q];
        x.grad_v = w.grad_v[q];
        if (on_circle)
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            w.shape_grad[i] = turned ? polar->shape_grad(i, q) : fe_values.shape_grad(i, q);
            w.shape_value[i] = turned ? polar->shape_value(i, q) : fe_values.shape_value(i, q);
          }
        if (base)
        {
          p_min = std::min(p_min, w.p[q]);
          p_max = std::max(p_max, w.p[q]);
        }
        for (unsigned int k = 0; k < n_k; ++k)
        {
          PointPerturbation d;
          d.direction = perturbations[k];
          if (d.direction)
          {
            d.dh = d.direction->dh ? d.direction->dh(x.f.r, x.f.theta) : 0.0;
            d.dh_t = perturbation_squeeze(*d.direction, x.f.r, x.f.theta, w_frame);
          }
          d.dp = w.dp_k[k][q];
          d.dv = w.dv_k[k][q];
          d.grad_dp = w.grad_dp_k[k][q];
          d.grad_dv = w.grad_dv_k[k][q];
          add_pressure_loads(x, d, sums[k]);
          add_friction_and_squeeze(x, d, sums[k]);
          if (on_circle)
            add_residual(x, d, w.shape_grad, w.shape_value, w.local_residual_k[k]);
        }
      }
      if (on_circle)
        for (unsigned int k = 0; k < n_k; ++k)
          add_leakages(w.dofs, w.local_residual_k[k], sums[k]);
    }
    chunk.p_min = p_min;
    chunk.p_max = p_max;
  };

  std::vector<std::vector<double>> sums(n_k, std::vector<double>(n_sums, 0.0));
  double p_min = std::numeric_limits<double>::max(), p_max = -p_min, p_min_nodal = p_min;
  std::vector<DoFHandler<2>::active_cell_iterator> near_cavity;
  constexpr std::size_t chunk_size = 64, chunks_per_batch = 16;
  const std::size_t n_chunks = (cells.size() + chunk_size - 1) / chunk_size;
  std::array<std::vector<Chunk>, 2> batches;
  for (auto &batch : batches)
    batch.resize(std::min(chunks_per_batch, n_chunks));
  numerics::compute_in_batches_add_in_order(
      n_chunks, chunks_per_batch, batches, 1,
      [&](std::vector<Chunk> &batch, const std::size_t first_chunk, const std::size_t begin,
          const std::size_t end)
      {
        for (std::size_t c = begin; c < end; ++c)
        {
          const std::size_t first_cell = (first_chunk + c) * chunk_size;
          integrate_cells(first_cell, std::min(first_cell + chunk_size, cells.size()), batch[c]);
        }
      },
      [&](const std::vector<Chunk> &batch, std::size_t, const std::size_t count)
      {
        for (std::size_t c = 0; c < count; ++c)
        {
          const Chunk &chunk = batch[c];
          for (unsigned int k = 0; k < n_k; ++k)
            for (unsigned int m = 0; m < n_sums; ++m)
              sums[k][m] += chunk.sums[k][m];
          p_min = std::min(p_min, chunk.p_min);
          p_max = std::max(p_max, chunk.p_max);
          near_cavity.insert(near_cavity.end(), chunk.near_cavity.begin(), chunk.near_cavity.end());
        }
      });
  if (base)
    for (const auto i : s.locally_owned_dofs)
    {
      // Nodal values too: for Lagrange elements they are point values of p_h.
      p_min_nodal = std::min(p_min_nodal, s.locally_relevant_solution[i]);
      p_max = std::max(p_max, s.locally_relevant_solution[i]);
    }
  p_min = std::min(p_min, p_min_nodal);
  if (undershoot && !near_cavity.empty())
  {
    // In the cells at the cavity edge min(p_h - p_cav, 0) has a kink that a Gauss rule does not
    // integrate well: there a composite rule of 8 x 8 copies of the cell's Gauss rule (error
    // O(1/64) of the cut cells' share, see tests/validation/pressure_undershoot.cc), whose points
    // also sharpen the interpolant's minimum.
    const QIterated<2> fine(QGauss<1>(s.polynomial_degree + 2), 8);
    FEValues<2> fine_values(*s.mapping, *s.fe, fine, update_values | update_JxW_values);
    std::vector<double> p_fine(fine.size());
    for (const auto &cell : near_cavity)
    {
      fine_values.reinit(cell);
      fine_values.get_function_values(s.locally_relevant_solution, p_fine);
      for (unsigned int q = 0; q < fine.size(); ++q)
      {
        sums[0][15] += std::min(p_fine[q] - p_cav, 0.0) * fine_values.JxW(q);
        p_min = std::min(p_min, p_fine[q]);
      }
    }
  }
  std::vector<FilmLoads> result;
  for (unsigned int k = 0; k < n_k; ++k)
    result.push_back(finish(sums[k], base, p_min, p_max, p_min_nodal));
  return result;
}

FilmLoads LoadIntegrator::finish(const std::vector<double> &sum, const bool base,
                                 const double p_min, const double p_max,
                                 const double p_min_nodal) const
{
  const ReynoldsSolver &s = solver;
  std::vector<double> total(sum.size());
  MPI_Allreduce(sum.data(), total.data(), static_cast<int>(total.size()), MPI_DOUBLE, MPI_SUM,
                s.mpi_communicator);
  FilmLoads loads;
  loads.force_z = total[0];
  loads.moment_x = total[1];
  loads.moment_y = total[2];
  loads.moment_restoring = total[3];
  loads.moment_transverse = total[4];
  // The residual on a boundary is -(outward volume flux) through it.
  loads.leakage_inner = -total[5];
  loads.leakage_outer = -total[6];
  loads.friction_torque = total[7];
  loads.squeeze_flow = total[10];
  loads.contact_force = total[11];
  loads.contact_moment_x = total[12];
  loads.contact_moment_y = total[13];
  if (base)
  {
    loads.area = total[8];
    loads.contact_area_fraction = total[14] / total[8];
    loads.min_film = s.film.minimum().value;
    loads.min_film_over_sigma = s.flow_factors.is_smooth() && !s.contact.enabled()
                                    ? std::numeric_limits<double>::infinity()
                                    : loads.min_film / s.flow_factors.composite_roughness();
    loads.cavitated_fraction = total[9] / total[8];
    loads.min_pressure = Utilities::MPI::min(p_min, s.mpi_communicator);
    loads.max_pressure = Utilities::MPI::max(p_max, s.mpi_communicator);
    loads.min_pressure_nodal = Utilities::MPI::min(p_min_nodal, s.mpi_communicator);
    if (s.cavitation.is_nonlinear())
    {
      loads.pressure_undershoot =
          std::max(0.0, std::min(p_cav, loads.min_pressure_nodal) - loads.min_pressure);
      loads.pressure_undershoot_force = total[15];
    }
  }
  return loads;
}

std::vector<LoadIntegrator::VectorType> LoadIntegrator::linearized_right_hand_sides(
    const std::vector<FilmPerturbation> &perturbations) const
{
  // d(residual)/dh in each perturbation direction, scaled like the system by 12 mu / C0^3; the
  // perturbed unknown has homogeneous Dirichlet data. For reynolds/jfo the matrix is the
  // Jacobian of the converged state (jfo: the FB-Newton Jacobian, whose eliminations move the
  // cavity boundary with the perturbation; reynolds: the active set, frozen). One cell loop for
  // all right-hand sides.
  const ReynoldsSolver &s = solver;
  const double w_frame =
      s.film.feature_frame_speed(s.conditions.rotor_speed, s.conditions.stator_speed);
  const QGauss<2> quadrature(s.polynomial_degree + 2); // the assembly's rule
  FEValues<2> fe_values(*s.mapping, *s.fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), n = s.fe->n_dofs_per_cell();
  const unsigned int n_perturbations = perturbations.size();
  std::vector<double> v(n_q), shape_value(n);
  std::vector<Tensor<1, 2>> grad_p(n_q), grad_v(n_q), shape_grad(n);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<Vector<double>> cell_rhs(n_perturbations, Vector<double>(n));
  // The values the Jacobian was assembled with (polar_assembly: the rows' on the built-in
  // annulus), so that the linearised system is the derivative of one discrete system and its
  // leakages balance like those of the solve.
  std::optional<PolarCellValues> polar;
  if (polar_assembly())
    polar.emplace(*s.mapping, *s.fe, quadrature);
  Vector<double> cell_p(n), cell_v(n);

  std::vector<VectorType> rhs(n_perturbations,
                              VectorType(s.locally_owned_dofs, s.mpi_communicator));
  for (const auto &cell : s.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      const bool turned = polar && polar->reinit(cell);
      if (turned)
      {
        // grad p, v and grad v from the cell's nodal values and the turned shape functions
        cell->get_dof_values(s.locally_relevant_solution, cell_p);
        polar->get_function_gradients(cell_p, grad_p);
        if (jfo)
        {
          cell->get_dof_values(s.locally_relevant_void, cell_v);
          polar->get_function_values(cell_v, v);
          polar->get_function_gradients(cell_v, grad_v);
        }
      }
      else
      {
        fe_values.reinit(cell);
        fe_values.get_function_gradients(s.locally_relevant_solution, grad_p);
        if (jfo)
        {
          fe_values.get_function_values(s.locally_relevant_void, v);
          fe_values.get_function_gradients(s.locally_relevant_void, grad_v);
        }
      }
      const double tau = jfo ? s.streamline_tau(cell) : 0.0;
      for (auto &c : cell_rhs)
        c = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        // the film the assembly took at the point (film_matrices: the row's radius and angle)
        const ReynoldsSolver::LocalFilm f =
            turned ? s.local_film(polar->quadrature_point(q), polar->radius(q), polar->angle(q),
                                  cos_psi, sin_psi)
                   : s.local_film(fe_values.quadrature_point(q));
        const double r = f.r, theta = f.theta, JxW = turned ? polar->JxW(q) : fe_values.JxW(q);
        for (unsigned int i = 0; i < n; ++i)
        {
          shape_grad[i] = turned ? polar->shape_grad(i, q) : fe_values.shape_grad(i, q);
          shape_value[i] = turned ? polar->shape_value(i, q) : fe_values.shape_value(i, q);
        }
        const double liquid = jfo ? 1 - v[q] : 1.0;
        for (unsigned int k = 0; k < n_perturbations; ++k)
        {
          const FilmPerturbation &perturbation = perturbations[k];
          const double dh = perturbation.dh ? perturbation.dh(r, theta) : 0.0;
          const double dh_dt = perturbation_squeeze(perturbation, r, theta, w_frame);
          const Tensor<1, 2> dflux = dh * (f.dK_dh * grad_p[q]) - liquid * dh * f.dc_dh;
          double streamline = 0;
          if (jfo)
          {
            // d/dh of -tau div(v c): -tau (dh c' . grad v + v omega_eff' d(dh)/dtheta), the
            // theta derivative of dh by a central difference (dh is smooth in theta).
            const double d = 1e-6;
            const double ddh_dtheta =
                perturbation.dh
                    ? (perturbation.dh(r, theta + d) - perturbation.dh(r, theta - d)) / (2 * d)
                    : 0.0;
            streamline = -tau * (dh * (f.dc_dh * grad_v[q]) + v[q] * f.dc_div_factor * ddh_dtheta);
          }
          for (unsigned int i = 0; i < n; ++i)
            cell_rhs[k](i) -=
                s.equation_scale *
                (dflux * shape_grad[i] + liquid * f.dsqueeze_dht * dh_dt * shape_value[i] +
                 streamline * (f.u * shape_grad[i])) *
                JxW;
        }
      }
      cell->get_dof_indices(dofs);
      for (unsigned int k = 0; k < n_perturbations; ++k)
        s.homogeneous_constraints.distribute_local_to_global(cell_rhs[k], dofs, rhs[k]);
    }
  for (auto &r : rhs)
  {
    r.compress(VectorOperation::add);
    if (s.cavitation.model == Cavitation::reynolds)
    {
      for (const auto i : s.active_set)
        r[i] = 0; // frozen cavity: p stays p_cav there
      r.compress(VectorOperation::insert);
    }
  }
  return rhs;
}

void LoadIntegrator::nodal_perturbations(const VectorType &du, VectorType &dp, VectorType &dv) const
{
  const ReynoldsSolver &s = solver;
  const bool nonlinear = s.cavitation.is_nonlinear();
  VectorType dp_owned(s.locally_owned_dofs, s.mpi_communicator),
      dv_owned(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto i : s.locally_owned_dofs)
  {
    if (!nonlinear)
      dp_owned[i] = du[i];
    else if (!jfo)
      dp_owned[i] = s.pressure_scale * du[i];
    else if (s.jfo_keep_pressure[i] > 0.5)
    {
      dp_owned[i] = s.pressure_scale * du[i];
      dv_owned[i] = s.jfo_elimination[i] * du[i];
    }
    else
    {
      dv_owned[i] = du[i];
      dp_owned[i] = s.pressure_scale * s.jfo_elimination[i] * du[i];
    }
  }
  dp_owned.compress(VectorOperation::insert);
  dv_owned.compress(VectorOperation::insert);
  dp.reinit(s.locally_owned_dofs, s.locally_relevant_dofs, s.mpi_communicator);
  dv.reinit(s.locally_owned_dofs, s.locally_relevant_dofs, s.mpi_communicator);
  dp = dp_owned;
  dv = dv_owned;
}

std::vector<FilmLoads>
LoadIntegrator::linearized_loads(const std::vector<FilmPerturbation> &perturbations) const
{
  // One solve per direction with the factorisation (or AMG hierarchy) of run().
  const ReynoldsSolver &s = solver;
  const unsigned int n_perturbations = perturbations.size();
  const std::vector<VectorType> rhs = linearized_right_hand_sides(perturbations);
  std::vector<VectorType> dp_all(n_perturbations), dv_all(n_perturbations);
  for (unsigned int k = 0; k < n_perturbations; ++k)
  {
    VectorType du(s.locally_owned_dofs, s.mpi_communicator);
    s.solve_linear_system(rhs[k], du);
    s.homogeneous_constraints.distribute(du);
    nodal_perturbations(du, dp_all[k], dv_all[k]);
  }
  std::vector<const FilmPerturbation *> directions;
  std::vector<const VectorType *> dp_pointers, dv_pointers;
  for (unsigned int k = 0; k < n_perturbations; ++k)
  {
    directions.push_back(&perturbations[k]);
    dp_pointers.push_back(&dp_all[k]);
    dv_pointers.push_back(jfo ? &dv_all[k] : nullptr);
  }
  return integrate(directions, dp_pointers, dv_pointers);
}

bool LoadIntegrator::adjoint_applies(const std::size_t n_directions) const
{
  // CG was chosen for the matrix only because it is symmetric (full film, half-Sommerfeld); the
  // cavitation models' Jacobians are not, and their loads are not linear in the nodal unknown
  // alone (nodal_perturbations). A back-substitution costs little beside the factorisation, so
  // the direct solver keeps one solve per direction (and its results to the bit); with three
  // directions or fewer the adjoint's three solves would not be fewer.
  const auto method = solver.linear_solver_statistics().method();
  return n_directions > 3 && !solver.cavitation.is_nonlinear() &&
         (method == FilmLinearSolver::Method::cg_gmg || method == FilmLinearSolver::Method::cg_amg);
}

std::array<LoadIntegrator::VectorType, 3> LoadIntegrator::generalized_force_functionals() const
{
  // The same points, weights and shape values as integrate (add_pressure_loads: sums 0, 1, 2), so
  // that g_i . dp is its force and moments of dp to round-off.
  const ReynoldsSolver &s = solver;
  const QGauss<2> quadrature(s.polynomial_degree + 2);
  FEValues<2> fe_values(*s.mapping, *s.fe, quadrature,
                        update_values | update_quadrature_points | update_JxW_values);
  std::optional<PolarCellValues> polar;
  if (polar_assembly())
    polar.emplace(*s.mapping, *s.fe, quadrature);
  const unsigned int n_q = quadrature.size(), n = s.fe->n_dofs_per_cell();
  std::vector<double> p(n_q);
  Vector<double> cell_p(n);
  std::array<Vector<double>, 3> cell_g;
  for (auto &c : cell_g)
    c.reinit(n);
  std::vector<types::global_dof_index> dofs(n);
  std::array<VectorType, 3> g;
  for (auto &v : g)
    v.reinit(s.locally_owned_dofs, s.mpi_communicator);
  for (const auto &cell : s.dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      const bool turned = polar && polar->reinit(cell);
      if (!turned)
        fe_values.reinit(cell);
      // the pressure only decides which points half-Sommerfeld clips
      if (clip && turned)
      {
        cell->get_dof_values(s.locally_relevant_solution, cell_p);
        polar->get_function_values(cell_p, p);
      }
      else if (clip)
        fe_values.get_function_values(s.locally_relevant_solution, p);
      for (auto &c : cell_g)
        c = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        if (clip && p[q] < p_cav)
          continue; // half-Sommerfeld: the clipped pressure does not move (add_pressure_loads)
        const std::array<double, 3> weight = generalized_force_weights(
            turned ? polar->quadrature_point(q) : fe_values.quadrature_point(q));
        const double JxW = turned ? polar->JxW(q) : fe_values.JxW(q);
        for (unsigned int j = 0; j < n; ++j)
        {
          const double phi =
              (turned ? polar->shape_value(j, q) : fe_values.shape_value(j, q)) * JxW;
          for (unsigned int i = 0; i < 3; ++i)
            cell_g[i](j) += phi * weight[i];
        }
      }
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < 3; ++i)
        s.homogeneous_constraints.distribute_local_to_global(cell_g[i], dofs, g[i]);
    }
  for (auto &v : g)
    v.compress(VectorOperation::add);
  return g;
}

std::vector<std::array<double, 3>> LoadIntegrator::linearized_generalized_forces(
    const std::vector<FilmPerturbation> &perturbations) const
{
  std::vector<std::array<double, 3>> forces;
  if (!adjoint_applies(perturbations.size()))
  {
    for (const FilmLoads &l : linearized_loads(perturbations))
      forces.push_back({{l.force_z, l.moment_x, l.moment_y}});
    return forces;
  }
  // dL_i = g_i . C du_k with A du_k = b_k, A symmetric: = (A^-1 C^T g_i) . b_k = z_i . b_k. The
  // directions' terms at du = 0 (asperity contact: dcontact/dh dh, add_pressure_loads' only
  // term of the film alone) come from integrate with no pressure change. A Krylov solve per
  // load instead of per direction: its cost, not the right-hand sides', dominates the
  // coefficient set on the multigrid (doc/performance.md, "Session 25").
  const ReynoldsSolver &s = solver;
  const std::vector<VectorType> rhs = linearized_right_hand_sides(perturbations);
  if (s.contact.enabled())
  {
    std::vector<const FilmPerturbation *> directions;
    for (const auto &d : perturbations)
      directions.push_back(&d);
    for (const FilmLoads &l : integrate(directions, {}, {}))
      forces.push_back({{l.force_z, l.moment_x, l.moment_y}});
  }
  else
    forces.assign(perturbations.size(), {{0.0, 0.0, 0.0}});
  const std::array<VectorType, 3> g = generalized_force_functionals();
  for (unsigned int i = 0; i < 3; ++i)
  {
    VectorType z(s.locally_owned_dofs, s.mpi_communicator);
    s.solve_linear_system(g[i], z);
    for (unsigned int k = 0; k < perturbations.size(); ++k)
      forces[k][i] += z * rhs[k];
  }
  return forces;
}

} // namespace sealfe
