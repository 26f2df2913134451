#include <sealfe/reynolds_solver.h>

#include <deal.II/base/array_view.h>
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

#include <cmath>
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
  FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
  Vector<double> cell_rhs(dofs_per_cell);
  std::vector<types::global_dof_index> local_dof_indices(dofs_per_cell);

  const double C0 = film.clearance;
  const double mean_speed = conditions.mean_speed();

  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      cell_matrix = 0;
      cell_rhs = 0;
      fe_values.reinit(cell);
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        const Point<2> &x = fe_values.quadrature_point(q);
        const double r = x.norm(), theta = std::atan2(x[1], x[0]);
        const double h = film.value(r, theta);
        const double k = Utilities::fixed_power<3>(h / C0);
        // h u_mean, with u_mean = w_mean * (-y, x)
        const Tensor<1, 2> hu({-h * mean_speed * x[1], h * mean_speed * x[0]});
        double volume_source = film.d_dt(r, theta);
        if (source)
          volume_source += source(x);
        const double JxW = fe_values.JxW(q);
        for (const unsigned int i : fe_values.dof_indices())
        {
          const Tensor<1, 2> grad_i = fe_values.shape_grad(i, q);
          for (const unsigned int j : fe_values.dof_indices())
            cell_matrix(i, j) += k * (grad_i * fe_values.shape_grad(j, q)) * JxW;
          cell_rhs(i) +=
              equation_scale * (hu * grad_i - volume_source * fe_values.shape_value(i, q)) * JxW;
        }
      }
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

FilmLoads ReynoldsSolver::compute_loads() const
{
  TimerOutput::Scope t(timer, "loads");
  const QGauss<2> quadrature(polynomial_degree + 2); // the assembly's rule (see there)
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), dofs_per_cell = fe->n_dofs_per_cell();
  std::vector<double> p(n_q);
  std::vector<Tensor<1, 2>> grad_p(n_q);
  std::vector<types::global_dof_index> dofs(dofs_per_cell);

  IndexSet inner_dofs, outer_dofs;
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), inner_dofs,
                                  {AnnulusMesh::inner_boundary});
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), outer_dofs,
                                  {AnnulusMesh::outer_boundary});

  const double mu = conditions.viscosity, mean_speed = conditions.mean_speed();
  const double relative_speed = conditions.rotor_speed - conditions.stator_speed;
  const double p_ref = conditions.reference_pressure;
  const bool clip = cavitation.model == Cavitation::half_sommerfeld;
  const double p_cav = cavitation.pressure;
  const double cpsi = std::cos(film.tilt_angle), spsi = std::sin(film.tilt_angle);

  // sums: F, Mx, My, Mr, Mt, residual inner, residual outer, friction, area, cavitated area
  std::vector<double> sum(10, 0.0);
  double p_min = std::numeric_limits<double>::max(), p_max = -p_min;
  Vector<double> local_residual(dofs_per_cell);

  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_values(locally_relevant_solution, p);
      fe_values.get_function_gradients(locally_relevant_solution, grad_p);
      cell->get_dof_indices(dofs);
      local_residual = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> &x = fe_values.quadrature_point(q);
        const double r = x.norm(), theta = std::atan2(x[1], x[0]);
        const double h = film.value(r, theta);
        const double JxW = fe_values.JxW(q);
        // Half-Sommerfeld: sub-cavity pressures are replaced by p_cav in the loads.
        const bool cavitated = clip && p[q] < p_cav;
        const double dp = (cavitated ? p_cav : p[q]) - p_ref;
        if (cavitated)
          sum[9] += JxW;
        sum[0] += dp * JxW;
        sum[8] += JxW;
        sum[1] += dp * x[1] * JxW;
        sum[2] += -dp * x[0] * JxW;
        sum[3] += -dp * (x[0] * cpsi + x[1] * spsi) * JxW;
        sum[4] += dp * (x[1] * cpsi - x[0] * spsi) * JxW;
        // Shear on the rotor face (Couette + Poiseuille), as a torque resisting the rotor:
        // tau = mu (w1 - w2) r / h + (h / 2) (1/r) dp/dtheta, times the lever arm r.
        const double dp_dtheta = -x[1] * grad_p[q][0] + x[0] * grad_p[q][1];
        sum[7] += (mu * relative_speed * r * r / h + 0.5 * h * dp_dtheta) * JxW;
        p_min = std::min(p_min, p[q]);
        p_max = std::max(p_max, p[q]);

        // Residual of the unconstrained weak form, in physical units (m^3/s):
        // R_i = int K grad p . grad phi_i - h u . grad phi_i + dh/dt phi_i
        const double K = h * h * h / (12 * mu);
        const Tensor<1, 2> hu({-h * mean_speed * x[1], h * mean_speed * x[0]});
        double volume_source = film.d_dt(r, theta);
        if (source)
          volume_source += source(x);
        const Tensor<1, 2> flux_term = K * grad_p[q] - hu;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          local_residual(i) += (flux_term * fe_values.shape_grad(i, q) +
                                volume_source * fe_values.shape_value(i, q)) *
                               JxW;
      }
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        if (inner_dofs.is_element(dofs[i]))
          sum[5] += local_residual(i);
        if (outer_dofs.is_element(dofs[i]))
          sum[6] += local_residual(i);
      }
    }
  // Nodal values too: for Lagrange elements they are point values of p_h.
  for (const auto i : locally_owned_dofs)
  {
    p_min = std::min(p_min, locally_relevant_solution[i]);
    p_max = std::max(p_max, locally_relevant_solution[i]);
  }
  std::vector<double> total(sum.size());
  MPI_Allreduce(sum.data(), total.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM,
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
  loads.area = total[8];
  loads.min_pressure = Utilities::MPI::min(p_min, mpi_communicator);
  loads.max_pressure = Utilities::MPI::max(p_max, mpi_communicator);
  loads.min_film = film.minimum().value;
  loads.cavitated_fraction = total[9] / total[8];
  return loads;
}

FilmLoads ReynoldsSolver::linearized_loads(const FilmPerturbation &perturbation) const
{
  TimerOutput::Scope t(timer, "linearized solve");
  const QGauss<2> quadrature(polynomial_degree + 2); // the assembly's rule
  FEValues<2> fe_values(*mapping, *fe, quadrature,
                        update_values | update_gradients | update_quadrature_points |
                            update_JxW_values);
  const unsigned int n_q = quadrature.size(), dofs_per_cell = fe->n_dofs_per_cell();
  std::vector<Tensor<1, 2>> grad_p(n_q);
  std::vector<types::global_dof_index> dofs(dofs_per_cell);
  Vector<double> cell_rhs(dofs_per_cell);
  const double mu = conditions.viscosity, mean_speed = conditions.mean_speed();

  // dR_i = int (3 h^2 dh / (12 mu)) grad p . grad phi_i - dh u . grad phi_i + dh_t phi_i,
  // scaled like the system by 12 mu / C0^3; the perturbed pressure has homogeneous Dirichlet data.
  AffineConstraints<double> homogeneous(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, homogeneous);
  for (const auto id : {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary})
    VectorTools::interpolate_boundary_values(*mapping, dof_handler, id,
                                             Functions::ZeroFunction<2>(), homogeneous);
  homogeneous.close();

  TrilinosWrappers::MPI::Vector rhs(locally_owned_dofs, mpi_communicator);
  auto perturbation_at = [&](const Point<2> &x, double &dh, double &dh_dt)
  {
    const double r = x.norm(), theta = std::atan2(x[1], x[0]);
    dh = perturbation.dh ? perturbation.dh(r, theta) : 0.0;
    dh_dt = perturbation.dh_dt ? perturbation.dh_dt(r, theta) : 0.0;
  };
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_gradients(locally_relevant_solution, grad_p);
      cell_rhs = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> &x = fe_values.quadrature_point(q);
        const double h = film.value(x.norm(), std::atan2(x[1], x[0]));
        double dh, dh_dt;
        perturbation_at(x, dh, dh_dt);
        const Tensor<1, 2> dflux = (3 * h * h * dh / (12 * mu)) * grad_p[q] -
                                   Tensor<1, 2>({-dh * mean_speed * x[1], dh * mean_speed * x[0]});
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          cell_rhs(i) -=
              equation_scale *
              (dflux * fe_values.shape_grad(i, q) + dh_dt * fe_values.shape_value(i, q)) *
              fe_values.JxW(q);
      }
      cell->get_dof_indices(dofs);
      homogeneous.distribute_local_to_global(cell_rhs, dofs, rhs);
    }
  rhs.compress(VectorOperation::add);

  TrilinosWrappers::MPI::Vector dp_owned(locally_owned_dofs, mpi_communicator);
  solve_linear_system(rhs, dp_owned);
  homogeneous.distribute(dp_owned);
  TrilinosWrappers::MPI::Vector dp(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  dp = dp_owned;

  // Integrate the perturbed loads (same definitions as compute_loads, linearised).
  IndexSet inner_dofs, outer_dofs;
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), inner_dofs,
                                  {AnnulusMesh::inner_boundary});
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), outer_dofs,
                                  {AnnulusMesh::outer_boundary});
  const bool clip = cavitation.model == Cavitation::half_sommerfeld;
  const double cpsi = std::cos(film.tilt_angle), spsi = std::sin(film.tilt_angle);
  const double relative_speed = conditions.rotor_speed - conditions.stator_speed;
  std::vector<double> p(n_q), dpv(n_q);
  std::vector<Tensor<1, 2>> grad_dp(n_q);
  std::vector<double> sum(8, 0.0);
  Vector<double> local_residual(dofs_per_cell);
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_values(locally_relevant_solution, p);
      fe_values.get_function_gradients(locally_relevant_solution, grad_p);
      fe_values.get_function_values(dp, dpv);
      fe_values.get_function_gradients(dp, grad_dp);
      cell->get_dof_indices(dofs);
      local_residual = 0;
      for (unsigned int q = 0; q < n_q; ++q)
      {
        const Point<2> &x = fe_values.quadrature_point(q);
        const double r = x.norm(), theta = std::atan2(x[1], x[0]);
        const double h = film.value(r, theta), JxW = fe_values.JxW(q);
        double dh, dh_dt;
        perturbation_at(x, dh, dh_dt);
        const double d = (clip && p[q] < cavitation.pressure) ? 0.0 : dpv[q];
        sum[0] += d * JxW;
        sum[1] += d * x[1] * JxW;
        sum[2] += -d * x[0] * JxW;
        sum[3] += -d * (x[0] * cpsi + x[1] * spsi) * JxW;
        sum[4] += d * (x[1] * cpsi - x[0] * spsi) * JxW;
        const double dp_dtheta = -x[1] * grad_p[q][0] + x[0] * grad_p[q][1];
        const double ddp_dtheta = -x[1] * grad_dp[q][0] + x[0] * grad_dp[q][1];
        sum[7] += (-mu * relative_speed * r * r * dh / (h * h) + 0.5 * dh * dp_dtheta +
                   0.5 * h * ddp_dtheta) *
                  JxW;
        const double K = h * h * h / (12 * mu), dK = 3 * h * h * dh / (12 * mu);
        const Tensor<1, 2> dflux = K * grad_dp[q] + dK * grad_p[q] -
                                   Tensor<1, 2>({-dh * mean_speed * x[1], dh * mean_speed * x[0]});
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          local_residual(i) +=
              (dflux * fe_values.shape_grad(i, q) + dh_dt * fe_values.shape_value(i, q)) * JxW;
      }
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        if (inner_dofs.is_element(dofs[i]))
          sum[5] += local_residual(i);
        if (outer_dofs.is_element(dofs[i]))
          sum[6] += local_residual(i);
      }
    }
  std::vector<double> total(sum.size());
  MPI_Allreduce(sum.data(), total.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM,
                mpi_communicator);
  FilmLoads d;
  d.force_z = total[0];
  d.moment_x = total[1];
  d.moment_y = total[2];
  d.moment_restoring = total[3];
  d.moment_transverse = total[4];
  d.leakage_inner = -total[5];
  d.leakage_outer = -total[6];
  d.friction_torque = total[7];
  return d;
}

FilmLoads ReynoldsSolver::run(const FilmThickness &film_in,
                              const OperatingConditions &conditions_in,
                              const unsigned int coarsening)
{
  film = film_in;
  conditions = conditions_in;
  film.validate();
  conditions.validate();
  equation_scale = 12 * conditions.viscosity / Utilities::fixed_power<3>(film.clearance);
  timer.reset();
  setup_system(coarsening);
  assemble_system();
  solve();
  return compute_loads();
}

std::map<std::string, double> ReynoldsSolver::stage_times() const
{
  return timer.get_summary_data(TimerOutput::total_wall_time);
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
  FilmPostprocessor(const FilmThickness &film, const OperatingConditions &conditions)
      : film(film), conditions(conditions)
  {
  }
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
    {
      const Point<2> &x = in.evaluation_points[q];
      const double h = film.value(x.norm(), std::atan2(x[1], x[0]));
      const double K = h * h * h / (12 * conditions.viscosity);
      const double w = conditions.mean_speed();
      out[q](0) = h;
      out[q](1) = -K * in.solution_gradients[q][0] - h * w * x[1];
      out[q](2) = -K * in.solution_gradients[q][1] + h * w * x[0];
    }
  }
  std::vector<std::string> get_names() const override
  {
    return {"film_thickness", "volume_flux", "volume_flux"};
  }
  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  get_data_component_interpretation() const override
  {
    return {DataComponentInterpretation::component_is_scalar,
            DataComponentInterpretation::component_is_part_of_vector,
            DataComponentInterpretation::component_is_part_of_vector};
  }
  UpdateFlags get_needed_update_flags() const override
  {
    return update_values | update_gradients | update_quadrature_points;
  }

private:
  const FilmThickness &film;
  const OperatingConditions &conditions;
};
} // namespace

std::string ReynoldsSolver::write_output(const std::string &directory) const
{
  FilmPostprocessor postprocessor(film, conditions);
  DataOut<2> data_out;
  data_out.attach_dof_handler(dof_handler);
  data_out.add_data_vector(locally_relevant_solution, "pressure");
  data_out.add_data_vector(locally_relevant_solution, postprocessor);
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
