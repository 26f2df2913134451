// StatorTransient::run: the state of Eq. 26 (scaled) integrated by SUNDIALS IDA — variable-order
// BDF with a dense Newton solver whose difference Jacobian IDA itself rebuilds only when the
// Newton iteration or the step size asks for it.
//
// Why IDA through its C interface and not deal.II's SUNDIALS::IDA / ARKode wrappers (9.4): the
// wrappers check SUNDIALS' return codes with debug-only assertions (a failed integration would go
// on silently in a release build), hide the integrator memory (no step counts, no maximum number
// of steps), and the ARKode wrapper re-ran the Jacobian set-up before every linear solve
// (150 film evaluations per step on this problem).
#include <sealfe/dynamics/stator_transient.h>
#include <sealfe/film/film_expression.h>
#include <sealfe/io/interrupt.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

namespace sealfe
{
namespace
{
using State = TransientState;

/// What IDA's residual needs: the physical rate, the state scaling and which components of the
/// state the integrator carries (a rigid rotor's states are left out: IDA's error norm is a
/// root mean square over the components, so idle zeros would loosen the tolerance).
struct ResidualData
{
  const TransientState *scale;
  std::vector<unsigned int> active;
  std::function<State(double, const State &)> rate;
  std::function<double(double, const State &)> contact_margin;
  std::string failure;
};

/// g(t, y) = contact force - threshold x F_cls: its zeros are touch-down and lift-off.
int contact_root(const realtype t, N_Vector yy, N_Vector, realtype *g, void *user_data)
{
  auto &data = *static_cast<ResidualData *>(user_data);
  const double *y = N_VGetArrayPointer(yy);
  try
  {
    State physical{};
    for (unsigned int k = 0; k < data.active.size(); ++k)
      physical[data.active[k]] = y[k] * (*data.scale)[data.active[k]];
    g[0] = data.contact_margin(t, physical);
    return std::isfinite(g[0]) ? 0 : 1;
  }
  catch (std::exception &e)
  {
    data.failure = e.what();
    return 1;
  }
}

/// F(t, y, y') = y' - f(t, y) on the scaled state. A film or contact that cannot be evaluated
/// (the faces touch down past the contact model's range) is a recoverable failure: IDA retries
/// with a smaller step.
int residual(const realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user_data)
{
  auto &data = *static_cast<ResidualData *>(user_data);
  const double *y = N_VGetArrayPointer(yy), *dy = N_VGetArrayPointer(yp);
  double *r = N_VGetArrayPointer(rr);
  try
  {
    State physical{};
    for (unsigned int k = 0; k < data.active.size(); ++k)
      physical[data.active[k]] = y[k] * (*data.scale)[data.active[k]];
    const State d = data.rate(t, physical);
    for (unsigned int k = 0; k < data.active.size(); ++k)
    {
      r[k] = dy[k] - d[data.active[k]] / (*data.scale)[data.active[k]];
      if (!std::isfinite(r[k]))
        return 1;
    }
    return 0;
  }
  catch (std::exception &e)
  {
    data.failure = e.what();
    return 1;
  }
}

/// IDA's own messages go into the stop reason instead of onto stderr.
void keep_message(int, const char *, const char *function, char *message, void *user_data)
{
  *static_cast<std::string *>(user_data) = std::string(function) + ": " + message;
}

/// Owner of the SUNDIALS objects (freed in reverse order of creation).
struct IdaObjects
{
  SUNContext context = nullptr;
  N_Vector y = nullptr, yp = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  void *memory = nullptr;
  ~IdaObjects()
  {
    if (memory)
      IDAFree(&memory);
    if (solver)
      SUNLinSolFree(solver);
    if (matrix)
      SUNMatDestroy(matrix);
    if (yp)
      N_VDestroy(yp);
    if (y)
      N_VDestroy(y);
    if (context)
      SUNContext_Free(&context);
  }
};

void check(const int flag, const char *what)
{
  if (flag < 0)
    throw std::runtime_error(std::string("transient: SUNDIALS IDA set-up failed in ") + what);
}
} // namespace

StatorTransient::Result StatorTransient::run() const
{
  // rotor-borne features turn with the shaft: a film of loads made beforehand holds one angle
  if (seal.geometry.features_on_rotor() && !film.turns_rotor_features())
    throw std::runtime_error("Transient: surface features on the rotor turn with it, but the " +
                             to_string(film.level()) +
                             " film holds its loads at one rotor angle (Phase); use Transient/"
                             "Film level = finite element");
  // a formula in t changes the film by itself; tables and closed forms hold it at t = 0
  if (seal.geometry.expression && seal.geometry.expression->depends_on_time() &&
      !film.turns_rotor_features())
    throw std::runtime_error("Transient: the Film expression depends on t, but the " +
                             to_string(film.level()) +
                             " film holds its loads at t = 0; use Transient/Film level = "
                             "finite element");
  Result result;
  // the integrated components: Z, Z', a, a', beta, V; the rotor's tilt and rate when it is
  // flexible; its axial displacement and rate when it is axially flexible
  std::vector<unsigned int> active = {0, 1, 2, 3, 4, 5, 6, 7};
  if (seal.rotor.flexible)
    active.insert(active.end(), {8, 9, 10, 11});
  if (seal.rotor.axially_flexible())
    active.insert(active.end(), {12, 13});
  const unsigned int n = active.size();
  ResidualData data{&scale, active, [this](double t, const State &y) { return rate(t, y); },
                    [this](double t, const State &y) { return contact_margin(t, y); }, ""};
  std::string ida_message;

  const State y0 = initial_state();
  const State dy0 = rate(0, y0);
  result.samples.push_back(sample(0, y0));
  if (after_output)
    after_output(0);

  IdaObjects ida;
  check(SUNContext_Create(nullptr, &ida.context), "SUNContext_Create");
  ida.y = N_VNew_Serial(n, ida.context);
  ida.yp = N_VNew_Serial(n, ida.context);
  for (unsigned int k = 0; k < n; ++k)
  {
    NV_Ith_S(ida.y, k) = y0[active[k]] / scale[active[k]];
    NV_Ith_S(ida.yp, k) = dy0[active[k]] / scale[active[k]];
  }
  ida.memory = IDACreate(ida.context);
  if (!ida.memory)
    throw std::runtime_error("transient: SUNDIALS IDA could not be created");
  check(IDAInit(ida.memory, residual, 0.0, ida.y, ida.yp), "IDAInit");
  check(IDASetErrHandlerFn(ida.memory, keep_message, &ida_message), "IDASetErrHandlerFn");
  check(IDASStolerances(ida.memory, settings.relative_tolerance, settings.absolute_tolerance),
        "IDASStolerances");
  check(IDASetUserData(ida.memory, &data), "IDASetUserData");
  check(IDASetMaxNumSteps(ida.memory, settings.maximum_steps), "IDASetMaxNumSteps");
  check(IDASetMaxOrd(ida.memory, settings.order), "IDASetMaxOrd");
  check(IDASetMinStep(ida.memory, settings.minimum_step), "IDASetMinStep");
  // Newton stops at 0.1 of the local error test instead of SUNDIALS' 0.33: with the stiff
  // squeeze film (D_zz / m ~ 1e9 1/s) and loose tolerances a single Newton iteration with an old
  // Jacobian passed the looser test and left the step size stuck near 1e-7 s (measured)
  check(IDASetNonlinConvCoef(ida.memory, 0.1), "IDASetNonlinConvCoef");
  check(IDASetInitStep(ida.memory, std::min(1e-6, settings.output_interval)), "IDASetInitStep");
  // a start that excites the squeeze film's fast mode (a stator at rest against a whirling
  // rotor) needs steps far below 1e-6 s at tight tolerances: IDA's 10 error-test failures per
  // step (a factor 4 each) end near 1e-12 s, which was not enough (measured at 1e-9)
  check(IDASetMaxErrTestFails(ida.memory, 30), "IDASetMaxErrTestFails");
  ida.matrix = SUNDenseMatrix(n, n, ida.context);
  ida.solver = SUNLinSol_Dense(ida.y, ida.matrix, ida.context);
  check(IDASetLinearSolver(ida.memory, ida.solver, ida.matrix), "IDASetLinearSolver");
  // touch-down and lift-off located between steps (the output rows only bracket them)
  check(IDARootInit(ida.memory, 1, contact_root), "IDARootInit");

  // outputs and the corners of the ramps: no step straddles a jump of the forcing's slope
  std::vector<double> stops = seal.ramps.corners();
  stops.erase(
      std::remove_if(stops.begin(), stops.end(), [&](double t) { return t >= settings.end_time; }),
      stops.end());
  stops.push_back(settings.end_time);
  std::size_t next_stop = 0;
  check(IDASetStopTime(ida.memory, stops[0]), "IDASetStopTime");

  const unsigned long rows =
      std::llround(std::ceil(settings.end_time / settings.output_interval - 1e-9));
  double t_reached = 0;
  auto last_report = std::chrono::steady_clock::now();
  for (unsigned long k = 1; k <= rows; ++k)
  {
    if (interrupt::requested())
    {
      // between output rows: the rows so far are whole, and kept
      std::ostringstream s;
      s << interrupt::reason() << " at t = " << t_reached << " s";
      result.stop_reason = s.str();
      break;
    }
    const double t_out = std::min(settings.end_time, k * settings.output_interval);
    realtype t_ret = t_reached;
    int flag = IDA_SUCCESS;
    while (t_ret < t_out && flag >= 0)
    {
      flag = IDASolve(ida.memory, t_out, &t_ret, ida.y, ida.yp, IDA_NORMAL);
      if (flag == IDA_ROOT_RETURN)
      {
        int direction = 0;
        IDAGetRootInfo(ida.memory, &direction);
        result.contact_events.push_back({t_ret, seal.ramps.speed.value(t_ret), direction < 0});
      }
      if (flag == IDA_TSTOP_RETURN && next_stop + 1 < stops.size())
        IDASetStopTime(ida.memory, stops[++next_stop]);
    }
    if (flag < 0)
    {
      std::ostringstream s;
      s << "the integrator stopped at t = " << t_ret << " s (IDA: " << ida_message << ")";
      if (!data.failure.empty())
        s << "; last film/contact failure: " << data.failure;
      result.stop_reason = s.str();
      break;
    }
    t_reached = t_out;
    if (std::chrono::steady_clock::now() - last_report > std::chrono::seconds(2))
    {
      // progress on stderr for long runs (a finite-element film at every evaluation)
      long steps = 0;
      IDAGetNumSteps(ida.memory, &steps);
      std::cerr << "sealfe transient: t = " << t_out << " of " << settings.end_time << " s, "
                << steps << " steps, " << evaluations << " film evaluations" << std::endl;
      last_report = std::chrono::steady_clock::now();
    }
    State y{};
    for (unsigned int k = 0; k < n; ++k)
      y[active[k]] = NV_Ith_S(ida.y, k) * scale[active[k]];
    result.samples.push_back(sample(t_out, y));
    if (after_output)
      after_output(t_out);
  }
  result.complete = result.stop_reason.empty();
  long steps = 0, fails = 0, conv = 0, setups = 0;
  IDAGetNumSteps(ida.memory, &steps);
  IDAGetNumErrTestFails(ida.memory, &fails);
  IDAGetNumNonlinSolvConvFails(ida.memory, &conv);
  IDAGetNumLinSolvSetups(ida.memory, &setups);
  result.steps = steps;
  result.error_test_failures = fails;
  result.convergence_failures = conv;
  result.jacobian_setups = setups;
  result.film_evaluations = evaluations;
  return result;
}
} // namespace sealfe
