#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using namespace dealii;

namespace
{
/// Below this many unknowns a sparse direct solve (KLU) beats AMG-preconditioned CG on 2D
/// Reynolds problems on this class of machine; above it the fill-in of the direct solver grows.
constexpr types::global_dof_index direct_solver_limit = 150000;
} // namespace

ReynoldsSolver::ReynoldsSolver(MPI_Comm comm)
    : mpi_communicator(comm), triangulation(comm), dof_handler(triangulation),
      timer(std::cerr, TimerOutput::never, TimerOutput::wall_times)
{
}

void ReynoldsSolver::declare_parameters(ParameterHandler &prm)
{
  AnnulusMesh::declare_parameters(prm);
  CavitationSettings::declare_parameters(prm);
  FlowFactors::declare_parameters(prm);
  AsperityContact::declare_parameters(prm);
  prm.enter_subsection("Discretization");
  prm.declare_entry("Polynomial degree", "2", Patterns::Integer(1, 6),
                    "Degree k of the continuous Lagrange elements (and of the curved mapping).");
  prm.declare_entry("Linear solver", "auto", Patterns::Selection("auto|direct|cg-amg"),
                    "auto: sparse direct (KLU) below 150000 unknowns, CG with algebraic "
                    "multigrid above; direct or cg-amg force one.");
  prm.declare_entry("Solver tolerance", "1e-12", Patterns::Double(0),
                    "Relative residual tolerance of the iterative solver (the equation is scaled "
                    "by 12 mu / C0^3, so this is relative to the pressure load).");
  prm.declare_entry("Error estimate", "true", Patterns::Bool(),
                    "Estimate the discretisation error of every load by a second solve on a mesh "
                    "twice as coarse (cost about 1/4 of the main solve).");
  prm.leave_subsection();
}

void ReynoldsSolver::parse_parameters(ParameterHandler &prm)
{
  mesh_parameters.parse_parameters(prm);
  cavitation.parse_parameters(prm);
  flow_factors.parse_parameters(prm);
  contact.parse_parameters(prm);
  prm.enter_subsection("Discretization");
  polynomial_degree = prm.get_integer("Polynomial degree");
  const std::string s = prm.get("Linear solver");
  linear_solver = (s == "direct")   ? LinearSolver::direct
                  : (s == "cg-amg") ? LinearSolver::cg_amg
                                    : LinearSolver::automatic;
  solver_tolerance = prm.get_double("Solver tolerance");
  estimate_error = prm.get_bool("Error estimate");
  prm.leave_subsection();
}

void ReynoldsSolver::setup_system(const unsigned int coarsening)
{
  TimerOutput::Scope t(timer, "setup");
  dof_handler.clear();
  triangulation.clear();
  // Grading from C0 and coning only, so that perturbing z or the tilts (finite-difference
  // coefficients) keeps the same mesh.
  mesh_parameters.grading_clearance = film.clearance;
  mesh_parameters.grading_coning = film.coning;
  mesh_parameters.create(triangulation, film.inner_radius, film.outer_radius, coarsening);

  fe = std::make_unique<FE_Q<2>>(polynomial_degree);
  mapping = std::make_unique<MappingQ<2>>(polynomial_degree);
  dof_handler.distribute_dofs(*fe);

  locally_owned_dofs = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
  locally_relevant_solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  system_rhs.reinit(locally_owned_dofs, mpi_communicator);

  constraints.clear();
  constraints.reinit(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  if (boundary_pressure)
  {
    const ScalarFunctionFromFunctionObject<2> g(boundary_pressure);
    for (const auto id : {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary})
      VectorTools::interpolate_boundary_values(*mapping, dof_handler, id, g, constraints);
  }
  else
  {
    VectorTools::interpolate_boundary_values(
        *mapping, dof_handler, AnnulusMesh::inner_boundary,
        Functions::ConstantFunction<2>(conditions.inner_pressure), constraints);
    VectorTools::interpolate_boundary_values(
        *mapping, dof_handler, AnnulusMesh::outer_boundary,
        Functions::ConstantFunction<2>(conditions.outer_pressure), constraints);
  }
  constraints.close();

  // The same with zero Dirichlet data: the constraints of every correction and perturbation
  // (Newton steps of the cavitation models, linearised solves of the coefficients).
  homogeneous_constraints.clear();
  homogeneous_constraints.reinit(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, homogeneous_constraints);
  for (const auto id : {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary})
    VectorTools::interpolate_boundary_values(*mapping, dof_handler, id,
                                             Functions::ZeroFunction<2>(), homogeneous_constraints);
  homogeneous_constraints.close();

  // Dofs on each circle, for the consistent boundary fluxes (leakages).
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), inner_boundary_dofs,
                                  {AnnulusMesh::inner_boundary});
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), outer_boundary_dofs,
                                  {AnnulusMesh::outer_boundary});

  DynamicSparsityPattern dsp(locally_relevant_dofs);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
  SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                             locally_relevant_dofs);
  system_matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
}

void ReynoldsSolver::assemble_system()
{
  TimerOutput::Scope t(timer, "assemble");
  // h is not polynomial in x, y (cos theta, r): one Gauss point more than the element needs. The
  // load/residual integration uses the same rule, so that the interior residuals vanish to solver
  // tolerance and the leakages balance.
  const QGauss<2> quadrature(polynomial_degree + 2);
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
  FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell),
      unused(dofs_per_cell, dofs_per_cell);
  Vector<double> cell_rhs(dofs_per_cell);
  std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);

  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      // the full-film pressure matrix and Couette + squeeze right-hand side
      cell_film_matrices(fe_values, cell, false, cell_matrix, unused, cell_rhs);
      cell->get_dof_indices(local_dof_indices);
      constraints.distribute_local_to_global(cell_matrix, cell_rhs, local_dof_indices,
                                             system_matrix, system_rhs);
    }
  system_matrix.compress(VectorOperation::add);
  system_rhs.compress(VectorOperation::add);
}

void ReynoldsSolver::factorize()
{
  // One factorisation (or AMG hierarchy) per matrix, reused by the solve and by every linearised
  // solve of the dynamic coefficients.
  use_direct_solver =
      linear_solver == LinearSolver::direct ||
      (linear_solver == LinearSolver::automatic && dof_handler.n_dofs() < direct_solver_limit);
  direct_control = std::make_unique<SolverControl>(1, 0);
  if (use_direct_solver)
  {
    direct_solver = std::make_unique<TrilinosWrappers::SolverDirect>(*direct_control);
    direct_solver->initialize(system_matrix);
  }
  else
  {
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = polynomial_degree > 1;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 0.02;
    amg->initialize(system_matrix, data);
  }
}

unsigned int ReynoldsSolver::solve_linear_system(const TrilinosWrappers::MPI::Vector &rhs,
                                                 TrilinosWrappers::MPI::Vector &x) const
{
  if (use_direct_solver)
  {
    direct_solver->solve(x, rhs);
    return 1;
  }
  const double target = solver_tolerance * rhs.l2_norm();
  SolverControl control(std::max<unsigned int>(1000, dof_handler.n_dofs() / 10),
                        std::max(target, std::numeric_limits<double>::min()), false, false);
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  try
  {
    cg.solve(system_matrix, x, rhs, *amg);
  }
  catch (SolverControl::NoConvergence &e)
  {
    std::ostringstream s;
    s << "Reynolds solver: CG+AMG did not converge in " << e.last_step << " iterations (residual "
      << e.last_residual << ", target " << target << "); try 'set Linear solver = direct'";
    throw std::runtime_error(s.str());
  }
  return control.last_step();
}

void ReynoldsSolver::solve()
{
  TimerOutput::Scope t(timer, "solve");
  factorize();
  TrilinosWrappers::MPI::Vector solution(locally_owned_dofs, mpi_communicator);
  last_iterations = solve_linear_system(system_rhs, solution);
  constraints.distribute(solution);
  if (!std::isfinite(solution.linfty_norm()))
    throw std::runtime_error("Reynolds solver: the linear solve produced a non-finite pressure");
  locally_relevant_solution = solution;
}

ReynoldsSolver::LocalFilm ReynoldsSolver::local_film(const Point<2> &x) const
{
  LocalFilm f;
  f.r = x.norm();
  f.theta = std::atan2(x[1], x[0]);
  f.h = film.value(f.r, f.theta);
  const double mu = conditions.viscosity;
  const double w_mean = conditions.mean_speed();
  const double w_half_difference = 0.5 * (conditions.rotor_speed - conditions.stator_speed);
  const Tensor<1, 2> er({x[0] / f.r, x[1] / f.r}), et({-x[1] / f.r, x[0] / f.r});
  const Tensor<1, 2> rotation({-x[1], x[0]}); // r e_theta
  f.u = w_mean * rotation;
  double h_t = film.d_dt(f.r, f.theta);
  if (source)
    h_t += source(x);
  const double dh_dtheta = film.d_dtheta(f.r, f.theta);

  if (flow_factors.is_smooth())
  {
    const double k = f.h * f.h * f.h / (12 * mu);
    f.K = k * unit_symmetric_tensor<2>();
    f.dK_dh = (3 * k / f.h) * unit_symmetric_tensor<2>();
    f.c = f.h * f.u;
    f.dc_dh = f.u;
    f.dc_div_factor = w_mean;
    f.squeeze = h_t;
    f.dsqueeze_dht = 1;
    f.h_T = f.h;
  }
  else
  {
    // Average Reynolds equation of Patir & Cheng in the polar frame: radial and circumferential
    // pressure flow factors, expected gap h_T in the Couette and squeeze terms, shear flow
    // sigma phi_s (u1 - u2)/2 along e_theta. The flow coefficient uses the nominal h, held at
    // 0.5 sigma (the fits' validity limit) where the faces are in asperity contact.
    const auto ff = flow_factors.film_factors(f.h);
    const double sigma = flow_factors.composite_roughness();
    const double h_flow = std::max(f.h, 0.5 * sigma);
    const double k = h_flow * h_flow * h_flow / (12 * mu);
    const double dk = f.h > 0.5 * sigma ? 3 * k / h_flow : 0.0;
    f.K = k * (ff.phi_r.value * outer_product(er, er) + ff.phi_theta.value * outer_product(et, et));
    f.dK_dh = (dk * ff.phi_r.value + k * ff.phi_r.d_dh) * outer_product(er, er) +
              (dk * ff.phi_theta.value + k * ff.phi_theta.d_dh) * outer_product(et, et);
    const double omega_eff = w_mean * ff.h_T.value + w_half_difference * sigma * ff.phi_s.value;
    f.dc_div_factor = w_mean * ff.h_T.d_dh + w_half_difference * sigma * ff.phi_s.d_dh;
    f.c = omega_eff * rotation;
    f.dc_dh = f.dc_div_factor * rotation;
    f.squeeze = ff.h_T.d_dh * h_t;
    f.dsqueeze_dht = ff.h_T.d_dh;
    f.phi_r = ff.phi_r.value;
    f.phi_theta = ff.phi_theta.value;
    f.phi_s = ff.phi_s.value;
    f.h_T = ff.h_T.value;
  }
  // div(omega_eff(h) r e_theta) = omega_eff'(h) dh/dtheta (r e_theta is divergence free)
  f.c_div = f.dc_div_factor * dh_dtheta;
  const ValueAndSlope pc = contact.contact_pressure(f.h);
  f.contact_pressure = pc.value;
  f.dcontact_dh = pc.d_dh;
  return f;
}

double ReynoldsSolver::streamline_tau(const DoFHandler<2>::active_cell_iterator &cell) const
{
  // Streamline-diffusion parameter for the transport of the void fraction in the cavity: full
  // upwinding, tau = h_K / (2 |u|), with |u| the Couette speed at the cell centre.
  const double speed = std::abs(conditions.mean_speed()) * cell->center().norm();
  return speed > 0 ? cell->diameter() / (2 * speed) : 0.0;
}

namespace
{
/// Film data at one quadrature point.
struct FilmPoint
{
  double r, theta, h, dh_dtheta, dh_dt;
  Tensor<1, 2> u; // Couette velocity (w1 + w2)/2 * r e_theta
};
} // namespace

// ------------------------------------------------------------------------------------------------
// Cavitation (reynolds, jfo).
//
// JFO / Elrod-Adams: every dof j carries a_j = (p_j - p_cav)/P >= 0 and the void fraction
// v_j = 1 - s_j >= 0 with a_j v_j = 0 (p > p_cav => s = 1, s < 1 => p = p_cav). The discrete mass
// balance at dof i (the weak form of div(K grad p) = div(s h u) + s dh/dt, s = 1 - v, tested with
// phi_i) is
//
//   R_i = sum_j A_ij p_j - F_i + sum_j G_ij v_j = 0,
//   A_ij = int K grad phi_j . grad phi_i,          F_i = int h u . grad phi_i - dh/dt phi_i,
//   G_ij = int phi_j (h u . grad phi_i - dh/dt phi_i) - tau_K (u . grad(phi_j h))(u . grad phi_i).
//
// The last term is streamline diffusion of the transported void h v (with the sign of a positive
// diffusion relative to the transport term, which enters R as -u . grad(v h)): in the cavity the
// equation is pure transport along the Couette streamlines, which Galerkin alone leaves
// oscillating (Gravenkamp, Pfeil & Codina 2024). It acts on v only, so it vanishes identically
// wherever the film is full: without cavitation the JFO discretisation is the full-film Galerkin
// one. Summed over all test functions it is zero (sum phi_i = 1), so it moves no mass: the two
// boundary leakages balance the squeeze flow to solver tolerance. The complementarity is solved
// by Fischer-Burmeister-Newton-Schur (solve_jfo).
//
// Reynolds (Swift-Stieber): p_j = p_cav + P u_j with the complementarity min(u_j, R_j/J_jj) = 0,
// solved by the primal-dual active-set method (Hintermueller, Ito & Kunisch 2002).

void ReynoldsSolver::cell_film_matrices(FEValues<2> &fe_values,
                                        const DoFHandler<2>::active_cell_iterator &cell,
                                        const bool with_void, FullMatrix<double> &A,
                                        FullMatrix<double> &G, Vector<double> &F) const
{
  // A: pressure flow, F: full-film Couette + squeeze, G: void-fraction terms (see above). All
  // scaled by 12 mu / C0^3 like the full-film system.
  const unsigned int n = fe->n_dofs_per_cell();
  const double tau = with_void ? streamline_tau(cell) : 0.0;
  fe_values.reinit(cell);
  A = 0;
  G = 0;
  F = 0;
  for (const unsigned int q : fe_values.quadrature_point_indices())
  {
    const LocalFilm f = local_film(fe_values.quadrature_point(q));
    const Tensor<2, 2> K = equation_scale * f.K;
    const double JxW = fe_values.JxW(q);
    for (unsigned int i = 0; i < n; ++i)
    {
      const Tensor<1, 2> gi = fe_values.shape_grad(i, q);
      const double vi = fe_values.shape_value(i, q);
      const double c_grad_i = f.c * gi, u_grad_i = f.u * gi;
      F(i) += equation_scale * (c_grad_i - f.squeeze * vi) * JxW;
      for (unsigned int j = 0; j < n; ++j)
      {
        A(i, j) += (gi * (K * fe_values.shape_grad(j, q))) * JxW;
        if (with_void)
        {
          // div(phi_j c) = c . grad phi_j + phi_j div c: the transported void content
          const double vj = fe_values.shape_value(j, q);
          const double div_jc = f.c * fe_values.shape_grad(j, q) + vj * f.c_div;
          G(i, j) +=
              equation_scale * (vj * (c_grad_i - f.squeeze * vi) - tau * div_jc * u_grad_i) * JxW;
        }
      }
    }
  }
}

double ReynoldsSolver::assemble_reynolds_system(const TrilinosWrappers::MPI::Vector &u,
                                                const bool with_jacobian,
                                                TrilinosWrappers::MPI::Vector &rhs)
{
  const QGauss<2> quadrature(polynomial_degree + 2);
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n = fe->n_dofs_per_cell();
  FullMatrix<double> A(n, n), G(n, n), J(n, n);
  Vector<double> F(n), R(n), local_u(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  if (with_jacobian)
    system_matrix = 0;
  rhs = 0;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      cell->get_dof_indices(dofs);
      cell->get_dof_values(u, local_u);
      for (unsigned int j = 0; j < n; ++j)
        local_p(j) = cavitation.pressure + pressure_scale * local_u(j);
      cell_film_matrices(fe_values, cell, false, A, G, F);
      A.vmult(R, local_p);
      R -= F;
      R *= -1.0; // rhs holds -R
      if (with_jacobian)
      {
        J = A;
        J *= pressure_scale;
        homogeneous_constraints.distribute_local_to_global(J, R, dofs, system_matrix, rhs);
      }
      else
        homogeneous_constraints.distribute_local_to_global(R, dofs, rhs);
    }
  if (with_jacobian)
    system_matrix.compress(VectorOperation::add);
  rhs.compress(VectorOperation::add);

  {
    // Primal-dual active set: dof i is cavitated if u_i - R_i / J_ii <= 0; there the equation is
    // replaced by u_i = 0 (the Newton row delta u_i = -u_i).
    active_set.clear();
    for (const auto i : locally_owned_dofs)
      if (!homogeneous_constraints.is_constrained(i))
      {
        const double diagonal =
            with_jacobian ? system_matrix.diag_element(i) : reynolds_diagonal[i];
        if (u[i] + rhs[i] / diagonal <= 0)
          active_set.push_back(i);
      }
    if (with_jacobian)
    {
      for (const auto i : locally_owned_dofs)
        reynolds_diagonal[i] = system_matrix.diag_element(i);
      reynolds_diagonal.compress(VectorOperation::insert);
      system_matrix.clear_rows(active_set, 1.0);
    }
    for (const auto i : active_set)
      rhs[i] = -u[i];
    rhs.compress(VectorOperation::insert);
  }
  return rhs.l2_norm();
}

namespace
{
/// Fischer-Burmeister function phi(a, b) = a + b - sqrt(a^2 + b^2): zero iff a >= 0, b >= 0,
/// a b = 0. Returns phi and its partial derivatives (the generalised ones at the origin).
struct FischerBurmeister
{
  double value, d_a, d_b;
  FischerBurmeister(const double a, const double b)
  {
    const double rho = std::hypot(a, b);
    value = a + b - rho;
    d_a = rho > 0 ? 1 - a / rho : 1 - M_SQRT1_2;
    d_b = rho > 0 ? 1 - b / rho : 1 - M_SQRT1_2;
  }
  /// Which unknown a node keeps in the reduced Newton system: the one whose complementarity
  /// derivative is smaller is eliminated (d_a + d_b >= 2 - sqrt 2, so the kept one is >= 0.29).
  bool keeps_pressure() const { return d_b >= d_a; }
};
} // namespace

// JFO by Fischer-Burmeister-Newton-Schur (Woloszynski et al. 2015): nodal unknowns a_j = (p_j -
// p_cav)/P and v_j, equations R_j(a, v) = 0 (mass balance, see above) and phi(a_j, v_j) = 0.
// Each node's complementarity row is used to eliminate one of its two unknowns, so the Newton
// system stays N x N with the sparsity of the pressure matrix; unlike the universal variable, a
// node near the cavity boundary sees both its pressure and its void derivative, which is what
// lets the active set settle. Globalised by backtracking on 1/2 (|R|^2 + |phi|^2).
double ReynoldsSolver::assemble_jfo_system(const TrilinosWrappers::MPI::Vector &a,
                                           const TrilinosWrappers::MPI::Vector &v,
                                           const bool with_jacobian,
                                           TrilinosWrappers::MPI::Vector &residual,
                                           TrilinosWrappers::MPI::Vector &newton_rhs,
                                           const bool active_set_step)
{
  const unsigned int n = fe->n_dofs_per_cell();
  // A, G, F do not depend on the state: computed once per solve and reused by every Newton
  // iteration and line-search trial.
  if (cell_A.empty())
  {
    const QGauss<2> quadrature(polynomial_degree + 2);
    FEValues<2> fe_values(*mapping, *fe, quadrature,
                          update_values | update_gradients | update_quadrature_points |
                              update_JxW_values);
    cell_A.resize(triangulation.n_active_cells());
    cell_G.resize(triangulation.n_active_cells());
    cell_F.resize(triangulation.n_active_cells());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        const auto k = cell->active_cell_index();
        cell_A[k].reinit(n, n);
        cell_G[k].reinit(n, n);
        cell_F[k].reinit(n);
        cell_film_matrices(fe_values, cell, true, cell_A[k], cell_G[k], cell_F[k]);
      }
  }
  FullMatrix<double> J(n, n);
  Vector<double> R(n), correction(n), local_a(n), local_v(n), local_p(n);
  std::vector<types::global_dof_index> dofs(n);
  const double P = pressure_scale;

  if (with_jacobian)
  {
    system_matrix = 0;
    newton_rhs = 0;
  }
  residual = 0;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      const auto k = cell->active_cell_index();
      const FullMatrix<double> &A = cell_A[k], &G = cell_G[k];
      cell->get_dof_indices(dofs);
      cell->get_dof_values(a, local_a);
      cell->get_dof_values(v, local_v);
      for (unsigned int j = 0; j < n; ++j)
        local_p(j) = cavitation.pressure + P * local_a(j);
      A.vmult(R, local_p);
      R -= cell_F[k];
      G.vmult_add(R, local_v);
      R *= -1.0; // residual vector holds -R
      homogeneous_constraints.distribute_local_to_global(R, dofs, residual);
      if (with_jacobian)
      {
        correction = 0;
        for (unsigned int j = 0; j < n; ++j)
        {
          const FischerBurmeister fb(local_a(j), local_v(j));
          if (active_set_step)
          {
            // Active-set step: the node keeps the larger of its two unknowns, the other is set
            // to zero (its current value moves to the right-hand side).
            const bool keep_pressure = local_a(j) >= local_v(j);
            for (unsigned int i = 0; i < n; ++i)
            {
              J(i, j) = keep_pressure ? P * A(i, j) : G(i, j);
              correction(i) += keep_pressure ? G(i, j) * local_v(j) : P * A(i, j) * local_a(j);
            }
          }
          else if (fb.keeps_pressure())
          {
            const double ratio = fb.d_a / fb.d_b, shift = fb.value / fb.d_b;
            for (unsigned int i = 0; i < n; ++i)
            {
              J(i, j) = P * A(i, j) - G(i, j) * ratio;
              correction(i) += G(i, j) * shift;
            }
          }
          else
          {
            const double ratio = fb.d_b / fb.d_a, shift = fb.value / fb.d_a;
            for (unsigned int i = 0; i < n; ++i)
            {
              J(i, j) = G(i, j) - P * A(i, j) * ratio;
              correction(i) += P * A(i, j) * shift;
            }
          }
        }
        R += correction;
        homogeneous_constraints.distribute_local_to_global(J, R, dofs, system_matrix, newton_rhs);
      }
    }
  residual.compress(VectorOperation::add);
  if (with_jacobian)
  {
    system_matrix.compress(VectorOperation::add);
    newton_rhs.compress(VectorOperation::add);
  }
  double fb_squared = 0;
  for (const auto i : locally_owned_dofs)
    if (!homogeneous_constraints.is_constrained(i))
      fb_squared += Utilities::fixed_power<2>(FischerBurmeister(a[i], v[i]).value);
  fb_squared = Utilities::MPI::sum(fb_squared, mpi_communicator);
  const double r = residual.l2_norm() / jfo_flow_scale;
  return 0.5 * (r * r + fb_squared);
}

void ReynoldsSolver::solve_jfo(const double flow_scale)
{
  jfo_flow_scale = flow_scale;
  cell_A.clear();
  cell_G.clear();
  cell_F.clear();
  // Warm start. The Newton iteration moves the cavity boundary by about one cell per iteration
  // (measured: 17, 63, 168, 400 iterations on 32, 64, 128, 256 cells around), so it starts from
  // the converged JFO state of the mesh twice as coarse (recursively, mesh sequencing), evaluated
  // at this mesh's nodes; on the coarsest mesh from the full film: a = (p - p_cav)/P where
  // positive, else a = 0 with a small void.
  TrilinosWrappers::MPI::Vector a_owned(locally_owned_dofs, mpi_communicator),
      v_owned(locally_owned_dofs, mpi_communicator);
  for (const auto i : locally_owned_dofs)
  {
    const double d = (locally_relevant_solution[i] - cavitation.pressure) / pressure_scale;
    a_owned[i] = std::max(d, 0.0);
    v_owned[i] = d < 0 ? std::min(-d, 1e-3) : 0.0;
  }
  if (dof_handler.n_dofs() > 200 && mesh_parameters.can_coarsen(current_coarsening + 1))
  {
    ReynoldsSolver coarse(mpi_communicator);
    coarse.mesh_parameters = mesh_parameters;
    coarse.cavitation = cavitation;
    coarse.polynomial_degree = polynomial_degree;
    coarse.linear_solver = linear_solver;
    coarse.solver_tolerance = solver_tolerance;
    coarse.boundary_pressure = boundary_pressure;
    coarse.source = source;
    bool coarse_ok = true;
    try
    {
      coarse.run(film, conditions, current_coarsening + 1);
    }
    catch (std::exception &)
    {
      coarse_ok = false; // fall back to the full-film start
    }
    if (coarse_ok)
    {
      std::map<types::global_dof_index, Point<2>> support;
      DoFTools::map_dofs_to_support_points(*mapping, dof_handler, support);
      std::vector<Point<2>> points;
      std::vector<types::global_dof_index> indices;
      for (const auto i : locally_owned_dofs)
        if (!homogeneous_constraints.is_constrained(i))
        {
          indices.push_back(i);
          points.push_back(support[i]);
        }
      Utilities::MPI::RemotePointEvaluation<2> cache;
      const std::vector<double> pressure = VectorTools::point_values<1>(
          *coarse.mapping, coarse.dof_handler, coarse.locally_relevant_solution, points, cache);
      const std::vector<double> void_fraction =
          VectorTools::point_values<1>(cache, coarse.dof_handler, coarse.locally_relevant_void);
      if (cache.all_points_found())
        for (unsigned int k = 0; k < indices.size(); ++k)
        {
          a_owned[indices[k]] = std::max((pressure[k] - cavitation.pressure) / pressure_scale, 0.0);
          v_owned[indices[k]] = std::clamp(void_fraction[k], 0.0, 1.0);
        }
      coarse_iterations = coarse.cavitation_iterations + coarse.coarse_iterations;
    }
  }
  a_owned.compress(VectorOperation::insert);
  v_owned.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector a(locally_owned_dofs, locally_relevant_dofs, mpi_communicator),
      v(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  a = a_owned;
  v = v_owned;

  TrilinosWrappers::MPI::Vector residual(locally_owned_dofs, mpi_communicator),
      newton_rhs(locally_owned_dofs, mpi_communicator), w(locally_owned_dofs, mpi_communicator),
      da(locally_owned_dofs, mpi_communicator), dv(locally_owned_dofs, mpi_communicator),
      trial_a(locally_owned_dofs, mpi_communicator), trial_v(locally_owned_dofs, mpi_communicator);
  TrilinosWrappers::MPI::Vector ta(locally_owned_dofs, locally_relevant_dofs, mpi_communicator),
      tv(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);

  auto fb_max =
      [&](const TrilinosWrappers::MPI::Vector &aa, const TrilinosWrappers::MPI::Vector &vv)
  {
    double m = 0;
    for (const auto i : locally_owned_dofs)
      if (!homogeneous_constraints.is_constrained(i))
        m = std::max(m, std::abs(FischerBurmeister(aa[i], vv[i]).value));
    return Utilities::MPI::max(m, mpi_communicator);
  };

  // Newton update of (a, v) from the reduced unknown w (each node's eliminated unknown from its
  // linearised complementarity row).
  auto recover = [&](const TrilinosWrappers::MPI::Vector &w)
  {
    for (const auto i : locally_owned_dofs)
    {
      if (homogeneous_constraints.is_constrained(i))
      {
        da[i] = dv[i] = 0;
        continue;
      }
      const FischerBurmeister fb(a_owned[i], v_owned[i]);
      if (fb.keeps_pressure())
      {
        da[i] = w[i];
        dv[i] = (-fb.value - fb.d_a * w[i]) / fb.d_b;
      }
      else
      {
        dv[i] = w[i];
        da[i] = (-fb.value - fb.d_b * w[i]) / fb.d_a;
      }
    }
    da.compress(VectorOperation::insert);
    dv.compress(VectorOperation::insert);
  };
  double best_merit = std::numeric_limits<double>::max();
  TrilinosWrappers::MPI::Vector best_a(a_owned), best_v(v_owned);
  unsigned int steps_without_progress = 0;
  bool monotone = false;
  unsigned int active_set_rounds = 0, next_polish = 0, polish_gap = 1;

  double merit = 0, mass_residual = 0, complementarity = 0;
  bool converged = false;
  unsigned int it = 0;
  for (; it < cavitation.maximum_iterations; ++it)
  {
    merit = assemble_jfo_system(a, v, true, residual, newton_rhs);
    mass_residual = residual.l2_norm() / flow_scale;
    complementarity = fb_max(a_owned, v_owned);
    if (mass_residual < cavitation.tolerance && complementarity < cavitation.tolerance)
    {
      converged = true;
      break;
    }
    if (it >= next_polish)
    {
      // Active-set polish: with the cavitated set fixed the discrete problem is linear. Starting
      // from the set read off the current iterate (v > a), nodes whose solution is inconsistent
      // (a < 0 on a pressure node, v < 0 on a cavitated one) switch set and the linear problem is
      // solved again (primal-dual active set). A consistent solution is the exact JFO solution
      // and ends the iteration at the next check; after a few unsuccessful rounds the polish is
      // abandoned for this iteration and the FB-Newton step is taken.
      TrilinosWrappers::MPI::Vector set_a(a_owned), set_v(v_owned);
      bool consistent = false;
      for (unsigned int round = 0; round < 40 && !consistent; ++round)
      {
        ta = set_a;
        tv = set_v;
        assemble_jfo_system(ta, tv, true, residual, newton_rhs, true);
        ++active_set_rounds;
        factorize();
        w = 0;
        solve_linear_system(newton_rhs, w);
        homogeneous_constraints.set_zero(w);
        unsigned int flips = 0;
        for (const auto i : locally_owned_dofs)
        {
          if (homogeneous_constraints.is_constrained(i))
          {
            trial_a[i] = set_a[i];
            trial_v[i] = set_v[i];
            continue;
          }
          const bool keep_pressure = set_a[i] >= set_v[i];
          const double value = (keep_pressure ? set_a[i] : set_v[i]) + w[i];
          // round-off of the linear solve (values are O(1)) is not a set change
          trial_a[i] = keep_pressure ? std::max(value, 0.0) : 0.0;
          trial_v[i] = keep_pressure ? 0.0 : std::max(value, 0.0);
          if (value < -1e-12)
          {
            // switch set: a tiny value of the other unknown marks the new set
            ++flips;
            set_a[i] = keep_pressure ? 0.0 : 1e-300;
            set_v[i] = keep_pressure ? 1e-300 : 0.0;
          }
          else
          {
            set_a[i] = trial_a[i];
            set_v[i] = trial_v[i];
          }
        }
        trial_a.compress(VectorOperation::insert);
        trial_v.compress(VectorOperation::insert);
        set_a.compress(VectorOperation::insert);
        set_v.compress(VectorOperation::insert);
        consistent = Utilities::MPI::sum(flips, mpi_communicator) == 0;
      }
      // After a failed polish the next one waits twice as long (it costs up to 40 solves).
      next_polish = it + polish_gap;
      polish_gap *= 2;
      if (consistent)
      {
        a_owned = trial_a;
        v_owned = trial_v;
        a = a_owned;
        v = v_owned;
        continue;
      }
      merit = assemble_jfo_system(a, v, true, residual, newton_rhs);
    }
    factorize();
    w = 0;
    solve_linear_system(newton_rhs, w);
    homogeneous_constraints.set_zero(w);
    recover(w);
    // Projected full steps with a watchdog: the Newton step with a and v clipped at zero keeps
    // the iterate feasible and moves the cavity boundary as far as the linearisation says, which
    // the FB merit line search alone does not (it creeps when a full step trades mass residual
    // for complementarity residual: 31 instead of 5 iterations on the default mesh). Such steps
    // may raise the merit for a while; after 10 of them without a new best merit the iteration
    // returns to the best iterate and continues with Armijo backtracking on the merit, along
    // which the FB-Newton direction is a descent direction (so the method cannot cycle).
    double step = 1;
    if (merit < best_merit)
    {
      best_merit = merit;
      best_a = a_owned;
      best_v = v_owned;
      steps_without_progress = 0;
    }
    else
      ++steps_without_progress;
    if (!monotone && steps_without_progress >= 10)
    {
      // Back to the best iterate; from there on plain FB-Newton with backtracking.
      monotone = true;
      a_owned = best_a;
      v_owned = best_v;
      a = a_owned;
      v = v_owned;
      merit = assemble_jfo_system(a, v, true, residual, newton_rhs);
      factorize();
      w = 0;
      solve_linear_system(newton_rhs, w);
      homogeneous_constraints.set_zero(w);
      recover(w);
    }
    if (!monotone)
    {
      trial_a = a_owned;
      trial_a.add(1.0, da);
      trial_v = v_owned;
      trial_v.add(1.0, dv);
      for (const auto i : locally_owned_dofs)
      {
        trial_a[i] = std::max(static_cast<double>(trial_a[i]), 0.0);
        trial_v[i] = std::max(static_cast<double>(trial_v[i]), 0.0);
      }
      trial_a.compress(VectorOperation::insert);
      trial_v.compress(VectorOperation::insert);
      da = trial_a;
      da -= a_owned;
      dv = trial_v;
      dv -= v_owned;
    }
    else
      for (unsigned int ls = 0; ls < 30; ++ls, step *= 0.5)
      {
        trial_a = a_owned;
        trial_a.add(step, da);
        trial_v = v_owned;
        trial_v.add(step, dv);
        ta = trial_a;
        tv = trial_v;
        if (assemble_jfo_system(ta, tv, false, residual, newton_rhs) <= (1 - 1e-4 * step) * merit)
          break;
      }
    a_owned.add(step, da);
    v_owned.add(step, dv);
    a = a_owned;
    v = v_owned;
  }
  // Every linearised solve counts: FB-Newton steps and active-set rounds.
  cavitation_iterations = it + active_set_rounds;
  cavitation_residual = std::max(mass_residual, complementarity);
  if (!converged)
  {
    std::ostringstream s;
    s << "Cavitation (jfo): no convergence in " << cavitation.maximum_iterations
      << " Newton iterations (relative mass residual " << mass_residual
      << ", complementarity residual " << complementarity << ", tolerance " << cavitation.tolerance
      << "); refine the mesh or raise Cavitation/Maximum iterations";
    throw std::runtime_error(s.str());
  }
  // The last assembly built the Jacobian at the solution: factorise it for linearized_loads,
  // and keep which unknown each node kept with its complementarity derivatives.
  factorize();
  jfo_keep_pressure.reinit(locally_owned_dofs, mpi_communicator);
  jfo_elimination.reinit(locally_owned_dofs, mpi_communicator);
  for (const auto i : locally_owned_dofs)
  {
    const FischerBurmeister fb(a_owned[i], v_owned[i]);
    jfo_keep_pressure[i] = fb.keeps_pressure() ? 1.0 : 0.0;
    jfo_elimination[i] = fb.keeps_pressure() ? -fb.d_a / fb.d_b : -fb.d_b / fb.d_a;
  }
  jfo_keep_pressure.compress(VectorOperation::insert);
  jfo_elimination.compress(VectorOperation::insert);

  TrilinosWrappers::MPI::Vector p(locally_owned_dofs, mpi_communicator);
  for (const auto i : locally_owned_dofs)
    p[i] = cavitation.pressure + pressure_scale * a_owned[i];
  p.compress(VectorOperation::insert);
  locally_relevant_solution = p;
  locally_relevant_void = v_owned;
  last_iterations += it;
  cell_A.clear();
  cell_G.clear();
  cell_F.clear();
}

void ReynoldsSolver::solve_cavitation()
{
  TimerOutput::Scope t(timer, "cavitation");
  const bool jfo = cavitation.model == Cavitation::jfo;
  const double p_cav = cavitation.pressure;
  const double p_lo = std::min(conditions.inner_pressure, conditions.outer_pressure);
  const double p_hi = std::max(conditions.inner_pressure, conditions.outer_pressure);
  if (!boundary_pressure && p_lo < p_cav)
  {
    std::ostringstream s;
    s << "Cavitation: a boundary pressure (pi = " << conditions.inner_pressure
      << " Pa, po = " << conditions.outer_pressure << " Pa) is below the cavitation pressure ("
      << p_cav << " Pa)";
    throw std::runtime_error(s.str());
  }
  if (jfo && !boundary_pressure && p_hi <= p_cav)
    throw std::runtime_error(
        "Cavitation: no supply: both boundary pressures equal the cavitation pressure, so the "
        "mass-conserving (jfo) film content is not determined (the solution is not unique); raise "
        "a boundary pressure above the cavitation pressure");

  // Scale of the pressure unknown: the larger of the supply pressure difference and the
  // full-film pressure excursion.
  double excursion = 0;
  for (const auto i : locally_owned_dofs)
    excursion = std::max(excursion, std::abs(locally_relevant_solution[i] - p_cav));
  pressure_scale = std::max(Utilities::MPI::max(excursion, mpi_communicator), 1e-300);

  reynolds_diagonal.reinit(locally_owned_dofs, mpi_communicator);

  // Reynolds: warm start from the full-film solution clipped at p_cav.
  TrilinosWrappers::MPI::Vector u_owned(locally_owned_dofs, mpi_communicator);
  for (const auto i : locally_owned_dofs)
    u_owned[i] = std::max((locally_relevant_solution[i] - p_cav) / pressure_scale, 0.0);
  u_owned.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector u(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  u = u_owned;

  TrilinosWrappers::MPI::Vector rhs(locally_owned_dofs, mpi_communicator),
      du(locally_owned_dofs, mpi_communicator);
  // Residual scale: the Couette + squeeze + pressure flow right-hand side of the full film.
  const double flow_scale = std::max(system_rhs.l2_norm(), 1e-300);
  if (jfo)
  {
    solve_jfo(flow_scale);
    return;
  }
  std::vector<types::global_dof_index> previous_set = {
      std::numeric_limits<types::global_dof_index>::max()};
  double residual = 0;
  bool converged = false;
  unsigned int it = 0;
  for (; it < cavitation.maximum_iterations; ++it)
  {
    residual = assemble_reynolds_system(u, true, rhs) / flow_scale;
    const auto &set = active_set;
    const bool same_set =
        Utilities::MPI::min(static_cast<int>(set == previous_set), mpi_communicator) == 1;
    if (same_set && residual < cavitation.tolerance)
    {
      converged = true;
      break;
    }
    previous_set = set;
    factorize();
    du = 0;
    solve_linear_system(rhs, du);
    homogeneous_constraints.set_zero(du);
    u_owned.add(1.0, du);
    u = u_owned;
  }
  cavitation_iterations = it;
  cavitation_residual = residual;
  if (!converged)
  {
    std::ostringstream s;
    s << "Cavitation (reynolds): no convergence in " << cavitation.maximum_iterations
      << " Newton iterations (relative mass residual " << residual << ", tolerance "
      << cavitation.tolerance << "); refine the mesh or raise Cavitation/Maximum iterations";
    throw std::runtime_error(s.str());
  }
  // The last assembly built the Jacobian at the solution: factorise it for linearized_loads.
  factorize();
  TrilinosWrappers::MPI::Vector p(locally_owned_dofs, mpi_communicator);
  for (const auto i : locally_owned_dofs)
    p[i] = p_cav + pressure_scale * u_owned[i];
  p.compress(VectorOperation::insert);
  locally_relevant_solution = p;
  last_iterations += it;
}

/// Loads of the solved state, or (with `perturbation`) their derivative for a perturbation whose
/// nodal pressure and void-fraction changes are dp, dv. One routine, so that the linearisation
/// differentiates exactly what the loads integrate.
std::vector<FilmLoads> ReynoldsSolver::integrate_loads(
    const std::vector<const FilmPerturbation *> &perturbations,
    const std::vector<const TrilinosWrappers::MPI::Vector *> &dp_nodal,
    const std::vector<const TrilinosWrappers::MPI::Vector *> &dv_nodal) const
{
  // One cell loop for the solved state (perturbations = {nullptr}) or for all perturbation
  // directions at once (the film data at each quadrature point are computed once).
  const unsigned int n_k = perturbations.size();
  const bool base = n_k == 1 && perturbations[0] == nullptr;
  const QGauss<2> quadrature(polynomial_degree + 2); // the assembly's rule (see there)
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), dofs_per_cell = fe->n_dofs_per_cell();
  std::vector<double> p(n_q), v(n_q), indicator(n_q, 0.0);
  std::vector<Tensor<1, 2>> grad_p(n_q), grad_v(n_q);
  std::vector<std::vector<double>> dp_k(n_k, std::vector<double>(n_q, 0.0)), dv_k = dp_k;
  std::vector<std::vector<Tensor<1, 2>>> grad_dp_k(n_k, std::vector<Tensor<1, 2>>(n_q)),
      grad_dv_k = grad_dp_k;
  std::vector<types::global_dof_index> dofs(dofs_per_cell);

  const IndexSet &inner_dofs = inner_boundary_dofs, &outer_dofs = outer_boundary_dofs;

  const double mu = conditions.viscosity;
  const double p_ref = conditions.reference_pressure;
  const bool clip = cavitation.model == Cavitation::half_sommerfeld;
  const bool jfo = cavitation.model == Cavitation::jfo;
  const double p_cav = cavitation.pressure;
  const double cpsi = std::cos(film.tilt_angle), spsi = std::sin(film.tilt_angle);
  // Below this the film counts as cavitated (pressure at p_cav, or void fraction above zero).
  const double p_tol = 1e-9 * std::max(pressure_scale, 1.0);

  TrilinosWrappers::MPI::Vector cavitation_indicator;
  if (base && cavitation.is_nonlinear())
  {
    TrilinosWrappers::MPI::Vector owned(locally_owned_dofs, mpi_communicator);
    for (const auto i : locally_owned_dofs)
      owned[i] =
          (jfo ? locally_relevant_void[i] > 0 : locally_relevant_solution[i] <= p_cav + p_tol)
              ? 1.0
              : 0.0;
    owned.compress(VectorOperation::insert);
    cavitation_indicator.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    cavitation_indicator = owned;
  }

  // sums: F, Mx, My, Mr, Mt, residual inner, residual outer, friction, area, cavitated area,
  // squeeze flow, contact force, contact Mx, contact My, real contact area
  std::vector<std::vector<double>> sums(n_k, std::vector<double>(15, 0.0));
  double p_min = std::numeric_limits<double>::max(), p_max = -p_min;
  std::vector<Vector<double>> local_residual_k(n_k, Vector<double>(dofs_per_cell));

  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_values(locally_relevant_solution, p);
      fe_values.get_function_gradients(locally_relevant_solution, grad_p);
      if (jfo)
      {
        fe_values.get_function_values(locally_relevant_void, v);
        fe_values.get_function_gradients(locally_relevant_void, grad_v);
      }
      else
        std::fill(v.begin(), v.end(), 0.0), std::fill(grad_v.begin(), grad_v.end(), Tensor<1, 2>());
      for (unsigned int k = 0; k < n_k; ++k)
      {
        if (k < dp_nodal.size() && dp_nodal[k])
        {
          fe_values.get_function_values(*dp_nodal[k], dp_k[k]);
          fe_values.get_function_gradients(*dp_nodal[k], grad_dp_k[k]);
        }
        if (k < dv_nodal.size() && dv_nodal[k])
        {
          fe_values.get_function_values(*dv_nodal[k], dv_k[k]);
          fe_values.get_function_gradients(*dv_nodal[k], grad_dv_k[k]);
        }
        local_residual_k[k] = 0;
      }
      const double tau = jfo ? streamline_tau(cell) : 0.0;
      if (base && cavitation.is_nonlinear())
        fe_values.get_function_values(cavitation_indicator, indicator);
      cell->get_dof_indices(dofs);
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> &x = fe_values.quadrature_point(q);
        const LocalFilm f = local_film(x);
        const double r = f.r, theta = f.theta, h = f.h, JxW = fe_values.JxW(q);
        const Tensor<1, 2> &uc = f.u;
        const double s = 1 - v[q]; // liquid fraction
        for (unsigned int k = 0; k < n_k; ++k)
        {
          const FilmPerturbation *perturbation = perturbations[k];
          const std::vector<double> &dp = dp_k[k], &dv = dv_k[k];
          const std::vector<Tensor<1, 2>> &grad_dp = grad_dp_k[k], &grad_dv = grad_dv_k[k];
          std::vector<double> &sum = sums[k];
          Vector<double> &local_residual = local_residual_k[k];
          double dh = 0, dh_t = 0;
          if (perturbation)
          {
            dh = perturbation->dh ? perturbation->dh(r, theta) : 0.0;
            dh_t = perturbation->dh_dt ? perturbation->dh_dt(r, theta) : 0.0;
          }

          // Pressure in the loads: half-Sommerfeld clips it (and freezes the clipped region in
          // the linearisation); the other models use the solved field. The asperity contact
          // pressure (zero without a contact model) adds to it.
          const bool clipped = clip && p[q] < p_cav;
          const double contact_p = perturbation ? f.dcontact_dh * dh : f.contact_pressure;
          const double load_p =
              (perturbation ? (clipped ? 0.0 : dp[q]) : (clipped ? p_cav : p[q]) - p_ref) +
              contact_p;
          sum[0] += load_p * JxW;
          sum[1] += load_p * x[1] * JxW;
          sum[2] += -load_p * x[0] * JxW;
          sum[3] += -load_p * (x[0] * cpsi + x[1] * spsi) * JxW;
          sum[4] += load_p * (x[1] * cpsi - x[0] * spsi) * JxW;
          sum[8] += JxW;
          sum[11] += contact_p * JxW;
          sum[12] += contact_p * x[1] * JxW;
          sum[13] += -contact_p * x[0] * JxW;
          if (!perturbation && contact.enabled())
            sum[14] += contact.real_contact_area_fraction(h) * JxW;
          // Cavitated area: half-Sommerfeld where the clipped pressure applies; reynolds and jfo
          // where the interpolated nodal cavitation indicator is at least 1/2 (nodal, so that the
          // overshoot of higher-order interpolants at the cavity edge does not count).
          if (clipped || (cavitation.is_nonlinear() && indicator[q] >= 0.5))
            sum[9] += JxW;

          // Shear on the rotor face, as a torque resisting the rotor, -r tau_1: Couette part
          // (carried by the liquid fraction) and Poiseuille part; with roughness the Patir-Cheng
          // shear-stress factors (FlowFactors::rotor_shear_stress).
          const double dp_dtheta = -x[1] * grad_p[q][0] + x[0] * grad_p[q][1];
          const double s_clamped = std::clamp(s, 0.0, 1.0);
          const double u1 = conditions.rotor_speed * r, u2 = conditions.stator_speed * r;
          auto couette = [&](double hh)
          { return -flow_factors.rotor_shear_stress(std::max(hh, 1e-300), mu, u1, u2, 0.0) * r; };
          auto poiseuille = [&](double hh, double dpdx) {
            return -flow_factors.rotor_shear_stress(std::max(hh, 1e-300), mu, 0.0, 0.0, dpdx) * r;
          };
          if (!perturbation)
          {
            sum[7] += (s_clamped * couette(h) + poiseuille(h, dp_dtheta / r)) * JxW;
            sum[10] += s * f.squeeze * JxW;
            p_min = std::min(p_min, p[q]);
            p_max = std::max(p_max, p[q]);
          }
          else
          {
            const double ddp_dtheta = -x[1] * grad_dp[q][0] + x[0] * grad_dp[q][1];
            const double eps = 1e-7 * h;
            const double dcouette = (couette(h + eps) - couette(h - eps)) / (2 * eps);
            const double dpois =
                (poiseuille(h + eps, dp_dtheta / r) - poiseuille(h - eps, dp_dtheta / r)) /
                (2 * eps);
            sum[7] += (-dv[q] * couette(h) + s * dcouette * dh + dpois * dh +
                       poiseuille(h, ddp_dtheta / r)) *
                      JxW;
            sum[10] += (-dv[q] * f.squeeze + s * f.dsqueeze_dht * dh_t) * JxW;
          }

          // Residual of the unconstrained weak form in m^3/s (its linearisation with a
          // perturbation): R_i = int (K grad p - s c) . grad phi_i + s dh_T/dt phi_i
          //                      - tau div(v c) (u . grad phi_i).
          Tensor<1, 2> flux;
          double volume, streamline;
          if (!perturbation)
          {
            flux = f.K * grad_p[q] - s * f.c;
            volume = s * f.squeeze;
            streamline = -tau * (f.c * grad_v[q] + v[q] * f.c_div);
          }
          else
          {
            flux = f.K * grad_dp[q] + dh * (f.dK_dh * grad_p[q]) - (s * dh * f.dc_dh - dv[q] * f.c);
            volume = s * f.dsqueeze_dht * dh_t - dv[q] * f.squeeze;
            const double d = 1e-6;
            const double ddh_dtheta =
                perturbation->dh
                    ? (perturbation->dh(r, theta + d) - perturbation->dh(r, theta - d)) / (2 * d)
                    : 0.0;
            // (second derivatives of the flow factors in h are neglected here)
            streamline = -tau * (f.c * grad_dv[q] + dv[q] * f.c_div + dh * (f.dc_dh * grad_v[q]) +
                                 v[q] * f.dc_div_factor * ddh_dtheta);
          }
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            local_residual(i) +=
                (flux * fe_values.shape_grad(i, q) + volume * fe_values.shape_value(i, q) +
                 streamline * (uc * fe_values.shape_grad(i, q))) *
                JxW;
        }
      }
      for (unsigned int k = 0; k < n_k; ++k)
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          if (inner_dofs.is_element(dofs[i]))
            sums[k][5] += local_residual_k[k](i);
          if (outer_dofs.is_element(dofs[i]))
            sums[k][6] += local_residual_k[k](i);
        }
    }
  if (base)
    for (const auto i : locally_owned_dofs)
    {
      // Nodal values too: for Lagrange elements they are point values of p_h.
      p_min = std::min(p_min, locally_relevant_solution[i]);
      p_max = std::max(p_max, locally_relevant_solution[i]);
    }
  std::vector<FilmLoads> result;
  for (unsigned int k = 0; k < n_k; ++k)
  {
    std::vector<double> total(sums[k].size());
    MPI_Allreduce(sums[k].data(), total.data(), static_cast<int>(total.size()), MPI_DOUBLE, MPI_SUM,
                  mpi_communicator);
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
      loads.min_film = film.minimum().value;
      loads.min_film_over_sigma = flow_factors.is_smooth() && !contact.enabled()
                                      ? std::numeric_limits<double>::infinity()
                                      : loads.min_film / flow_factors.composite_roughness();
      loads.cavitated_fraction = total[9] / total[8];
      loads.min_pressure = Utilities::MPI::min(p_min, mpi_communicator);
      loads.max_pressure = Utilities::MPI::max(p_max, mpi_communicator);
    }
    result.push_back(loads);
  }
  return result;
}

FilmLoads ReynoldsSolver::compute_loads() const
{
  TimerOutput::Scope t(timer, "loads");
  return integrate_loads({nullptr}, {}, {})[0];
}

FilmLoads ReynoldsSolver::linearized_loads(const FilmPerturbation &perturbation) const
{
  return linearized_loads(std::vector<FilmPerturbation>{perturbation})[0];
}

std::vector<FilmLoads>
ReynoldsSolver::linearized_loads(const std::vector<FilmPerturbation> &perturbations) const
{
  TimerOutput::Scope t(timer, "linearized solve");
  const QGauss<2> quadrature(polynomial_degree + 2); // the assembly's rule
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), n = fe->n_dofs_per_cell();
  const unsigned int n_perturbations = perturbations.size();
  std::vector<double> v(n_q);
  std::vector<Tensor<1, 2>> grad_p(n_q), grad_v(n_q);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<Vector<double>> cell_rhs(n_perturbations, Vector<double>(n));
  const bool nonlinear = cavitation.is_nonlinear();
  const bool jfo = cavitation.model == Cavitation::jfo;

  // d(residual)/dh in each perturbation direction, scaled like the system by 12 mu / C0^3; the
  // perturbed unknown has homogeneous Dirichlet data. For reynolds/jfo the matrix is the
  // Jacobian of the converged state (jfo: the FB-Newton Jacobian, whose eliminations move the
  // cavity boundary with the perturbation; reynolds: the active set, frozen). One cell loop for
  // all right-hand sides, one solve each with the factorisation of run().
  const AffineConstraints<double> &homogeneous = homogeneous_constraints;

  std::vector<TrilinosWrappers::MPI::Vector> rhs(
      n_perturbations, TrilinosWrappers::MPI::Vector(locally_owned_dofs, mpi_communicator));
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_gradients(locally_relevant_solution, grad_p);
      if (jfo)
      {
        fe_values.get_function_values(locally_relevant_void, v);
        fe_values.get_function_gradients(locally_relevant_void, grad_v);
      }
      const double tau = jfo ? streamline_tau(cell) : 0.0;
      for (auto &c : cell_rhs)
        c = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const LocalFilm f = local_film(fe_values.quadrature_point(q));
        const double r = f.r, theta = f.theta, JxW = fe_values.JxW(q);
        const double s = jfo ? 1 - v[q] : 1.0;
        for (unsigned int k = 0; k < n_perturbations; ++k)
        {
          const FilmPerturbation &perturbation = perturbations[k];
          const double dh = perturbation.dh ? perturbation.dh(r, theta) : 0.0;
          const double dh_dt = perturbation.dh_dt ? perturbation.dh_dt(r, theta) : 0.0;
          const Tensor<1, 2> dflux = dh * (f.dK_dh * grad_p[q]) - s * dh * f.dc_dh;
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
            cell_rhs[k](i) -= equation_scale *
                              (dflux * fe_values.shape_grad(i, q) +
                               s * f.dsqueeze_dht * dh_dt * fe_values.shape_value(i, q) +
                               streamline * (f.u * fe_values.shape_grad(i, q))) *
                              JxW;
        }
      }
      cell->get_dof_indices(dofs);
      for (unsigned int k = 0; k < n_perturbations; ++k)
        homogeneous.distribute_local_to_global(cell_rhs[k], dofs, rhs[k]);
    }

  std::vector<TrilinosWrappers::MPI::Vector> dp_all(n_perturbations), dv_all(n_perturbations);
  for (unsigned int k = 0; k < n_perturbations; ++k)
  {
    rhs[k].compress(VectorOperation::add);
    if (cavitation.model == Cavitation::reynolds)
    {
      for (const auto i : active_set)
        rhs[k][i] = 0; // frozen cavity: p stays p_cav there
      rhs[k].compress(VectorOperation::insert);
    }
    TrilinosWrappers::MPI::Vector du(locally_owned_dofs, mpi_communicator);
    solve_linear_system(rhs[k], du);
    homogeneous.distribute(du);

    // Nodal perturbations of pressure and void fraction.
    TrilinosWrappers::MPI::Vector dp_owned(locally_owned_dofs, mpi_communicator),
        dv_owned(locally_owned_dofs, mpi_communicator);
    for (const auto i : locally_owned_dofs)
    {
      if (!nonlinear)
        dp_owned[i] = du[i];
      else if (!jfo)
        dp_owned[i] = pressure_scale * du[i];
      else if (jfo_keep_pressure[i] > 0.5)
      {
        dp_owned[i] = pressure_scale * du[i];
        dv_owned[i] = jfo_elimination[i] * du[i];
      }
      else
      {
        dv_owned[i] = du[i];
        dp_owned[i] = pressure_scale * jfo_elimination[i] * du[i];
      }
    }
    dp_owned.compress(VectorOperation::insert);
    dv_owned.compress(VectorOperation::insert);
    dp_all[k].reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    dv_all[k].reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    dp_all[k] = dp_owned;
    dv_all[k] = dv_owned;
  }
  std::vector<const FilmPerturbation *> directions;
  std::vector<const TrilinosWrappers::MPI::Vector *> dp_pointers, dv_pointers;
  for (unsigned int k = 0; k < n_perturbations; ++k)
  {
    directions.push_back(&perturbations[k]);
    dp_pointers.push_back(&dp_all[k]);
    dv_pointers.push_back(jfo ? &dv_all[k] : nullptr);
  }
  return integrate_loads(directions, dp_pointers, dv_pointers);
}

FilmLoads ReynoldsSolver::run(const FilmThickness &film_in,
                              const OperatingConditions &conditions_in,
                              const unsigned int coarsening)
{
  film = film_in;
  conditions = conditions_in;
  flow_factors.validate();
  contact.validate();
  // With rough faces in asperity contact a film that touches down is carried by the asperities
  // (h is the distance between the mean planes, Green (2002) Eq. 24; it may be <= 0).
  film.validate(contact.enabled() && !flow_factors.is_smooth());
  conditions.validate();
  flow_factors.reset_clamp_record();
  equation_scale = 12 * conditions.viscosity / Utilities::fixed_power<3>(film.clearance);
  timer.reset();
  current_coarsening = coarsening;
  coarse_iterations = 0;
  setup_system(coarsening);
  assemble_system();
  solve();
  cavitation_iterations = 0;
  cavitation_residual = 0;
  pressure_scale = 1;
  locally_relevant_void.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  if (cavitation.is_nonlinear())
    solve_cavitation();
  return compute_loads();
}

std::map<std::string, double> ReynoldsSolver::stage_times() const
{
  return timer.get_summary_data(TimerOutput::total_wall_time);
}

double ReynoldsSolver::volume_flow_through_circle(const double rho,
                                                  const unsigned int n_points) const
{
  std::vector<Point<2>> points;
  if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    for (unsigned int k = 0; k < n_points; ++k)
    {
      const double t = 2 * M_PI * (k + 0.5) / n_points;
      points.emplace_back(rho * std::cos(t), rho * std::sin(t));
    }
  Utilities::MPI::RemotePointEvaluation<2> cache;
  const auto gradients = VectorTools::point_gradients<1>(*mapping, dof_handler,
                                                         locally_relevant_solution, points, cache);
  double flow = 0;
  for (unsigned int k = 0; k < points.size(); ++k)
  {
    const Point<2> &x = points[k];
    const LocalFilm f = local_film(x);
    const Tensor<1, 2> er({x[0] / rho, x[1] / rho});
    flow += -(er * (f.K * gradients[k])) * rho * 2 * M_PI / n_points;
  }
  return Utilities::MPI::sum(flow, mpi_communicator);
}

double ReynoldsSolver::l2_error(const Function<2> &exact) const
{
  Vector<float> cellwise(triangulation.n_active_cells());
  VectorTools::integrate_difference(*mapping, dof_handler, locally_relevant_solution, exact,
                                    cellwise, QGauss<2>(polynomial_degree + 2),
                                    VectorTools::L2_norm);
  return VectorTools::compute_global_error(triangulation, cellwise, VectorTools::L2_norm);
}

namespace
{
/// Film thickness and volume flux q = -h^3/(12 mu) grad p + h u_mean at the output points.
class FilmPostprocessor : public DataPostprocessor<2>
{
public:
  explicit FilmPostprocessor(std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film)
      : film(std::move(film))
  {
  }
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
    {
      // q = -K grad p + c: the full-film flux (in a JFO cavity the Couette part carries the
      // liquid fraction: multiply c by liquid_fraction there; the pressure part is zero).
      const ReynoldsSolver::LocalFilm f = film(in.evaluation_points[q]);
      const Tensor<1, 2> flux = -(f.K * in.solution_gradients[q]) + f.c;
      out[q](0) = f.h;
      out[q](1) = flux[0];
      out[q](2) = flux[1];
      out[q](3) = f.h_T;
      out[q](4) = f.phi_r;
      out[q](5) = f.phi_theta;
      out[q](6) = f.phi_s;
      out[q](7) = f.contact_pressure;
    }
  }
  std::vector<std::string> get_names() const override
  {
    return {"film_thickness",
            "volume_flux",
            "volume_flux",
            "expected_gap",
            "pressure_flow_factor_r",
            "pressure_flow_factor_theta",
            "shear_flow_factor",
            "contact_pressure"};
  }
  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  get_data_component_interpretation() const override
  {
    std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
        8, DataComponentInterpretation::component_is_scalar);
    kinds[1] = kinds[2] = DataComponentInterpretation::component_is_part_of_vector;
    return kinds;
  }
  UpdateFlags get_needed_update_flags() const override
  {
    return update_values | update_gradients | update_quadrature_points;
  }

private:
  std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film;
};
} // namespace

std::string ReynoldsSolver::write_output(const std::string &directory) const
{
  FilmPostprocessor postprocessor([this](const Point<2> &x) { return local_film(x); });
  DataOut<2> data_out;
  data_out.attach_dof_handler(dof_handler);
  data_out.add_data_vector(locally_relevant_solution, "pressure");
  data_out.add_data_vector(locally_relevant_solution, postprocessor);
  // Liquid fraction s = 1 - v (1 in the full film; nodal, so exact at the nodes) and an
  // indicator of the cavitated region (1 where p <= p_cav or s < 1).
  TrilinosWrappers::MPI::Vector liquid(locally_owned_dofs, mpi_communicator),
      cavitated(locally_owned_dofs, mpi_communicator);
  const double p_tol = 1e-9 * std::max(pressure_scale, 1.0);
  for (const auto i : locally_owned_dofs)
  {
    const double v = cavitation.model == Cavitation::jfo ? locally_relevant_void[i] : 0.0;
    liquid[i] = 1 - v;
    const bool below = cavitation.model != Cavitation::none &&
                       locally_relevant_solution[i] <= cavitation.pressure + p_tol;
    cavitated[i] = (v > 0 || below) ? 1.0 : 0.0;
  }
  liquid.compress(VectorOperation::insert);
  cavitated.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector liquid_ghosted(locally_owned_dofs, locally_relevant_dofs,
                                               mpi_communicator),
      cavitated_ghosted(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  liquid_ghosted = liquid;
  cavitated_ghosted = cavitated;
  data_out.add_data_vector(liquid_ghosted, "liquid_fraction");
  data_out.add_data_vector(cavitated_ghosted, "cavitated");
  Vector<float> subdomain(triangulation.n_active_cells());
  subdomain = triangulation.locally_owned_subdomain();
  data_out.add_data_vector(subdomain, "rank");
  DataOutBase::VtkFlags flags;
  flags.write_higher_order_cells = false;
  data_out.set_flags(flags);
  data_out.build_patches(*mapping, polynomial_degree, DataOut<2>::curved_inner_cells);
  const std::string pvtu =
      data_out.write_vtu_with_pvtu_record(directory + "/", "solution", 0, mpi_communicator, 4, 1);
  if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
  {
    std::ofstream pvd(directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, {{0.0, pvtu}});
  }
  return "solution.pvd";
}

FilmLoads estimate_load_errors(const FilmLoads &fine, const FilmLoads &coarse,
                               const unsigned int degree)
{
  const double factor = 1.0 / (std::pow(2.0, degree) - 1);
  auto e = [&](double FilmLoads::*member)
  { return std::abs(fine.*member - coarse.*member) * factor; };
  FilmLoads error;
  for (auto member :
       {&FilmLoads::force_z, &FilmLoads::moment_x, &FilmLoads::moment_y,
        &FilmLoads::moment_restoring, &FilmLoads::moment_transverse, &FilmLoads::leakage_inner,
        &FilmLoads::leakage_outer, &FilmLoads::friction_torque, &FilmLoads::cavitated_fraction})
    error.*member = e(member);
  return error;
}

} // namespace sealfe
