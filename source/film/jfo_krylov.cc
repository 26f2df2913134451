#include <sealfe/film/jfo_krylov.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
#include <Ifpack.h>
#include <Ifpack_Preconditioner.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using namespace dealii;

namespace
{
double seconds_since(const std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The principal submatrix of M on the dofs `rows` (in that order), numbered 0.. on `map`.
std::unique_ptr<Epetra_CrsMatrix> principal_submatrix(const Epetra_CrsMatrix &M,
                                                      const std::vector<unsigned int> &rows,
                                                      const std::vector<int> &position,
                                                      const std::vector<char> &in_block,
                                                      const Epetra_Map &map)
{
  std::vector<int> counts(rows.size(), 0);
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    int entries;
    double *values;
    int *columns;
    M.ExtractMyRowView(rows[r], entries, values, columns);
    for (int e = 0; e < entries; ++e)
      counts[r] += in_block[M.ColMap().GID(columns[e])] ? 1 : 0;
  }
  auto S = std::make_unique<Epetra_CrsMatrix>(Copy, map, counts.data(), true);
  std::vector<int> sub_columns;
  std::vector<double> sub_values;
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    int entries;
    double *values;
    int *columns;
    M.ExtractMyRowView(rows[r], entries, values, columns);
    sub_columns.clear();
    sub_values.clear();
    for (int e = 0; e < entries; ++e)
    {
      const int j = M.ColMap().GID(columns[e]);
      if (in_block[j])
      {
        sub_columns.push_back(position[j]);
        sub_values.push_back(values[e]);
      }
    }
    const int err = S->InsertGlobalValues(static_cast<int>(r), sub_columns.size(),
                                          sub_values.data(), sub_columns.data());
    if (err < 0)
      throw std::runtime_error("ActiveSetKrylov: InsertGlobalValues failed");
  }
  S->FillComplete();
  return S;
}
} // namespace

/// One approximate block inverse: ML AMG, Ifpack ILU/ILUT, or an Amesos factorisation.
struct ActiveSetKrylov::BlockSolver
{
  std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
  std::unique_ptr<Ifpack_Preconditioner> ifpack;
  std::unique_ptr<Epetra_LinearProblem> problem;
  std::unique_ptr<Amesos_BaseSolver> direct;
  Epetra_Vector *lhs = nullptr, *rhs = nullptr;

  void factorize(Epetra_CrsMatrix &A)
  {
    problem = std::make_unique<Epetra_LinearProblem>();
    problem->SetOperator(&A);
    Amesos factory;
    direct.reset(
        factory.Create(A.NumGlobalRows() < 20000 ? "Amesos_Klu" : "Amesos_Mumps", *problem));
    if (!direct)
      throw std::runtime_error("ActiveSetKrylov: no Amesos solver");
    direct->SymbolicFactorization();
    direct->NumericFactorization();
  }
  void apply(const Epetra_Vector &r, Epetra_Vector &z) const
  {
    if (amg)
      amg->trilinos_operator().ApplyInverse(r, z);
    else if (ifpack)
      ifpack->ApplyInverse(r, z);
    else
    {
      problem->SetLHS(&z);
      problem->SetRHS(const_cast<Epetra_Vector *>(&r));
      direct->Solve();
    }
  }
};

ActiveSetKrylov::ActiveSetKrylov() = default;
ActiveSetKrylov::~ActiveSetKrylov() = default;

void ActiveSetKrylov::setup(const TrilinosWrappers::SparseMatrix &J,
                            const std::vector<char> &full_film, const std::vector<double> &x,
                            const std::vector<double> &y, const Options &opts)
{
  auto start = std::chrono::steady_clock::now();
  matrix = &J;
  options = opts;
  const Epetra_CrsMatrix &M = J.trilinos_matrix();
  const std::size_t n = M.NumMyRows();
  if (static_cast<long long>(n) != M.NumGlobalRows64() || full_film.size() != n)
    throw std::runtime_error("ActiveSetKrylov: one rank only");
  F.clear();
  C.clear();
  std::vector<int> position(n);
  std::vector<char> in_F(n), in_C(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    auto &block = full_film[i] ? F : C;
    position[i] = block.size();
    block.push_back(i);
    in_F[i] = full_film[i] ? 1 : 0;
    in_C[i] = full_film[i] ? 0 : 1;
  }
  map_F = std::make_unique<Epetra_Map>(static_cast<int>(F.size()), 0, M.Comm());
  map_C = std::make_unique<Epetra_Map>(static_cast<int>(C.size()), 0, M.Comm());
  J_FF = principal_submatrix(M, F, position, in_F, *map_F);
  J_CC = principal_submatrix(M, C, position, in_C, *map_C);
  // the coupling the triangle keeps: rows of the block solved second, columns of the first
  const auto &second = opts.lower ? C : F;
  const auto &first_flag = opts.lower ? in_F : in_C;
  coupling_start.assign(1, 0);
  coupling_column.clear();
  coupling_value.clear();
  for (const auto row : second)
  {
    int entries;
    double *values;
    int *columns;
    M.ExtractMyRowView(row, entries, values, columns);
    for (int e = 0; e < entries; ++e)
    {
      const int j = M.ColMap().GID(columns[e]);
      if (first_flag[j] && values[e] != 0)
      {
        coupling_column.push_back(j);
        coupling_value.push_back(values[e]);
      }
    }
    coupling_start.push_back(coupling_column.size());
  }
  r_F = std::make_unique<Epetra_Vector>(*map_F);
  z_F = std::make_unique<Epetra_Vector>(*map_F);
  r_C = std::make_unique<Epetra_Vector>(*map_C);
  z_C = std::make_unique<Epetra_Vector>(*map_C);
  split_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  solve_FF = std::make_unique<BlockSolver>();
  if (opts.full_film == FullFilmSolver::amg)
  {
    // FilmLinearSolver's cg-amg settings (film_linear_solver.cc: aggregation on the distance
    // Laplacian of the support points, Chebyshev smoothing) for a symmetric block
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = opts.degree > 1;
    data.smoother_sweeps = 3;
    data.aggregation_threshold = 0.02;
    data.smoother_type = "Chebyshev";
    Teuchos::ParameterList list;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    data.set_parameters(list, constant_modes, static_cast<const Epetra_RowMatrix &>(*J_FF));
    std::vector<double> fx(F.size()), fy(F.size());
    for (std::size_t k = 0; k < F.size(); ++k)
    {
      fx[k] = x[F[k]];
      fy[k] = y[F[k]];
    }
    list.set("aggregation: aux: enable", true);
    list.set("aggregation: aux: threshold", 0.05);
    list.set("x-coordinates", fx.data());
    list.set("y-coordinates", fy.data());
    solve_FF->amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    solve_FF->amg->initialize(*J_FF, list);
  }
  else
    solve_FF->factorize(*J_FF);
  full_film_setup_seconds = seconds_since(start);

  start = std::chrono::steady_clock::now();
  solve_CC = std::make_unique<BlockSolver>();
  if (C.empty())
    ;
  else if (opts.transport == TransportSolver::direct)
    solve_CC->factorize(*J_CC);
  else
  {
    Ifpack factory;
    const bool ilut = opts.transport == TransportSolver::ilut;
    solve_CC->ifpack.reset(factory.Create(ilut ? "ILUT" : "ILU", J_CC.get(), 0));
    if (!solve_CC->ifpack)
      throw std::runtime_error("ActiveSetKrylov: no Ifpack preconditioner");
    Teuchos::ParameterList list;
    if (ilut)
    {
      list.set("fact: ilut level-of-fill", 2.0);
      list.set("fact: drop tolerance", 1e-6);
    }
    else
      list.set("fact: level-of-fill", 0);
    solve_CC->ifpack->SetParameters(list);
    if (solve_CC->ifpack->Initialize() != 0 || solve_CC->ifpack->Compute() != 0)
      throw std::runtime_error("ActiveSetKrylov: Ifpack set-up failed");
  }
  transport_setup_seconds = seconds_since(start);
}

void ActiveSetKrylov::vmult(VectorType &dst, const VectorType &src) const
{
  const double *r = src.trilinos_vector()[0];
  double *z = dst.trilinos_vector()[0];
  double *rF = r_F->Values(), *rC = r_C->Values();
  for (std::size_t k = 0; k < F.size(); ++k)
    rF[k] = r[F[k]];
  for (std::size_t k = 0; k < C.size(); ++k)
    rC[k] = r[C[k]];
  // first block, then the second with the first's result moved to the right-hand side
  const auto &first = options.lower ? F : C, &second = options.lower ? C : F;
  Epetra_Vector &r_first = options.lower ? *r_F : *r_C, &z_first = options.lower ? *z_F : *z_C;
  Epetra_Vector &r_second = options.lower ? *r_C : *r_F, &z_second = options.lower ? *z_C : *z_F;
  const BlockSolver &solve_first = options.lower ? *solve_FF : *solve_CC;
  const BlockSolver &solve_second = options.lower ? *solve_CC : *solve_FF;
  if (!first.empty())
    solve_first.apply(r_first, z_first);
  for (std::size_t k = 0; k < first.size(); ++k)
    z[first[k]] = z_first[k];
  for (std::size_t k = 0; k < second.size(); ++k)
  {
    double sum = r_second[k];
    for (std::size_t e = coupling_start[k]; e < coupling_start[k + 1]; ++e)
      sum -= coupling_value[e] * z[coupling_column[e]];
    r_second[k] = sum;
  }
  if (!second.empty())
    solve_second.apply(r_second, z_second);
  for (std::size_t k = 0; k < second.size(); ++k)
    z[second[k]] = z_second[k];
}

unsigned int ActiveSetKrylov::solve(const VectorType &b, VectorType &x, const double target,
                                    const unsigned int max_iterations) const
{
  SolverControl control(max_iterations, std::max(target, std::numeric_limits<double>::min()), false,
                        false);
  // right preconditioning: the tolerance applies to the true residual
  SolverGMRES<VectorType>::AdditionalData data(options.restart + 2, true);
  SolverGMRES<VectorType> gmres(control, data);
  try
  {
    gmres.solve(*matrix, x, b, *this);
  }
  catch (SolverControl::NoConvergence &)
  {
    return std::numeric_limits<unsigned int>::max();
  }
  return control.last_step();
}

void probe_active_set_round(
    const TrilinosWrappers::SparseMatrix &matrix, const TrilinosWrappers::MPI::Vector &rhs,
    const TrilinosWrappers::MPI::Vector &direct, const std::vector<char> &full_film,
    const std::vector<char> &constrained, const std::vector<double> &base_value,
    const std::vector<double> &x, const std::vector<double> &y, const unsigned int degree,
    const double flow_scale, const double direct_seconds, const unsigned int round,
    const std::string &variants, std::ostream &out)
{
  const std::size_t n = full_film.size();
  const double *wd = direct.trilinos_vector()[0];
  const double b_norm = rhs.l2_norm();
  auto flip_differences = [&](const double *w)
  {
    unsigned int differences = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!constrained[i] && ((base_value[i] + w[i] < -1e-12) != (base_value[i] + wd[i] < -1e-12)))
        ++differences;
    return differences;
  };
  unsigned int direct_flips = 0;
  for (std::size_t i = 0; i < n; ++i)
    direct_flips += !constrained[i] && base_value[i] + wd[i] < -1e-12;
  {
    TrilinosWrappers::MPI::Vector r(rhs);
    matrix.vmult(r, direct);
    r.sadd(-1.0, 1.0, rhs);
    out << "krylov-probe round " << round << " n " << n << " |b|/flow_scale " << b_norm / flow_scale
        << " direct " << direct_seconds << " s, flips " << direct_flips << ", direct residual/|b| "
        << r.l2_norm() / b_norm << std::endl;
  }
  std::istringstream list(variants == "1" ? std::string("amg:ilu:lower") : variants);
  std::string variant;
  while (std::getline(list, variant, ','))
  {
    ActiveSetKrylov::Options options;
    options.degree = degree;
    std::istringstream parts(variant);
    std::string ff, cc, tri;
    std::getline(parts, ff, ':');
    std::getline(parts, cc, ':');
    std::getline(parts, tri, ':');
    options.full_film = ff == "direct" ? ActiveSetKrylov::FullFilmSolver::direct
                                       : ActiveSetKrylov::FullFilmSolver::amg;
    options.transport = cc == "direct" ? ActiveSetKrylov::TransportSolver::direct
                        : cc == "ilut" ? ActiveSetKrylov::TransportSolver::ilut
                                       : ActiveSetKrylov::TransportSolver::ilu;
    options.lower = tri != "upper";
    ActiveSetKrylov krylov;
    try
    {
      krylov.setup(matrix, full_film, x, y, options);
    }
    catch (std::exception &e)
    {
      out << "krylov-probe round " << round << " " << variant << " set-up failed: " << e.what()
          << std::endl;
      continue;
    }
    out << "krylov-probe round " << round << " " << variant << " |F| " << krylov.n_full_film()
        << " |C| " << krylov.n_cavitated() << " split " << krylov.split_seconds << " s, FF set-up "
        << krylov.full_film_setup_seconds << " s, CC set-up " << krylov.transport_setup_seconds
        << " s" << std::endl;
    for (const double tolerance : {1e-6, 1e-8, 1e-10})
    {
      TrilinosWrappers::MPI::Vector w(rhs);
      w = 0;
      const auto start = std::chrono::steady_clock::now();
      const unsigned int its = krylov.solve(rhs, w, tolerance * b_norm, 400);
      const double seconds = seconds_since(start);
      TrilinosWrappers::MPI::Vector difference(w);
      difference -= direct;
      out << "krylov-probe round " << round << " " << variant << " tol " << tolerance << " its "
          << (its == std::numeric_limits<unsigned int>::max() ? std::string("fail")
                                                              : std::to_string(its))
          << " solve " << seconds << " s, set-up + solve "
          << krylov.split_seconds + krylov.full_film_setup_seconds +
                 krylov.transport_setup_seconds + seconds
          << " s, |w-w_direct|_inf " << difference.linfty_norm() << ", flip decisions differing "
          << flip_differences(w.trilinos_vector()[0]) << std::endl;
      if (its == std::numeric_limits<unsigned int>::max())
        break;
    }
  }
}

} // namespace sealfe
