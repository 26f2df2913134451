// Surface features on the rotor turn with it (FilmState::rotor_angle): the film is solved in the
// features' frame with the stator-frame parts (tilt, tilt rate, waviness, film formula) turned by
// -phi into it and the moments turned back (film_force_model.h, FiniteElementFilm::loads), and
// the transient sets phi = Int omega dt (stator_transient.h, film_frame). Theory: the film has no
// memory (full film) and each solve is one instant, so the loads at rotor angle phi are those of
// a stationary face pair with the features drawn at Phase + phi; N identical features repeat
// after 2 pi / N; an axisymmetric stator film sees the same face at every phi. The fields of a
// turned rotor are written in the stator frame.
#include <sealfe/coefficients/finite_element_film.h>
#include <sealfe/dynamics/stator_transient.h>
#include <sealfe/film/film_expression.h>
#include <sealfe/film/film_output.h>
#include <sealfe/film/surface_features.h>

#include <gtest/gtest.h>

#include <vtkCell.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "../surface_feature_seals.h"

namespace
{
namespace fs = std::filesystem;
using namespace sealfe;
using namespace sealfe::test;

// Few pads: the loads' dependence on the rotor angle is a product of the tilt's first harmonic
// with the pads' N-th, so it grows like (tilt ro / h)^(N - 1); three pads show it plainly.
constexpr unsigned int n_pads = 3;
constexpr double ambient = 1e4; // Pa

/// Three Rayleigh pads on the rotor (RayleighPadSeal: dam 25..35 mm, land film 2 um, 16 x 8
/// cells per pad, degree 2), drawn from `phase`, 1e4 Pa on both circles (p_cav = 0), rotor
/// 100 rad/s. With `stator_pattern` the stator-frame film has every part that must turn: 3 waves
/// of 0.2 um and a formula with an angle, a radius and the time in it.
FilmSettings pad_film(const double phase, const bool stator_pattern, const Cavitation cavitation)
{
  RayleighPadSeal seal;
  seal.pads = n_pads;
  seal.cells_per_pad = 16;
  FilmSettings s = seal.settings();
  auto features = std::make_shared<SurfaceFeatures>(*s.geometry.features);
  features->face = SurfaceFeatures::Face::rotor;
  features->phase = phase;
  s.geometry.features = features;
  // a low ambient (loads above it): the diverging parts of the tilted pads cavitate under JFO
  s.conditions.inner_pressure = s.conditions.outer_pressure = ambient;
  s.conditions.reference_pressure = ambient;
  s.cavitation.model = cavitation;
  s.cavitation.pressure = 0;
  if (stator_pattern)
  {
    s.geometry.wave_amplitude = 0.2e-6;
    s.geometry.wave_number = 3;
    s.geometry.wave_phase = 0.4;
    s.geometry.expression = std::make_shared<const FilmExpression>(
        "a*(r - 0.025)/0.01*cos(theta - 1.1) + b*sin(2*theta)*t", "a=0.2e-6, b=5e-6",
        s.geometry.outer_radius);
  }
  return s;
}

/// A tilted, squeezing state in the stator frame: tilt 1.7e-5 rad (0.6 um at ro) thickest at
/// 0.8 rad, tilt rates of 2e-3 rad/s, axial velocity 1e-5 m/s, t = 0.03 s.
FilmState tilted_state(const FilmSettings &s, const double rotor_angle)
{
  FilmState state = FilmState::from(s.geometry, s.conditions);
  const auto tilt = tilt_vector(1.7e-5, 0.8);
  state.tilt_x = tilt[0];
  state.tilt_y = tilt[1];
  state.tilt_rate_x = 2e-3;
  state.tilt_rate_y = -1e-3;
  state.axial_velocity = 1e-5;
  state.time = 0.03;
  state.rotor_angle = rotor_angle;
  return state;
}

struct Scales
{
  double force, moment, flow, torque;
};

Scales scales(const FilmLoads &l, const double ro)
{
  return {std::abs(l.force_z), std::abs(l.force_z) * ro,
          std::max(std::abs(l.leakage_inner), std::abs(l.leakage_outer)),
          std::abs(l.friction_torque)};
}

/// Largest departure of b from a, each load against its scale.
double departure(const FilmLoads &a, const FilmLoads &b, const Scales &s)
{
  return std::max({std::abs(a.force_z - b.force_z) / s.force,
                   std::abs(a.moment_x - b.moment_x) / s.moment,
                   std::abs(a.moment_y - b.moment_y) / s.moment,
                   std::abs(a.leakage_inner - b.leakage_inner) / s.flow,
                   std::abs(a.leakage_outer - b.leakage_outer) / s.flow,
                   std::abs(a.friction_torque - b.friction_torque) / s.torque,
                   std::abs(a.cavitated_fraction - b.cavitated_fraction)});
}

void print(const char *what, const FilmLoads &l)
{
  std::cout << what << ": force " << l.force_z << " N, moments " << l.moment_x << ", " << l.moment_y
            << " N m, leakage " << l.leakage_inner << ", " << l.leakage_outer << " m^3/s, friction "
            << l.friction_torque << " N m, cavitated " << l.cavitated_fraction << "\n";
}

// (a) Frame invariance. The loads of the pads turned by phi (solved in their frame, the stator's
// tilt, rates, waviness and formula turned by -phi, the moments turned back) equal those of an
// independently built film whose pads are drawn at Phase + phi and solved at rotor angle 0 (the
// two meshes are turned copies of each other: the discrete problems are the same up to
// round-off). Tolerance 1e-8: the JFO Newton tolerance (1e-10 relative mass residual) with
// margin; the full film is a direct solve. The snapshot (the loads at rotor angle 0, what the
// transients used before the features turned) must depart by orders of magnitude more (else the
// test proves nothing).
TEST(RotorFeatures, TurnedRotorIsTheStationaryFaceWithThePadsAtPhasePlusTheAngle)
{
  const double phi = 0.37; // not a multiple of the period 2 pi / 3
  for (const Cavitation cavitation : {Cavitation::none, Cavitation::jfo})
  {
    const FiniteElementFilm turning(pad_film(0, true, cavitation), MPI_COMM_WORLD);
    const FiniteElementFilm placed(pad_film(phi, true, cavitation), MPI_COMM_WORLD);
    const FilmSettings &base = turning.settings();
    const FilmLoads a = turning.loads(tilted_state(base, phi));
    const FilmLoads b = placed.loads(tilted_state(base, 0));
    const FilmLoads snapshot = turning.loads(tilted_state(base, 0));
    print("turned by phi", a);
    print("drawn at phi ", b);
    print("snapshot     ", snapshot);
    const Scales s = scales(b, base.geometry.outer_radius);
    const double d = departure(a, b, s), d_snapshot = departure(snapshot, b, s);
    std::cout << "departure from the pads drawn at phi: " << d << " (snapshot: " << d_snapshot
              << ")\n";
    EXPECT_LT(d, 1e-8);
    EXPECT_GT(d_snapshot, 1e-4);
    if (cavitation == Cavitation::jfo)
    {
      EXPECT_GT(b.cavitated_fraction, 0.0);
    }

    // the linearised coefficients turn the same way (K, D of the turned solve turned back)
    const FilmCoefficients ka = turning.coefficients(tilted_state(base, phi));
    const FilmCoefficients kb = placed.coefficients(tilted_state(base, 0));
    double k_scale = 0, d_scale = 0, k_err = 0, d_err = 0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        // dimensionally uniform (tilts as ro tilt, moments as M / ro)
        const double f = (i > 0 ? 1 / base.geometry.outer_radius : 1.0) *
                         (j > 0 ? 1 / base.geometry.outer_radius : 1.0);
        k_scale = std::max(k_scale, std::abs(kb.stiffness[i][j]) * f);
        d_scale = std::max(d_scale, std::abs(kb.damping[i][j]) * f);
        k_err = std::max(k_err, std::abs(ka.stiffness[i][j] - kb.stiffness[i][j]) * f);
        d_err = std::max(d_err, std::abs(ka.damping[i][j] - kb.damping[i][j]) * f);
      }
    std::cout << "coefficients: K " << k_err / k_scale << ", D " << d_err / d_scale << "\n";
    EXPECT_LT(k_err / k_scale, 1e-8);
    EXPECT_LT(d_err / d_scale, 1e-8);
  }
}

// (a') The fields of the turned rotor stand in the stator frame: the VTU of the film solved at
// rotor angle phi in the pads' frame, written turned by FiniteElementFilm::frame_angle (the
// transient's `Field output times`), is the VTU of the stationary face with the pads drawn at
// Phase + phi: the same points (the meshes are turned copies, cell by cell) carrying the same
// pressure, film thickness and flux vector inside every cell, to the float32 precision of the
// VTU (relative 6e-8; 1e-6 of each field's largest value). Written unturned, the points are phi r =
// 0.013 m away.
TEST(RotorFeatures, TransientFieldsStandInTheStatorFrame)
{
  const double phi = 0.37;
  const FiniteElementFilm turning(pad_film(0, true, Cavitation::none), MPI_COMM_WORLD);
  const FiniteElementFilm placed(pad_film(phi, true, Cavitation::none), MPI_COMM_WORLD);
  const FilmSettings &base = turning.settings();
  turning.loads(tilted_state(base, phi));
  placed.loads(tilted_state(base, 0));
  EXPECT_EQ(turning.frame_angle(), phi);
  EXPECT_EQ(placed.frame_angle(), 0.0);
  const fs::path dir = fs::temp_directory_path() / "sealfe_rotor_feature_fields";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_film_fields(turning.reynolds(), dir.string(), "turned", 0, FieldSelection(),
                    turning.frame_angle());
  write_film_fields(turning.reynolds(), dir.string(), "unturned", 0);
  write_film_fields(placed.reynolds(), dir.string(), "placed", 0);
  auto read = [&dir](const std::string &name)
  {
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName((dir / (name + "_0000.0.vtu")).c_str());
    reader->Update();
    return reader;
  };
  const auto turned = read("turned"), unturned = read("unturned"), drawn = read("placed");
  vtkUnstructuredGrid *a = turned->GetOutput(), *b = drawn->GetOutput(), *u = unturned->GetOutput();
  ASSERT_GT(b->GetNumberOfPoints(), 0);
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  double max_point = 0, max_unturned = 0;
  for (vtkIdType i = 0; i < b->GetNumberOfPoints(); ++i)
  {
    double xa[3], xb[3], xu[3];
    a->GetPoint(i, xa);
    b->GetPoint(i, xb);
    u->GetPoint(i, xu);
    max_point = std::max(max_point, std::hypot(xa[0] - xb[0], xa[1] - xb[1]));
    max_unturned = std::max(max_unturned, std::hypot(xu[0] - xb[0], xu[1] - xb[1]));
  }
  // the fields at the cells' interior points: the mesh follows the pads' steps, so a point on a
  // cell edge may lie on a step, where the film thickness jumps by the recess and either side is
  // a right answer for a round-off-different angle
  std::map<std::string, double> max_error, max_value;
  for (vtkIdType c = 0; c < b->GetNumberOfCells(); ++c)
  {
    vtkIdList *ids = b->GetCell(c)->GetPointIds();
    const int order = int(std::lround(std::sqrt(double(ids->GetNumberOfIds())))) - 1;
    for (vtkIdType k = 4 * order; k < ids->GetNumberOfIds(); ++k) // interior nodes (VTK order)
    {
      const vtkIdType i = ids->GetId(k);
      for (const char *name : {"pressure", "film_thickness", "volume_flux"})
      {
        vtkDataArray *fa = a->GetPointData()->GetArray(name),
                     *fb = b->GetPointData()->GetArray(name);
        ASSERT_TRUE(fa && fb) << name;
        for (int d = 0; d < fb->GetNumberOfComponents(); ++d)
        {
          max_error[name] =
              std::max(max_error[name], std::abs(fa->GetComponent(i, d) - fb->GetComponent(i, d)));
          max_value[name] = std::max(max_value[name], std::abs(fb->GetComponent(i, d)));
        }
      }
    }
  }
  std::cout << "fields turned by phi against the pads drawn at phi: points " << max_point
            << " m (unturned " << max_unturned << " m); pressure " << max_error["pressure"]
            << " of " << max_value["pressure"] << " Pa, flux " << max_error["volume_flux"] << " of "
            << max_value["volume_flux"] << " m^2/s\n";
  const double ro = base.geometry.outer_radius;
  EXPECT_LT(max_point, 1e-6 * ro);
  EXPECT_GT(max_unturned, 0.5 * phi * base.geometry.inner_radius);
  for (const char *name : {"pressure", "film_thickness", "volume_flux"})
    EXPECT_LT(max_error[name], 1e-6 * max_value[name]) << name;
  fs::remove_all(dir);
}

// (b) Periodicity: three identical pads turned by 2 pi / 3 more are the same face, so the loads
// repeat (to solver tolerance: the mesh has the pads' symmetry); half a period on they differ
// (the pads on a tilted, wavy film are not rotationally invariant: else (a) proves nothing).
TEST(RotorFeatures, LoadsRepeatAfterOnePadPeriod)
{
  const FiniteElementFilm film(pad_film(0, true, Cavitation::none), MPI_COMM_WORLD);
  const FilmSettings &base = film.settings();
  const double phi = 1.3, period = 2 * M_PI / n_pads;
  const FilmLoads a = film.loads(tilted_state(base, phi));
  const FilmLoads b = film.loads(tilted_state(base, phi + period));
  const FilmLoads c = film.loads(tilted_state(base, phi + 0.5 * period));
  print("phi           ", a);
  print("phi + P       ", b);
  print("phi + P/2     ", c);
  const Scales s = scales(a, base.geometry.outer_radius);
  std::cout << "departure after one period " << departure(a, b, s) << ", after half "
            << departure(a, c, s) << "\n";
  EXPECT_LT(departure(a, b, s), 1e-8);
  EXPECT_GT(departure(a, c, s), 1e-4);
}

// (c) Axisymmetric stator film (no tilt, no waviness; coning and a formula in r and t only): the
// turned face is the same face, so force, leakages and friction do not depend on phi, and the
// moments of three pads vanish by symmetry at every phi (exact; to round-off and solver
// tolerance: the moments' scale is force x ro). This case was exact before the features turned too:
// it guards the turned path.
TEST(RotorFeatures, AxisymmetricFilmLoadsDoNotDependOnTheRotorAngle)
{
  FilmSettings settings = pad_film(0, false, Cavitation::jfo);
  settings.geometry.coning = 1e-4;
  settings.geometry.expression = std::make_shared<const FilmExpression>(
      "a*((r - 0.025)/0.01)^2*(1 + t)", "a=0.3e-6", settings.geometry.outer_radius);
  const FiniteElementFilm film(settings, MPI_COMM_WORLD);
  FilmState state = FilmState::from(settings.geometry, settings.conditions);
  state.axial_velocity = 1e-5;
  state.time = 0.03;
  const FilmLoads still = film.loads(state);
  print("phi = 0  ", still);
  const Scales s = scales(still, settings.geometry.outer_radius);
  for (const double phi : {0.37, 1.9, -2.6})
  {
    state.rotor_angle = phi;
    const FilmLoads l = film.loads(state);
    print("turned   ", l);
    EXPECT_LT(departure(l, still, s), 1e-8);
    EXPECT_LT(std::hypot(l.moment_x, l.moment_y) / s.moment, 1e-8);
  }
}

// (d) In the transient (StatorTransient::sample, the film evaluation the integrator calls): the
// rotor has turned by phi(t) = Int omega dt (speed ramped 0 -> 100 rad/s over 20 ms: phi =
// omega t^2 / (2 t1) on the ramp, omega (t - t1/2) after it), the stator held tilted in space.
// The stator carries 3 waves. The film's moments in the inertial frame are those of the
// stationary face with the pads drawn at phi(t) (built independently), in both integration
// frames (inertial, turning with the shaft), also with the relative tilt turning in space at a
// rate g (seen in the turning frame as a' = R(-phi) g - omega J a); at constant speed they repeat
// after T = 2 pi / (N omega) = 20.9 ms, and half of T on they differ: the moments oscillate at
// N omega.
TEST(RotorFeatures, TransientMomentsOscillateAtThePadFrequency)
{
  const double omega = 100, t1 = 0.02;
  // the pads and 3 waves of 0.2 um on the stator (fixed in space, in both integration frames)
  const auto wavy_pads = [](const double phase)
  {
    FilmSettings s = pad_film(phase, false, Cavitation::none);
    s.geometry.wave_amplitude = 0.2e-6;
    s.geometry.wave_number = 3;
    s.geometry.wave_phase = 0.4;
    return s;
  };
  const FilmSettings settings = wavy_pads(0);
  const FiniteElementFilm film(settings, MPI_COMM_WORLD);
  FlexibleStatorSeal seal;
  seal.geometry = settings.geometry;
  seal.conditions = settings.conditions;
  seal.runout.tilt = 0;
  seal.thermal.model = ThermalConing::Model::none;
  seal.ramps.speed = Ramp{0, omega, t1, 1e300, 1e300};
  seal.ramps.outer_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.ramps.inner_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.contact =
      FaceContact(AsperityContact(AsperityContact::Model::none, AsperityContactParameters()),
                  settings.geometry.inner_radius, settings.geometry.outer_radius, 8, 96);
  const auto tilt = tilt_vector(1.7e-5, 0.8); // the relative tilt, fixed in space
  const double period = 2 * M_PI / (n_pads * omega);

  auto rotor_angle = [&](const double t)
  { return t < t1 ? omega * t * t / (2 * t1) : omega * (t - 0.5 * t1); };
  const double ro = settings.geometry.outer_radius;
  double moment_scale = 0;
  std::vector<std::array<double, 2>> inertial_moments;
  for (const double t : {0.011, 0.05, 0.05 + period, 0.05 + 0.5 * period})
    for (const double rate : {0.0, 1.0})
    {
      // the stationary face with the pads at phi(t), the stator's tilt where it is; with `rate`,
      // the relative tilt also turning in space at 2e-3, -1e-3 rad/s (the squeeze of a nutating
      // stator; its rate as seen in the integration frame below)
      const std::array<double, 2> tilt_rate{{2e-3 * rate, -1e-3 * rate}};
      const double phi = rotor_angle(t);
      const FiniteElementFilm placed(wavy_pads(phi), MPI_COMM_WORLD);
      FilmState state = FilmState::from(settings.geometry, settings.conditions);
      state.tilt_x = tilt[0];
      state.tilt_y = tilt[1];
      state.tilt_rate_x = tilt_rate[0];
      state.tilt_rate_y = tilt_rate[1];
      state.rotor_speed = seal.ramps.speed.value(t);
      state.time = t;
      const FilmLoads expected = placed.loads(state);
      moment_scale = std::max(moment_scale, std::abs(expected.force_z) * ro);
      for (const std::string frame : {"inertial", "rotating"})
      {
        TransientSettings ts;
        ts.frame = frame;
        const StatorTransient transient(seal, film, ts);
        TransientState y{};
        // the relative tilt in the integration frame and its rate there: the inertial rate g
        // turned into the frame, minus omega J a in the turning frame (film_state: the film takes
        // a' + omega J a there, turned back into space)
        const bool rotating = frame == "rotating";
        const double psi = rotating ? -seal.ramps.speed.integral(t) : 0.0;
        const auto a = turned(tilt, psi), g = turned(tilt_rate, psi);
        y[2] = a[0];
        y[3] = a[1];
        y[4] = g[0] + (rotating ? state.rotor_speed * a[1] : 0.0);
        y[5] = g[1] - (rotating ? state.rotor_speed * a[0] : 0.0);
        const TransientSample sample = transient.sample(t, y);
        std::cout << "t = " << t << " s, phi = " << phi << ", " << frame << " frame: moments "
                  << sample.film_moment_x << ", " << sample.film_moment_y << " N m (pads drawn at "
                  << "phi: " << expected.moment_x << ", " << expected.moment_y << "), force "
                  << sample.film_force << " (" << expected.force_z << ")\n";
        EXPECT_NEAR(sample.film_force, expected.force_z, 1e-8 * std::abs(expected.force_z));
        EXPECT_NEAR(sample.film_moment_x, expected.moment_x,
                    1e-8 * std::abs(expected.force_z) * ro);
        EXPECT_NEAR(sample.film_moment_y, expected.moment_y,
                    1e-8 * std::abs(expected.force_z) * ro);
        if (!rotating && rate == 0)
          inertial_moments.push_back({{sample.film_moment_x, sample.film_moment_y}});
      }
    }
  // inertial_moments: t = 0.011, 0.05, 0.05 + T, 0.05 + T/2
  const auto difference = [&](const unsigned int i, const unsigned int j)
  {
    return std::hypot(inertial_moments[i][0] - inertial_moments[j][0],
                      inertial_moments[i][1] - inertial_moments[j][1]) /
           moment_scale;
  };
  std::cout << "moment change over T: " << difference(1, 2) << ", over T/2: " << difference(1, 3)
            << " of the moment scale\n";
  EXPECT_LT(difference(1, 2), 1e-8);
  EXPECT_GT(difference(1, 3), 1e-4);
}

// (d') The same through an integration (StatorTransient::run, IDA, inertial frame): a stator so
// heavy (1e15 kg, 1e15 kg m^2) that over two pad periods its tilt stays the initial 1.7e-5 rad
// and its axial position C0 (relative drift < 1e-12), speed 100 rad/s from t = 0, three pads and
// three waves. The output rows, T / 4 apart (T = 2 pi / (3 omega)), repeat after four rows and
// differ after two. (The turning integration frame is checked by (d) at the same film
// evaluations; integrated there, the tilt fixed in space turns at -omega and drifts by IDA's
// tolerance.)
TEST(RotorFeatures, IntegratedTransientRepeatsAfterOnePadPeriod)
{
  const double omega = 100;
  FilmSettings settings = pad_film(0, false, Cavitation::none);
  settings.geometry.wave_amplitude = 0.2e-6;
  settings.geometry.wave_number = 3;
  const FiniteElementFilm film(settings, MPI_COMM_WORLD);
  FlexibleStatorSeal seal;
  seal.geometry = settings.geometry;
  seal.conditions = settings.conditions;
  seal.runout.tilt = 0;
  seal.stator.mass = 1e15;
  seal.stator.transverse_inertia = 1e15;
  seal.thermal.model = ThermalConing::Model::none;
  seal.ramps.speed = Ramp{omega, omega, 0, 1e300, 1e300};
  seal.ramps.outer_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.ramps.inner_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.contact =
      FaceContact(AsperityContact(AsperityContact::Model::none, AsperityContactParameters()),
                  settings.geometry.inner_radius, settings.geometry.outer_radius, 8, 96);
  const double period = 2 * M_PI / (n_pads * omega);
  TransientSettings ts;
  ts.frame = "inertial";
  ts.end_time = 2 * period;
  ts.output_interval = period / 4;
  ts.initial_axial_offset = 0;
  ts.initial_tilt = 1.7e-5;
  ts.initial_tilt_angle = 0.8;
  const StatorTransient transient(seal, film, ts);
  const StatorTransient::Result r = transient.run();
  ASSERT_TRUE(r.complete) << r.stop_reason;
  ASSERT_GE(r.samples.size(), 9u);
  std::cout << r.steps << " steps, " << r.film_evaluations << " film evaluations\n";
  for (const TransientSample &row : r.samples)
    std::cout << "  t = " << row.time << " s: moments " << row.film_moment_x << ", "
              << row.film_moment_y << " N m, force " << row.film_force << " N, tilt "
              << row.relative_tilt << " rad\n";
  const std::vector<TransientSample> &rows = r.samples;
  const double scale = std::abs(rows[0].film_force) * settings.geometry.outer_radius;
  const auto difference = [&](const TransientSample &a, const TransientSample &b)
  {
    return std::hypot(a.film_moment_x - b.film_moment_x, a.film_moment_y - b.film_moment_y) / scale;
  };
  double over_period = 0, over_half = 1;
  for (unsigned int k = 0; k + 4 < rows.size(); ++k)
  {
    over_period = std::max(over_period, difference(rows[k], rows[k + 4]));
    over_half = std::min(over_half, difference(rows[k], rows[k + 2]));
  }
  std::cout << "moment change over T " << over_period << ", over T/2 (smallest) " << over_half
            << " of the moment scale\n";
  EXPECT_LT(over_period, 1e-8);
  EXPECT_GT(over_half, 1e-3);
}

/// A film of loads made beforehand (no FE solve): holds the rotor features at one angle.
class FixedFilm : public FilmForceModel
{
public:
  FilmLevel level() const override { return FilmLevel::table; }
  std::string description() const override { return "fixed"; }
  FilmLoads loads(const FilmState &) const override { return FilmLoads(); }
  FilmCoefficients coefficients(const FilmState &) const override { return FilmCoefficients(); }
};

// A transient whose film cannot turn the rotor's features (a table) is refused in one line
// before any work, instead of integrating the snapshot at Phase.
TEST(RotorFeatures, FilmOfOneRotorAngleIsRefusedInTransients)
{
  FlexibleStatorSeal seal;
  seal.geometry = pad_film(0, false, Cavitation::none).geometry;
  const FixedFilm film;
  const StatorTransient transient(seal, film, TransientSettings());
  std::string message;
  try
  {
    transient.run();
  }
  catch (const std::runtime_error &e)
  {
    message = e.what();
  }
  std::cout << message << "\n";
  EXPECT_NE(message.find("Film level = finite element"), std::string::npos);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

// A film formula in t changes the film by itself; a film of loads made beforehand holds it at
// t = 0, so such a transient is refused in one line (a formula without t is not).
TEST(RotorFeatures, FormulaInTimeIsRefusedByAFilmMadeBeforehand)
{
  const auto run_with = [](const std::string &formula)
  {
    FlexibleStatorSeal seal;
    seal.geometry.expression = std::make_shared<const FilmExpression>(formula, "", 0.04);
    const FixedFilm film;
    TransientSettings settings;
    settings.end_time = 1e-4;
    const StatorTransient transient(seal, film, settings);
    try
    {
      transient.run();
    }
    catch (const std::runtime_error &e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string in_time = run_with("1e-7 * sin(1000 * t)");
  std::cout << in_time << "\n";
  EXPECT_NE(in_time.find("depends on t"), std::string::npos);
  EXPECT_EQ(in_time.find('\n'), std::string::npos);
  EXPECT_EQ(run_with("1e-7 * cos(theta)").find("depends on t"), std::string::npos);
}
} // namespace
