// `sealfe transient` end to end with a feature on the rotor and field output: the application run
// on a prm, checked from the files it writes (transient.csv, transient_fields.pvd and the VTU
// files it lists, read through VTK; summary.json). Theory: the rotor has turned by
// phi(t) = Int omega dt (a closed form for the ramped speed), and the full film has no memory, so
// the fields written at t are the steady film of the pad drawn at its rotor angle + phi(t), in the
// stator frame: the pocket (film C0 + depth) spans that arc and the pressure is largest at the
// pad's step (Rayleigh 1918: the pressure rises along the pocket and falls along the land) and
// smallest where the pocket begins. What the library tests (tests/validation/
// rotor_features_turning.cc) check in-process, here through the prm, the integration and the files.
#include "../sealfe_cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

using namespace sealfe::testing;

namespace
{
// One Rayleigh pad on the rotor of a flat 25..35 mm dam, land film C0 = 2 um, pocket 2 um deeper
// across the whole dam, no feeding groove. Rotor face: the pad is mirrored (surface_features.h),
// so in the rotor's frame the pocket spans [Phase - f L, Phase] and its step (pocket -> land, in
// the direction the stator slides past) is at Phase - f L.
constexpr double ri = 0.025, ro = 0.035, C0 = 2e-6, depth = 2e-6;
constexpr double phase = 0.3, pad_angle = 1.2, step_fraction = 0.5;
constexpr unsigned int circumferential_cells = 96;
// Speed ramped from 50 to 100 rad/s over t1 = 10 ms, then held.
constexpr double omega0 = 50, omega1 = 100, t1 = 0.01;

double speed(const double t)
{
  return t < t1 ? omega0 + (omega1 - omega0) * t / t1 : omega1;
}
/// Int_0^t omega dt of the ramp.
double rotor_angle(const double t)
{
  return t < t1 ? omega0 * t + (omega1 - omega0) * t * t / (2 * t1)
                : omega0 * t1 + (omega1 - omega0) * t1 / 2 + omega1 * (t - t1);
}

/// a - b wrapped into (-pi, pi].
double angle_difference(const double a, const double b)
{
  return std::remainder(a - b, 2 * M_PI);
}

std::string case_prm()
{
  std::ostringstream s;
  s.precision(17);
  s << "subsection Geometry\n  set Inner radius = " << ri << "\n  set Outer radius = " << ro
    << "\n  set Clearance = " << C0 << "\n  set Coning = 0\n"
    << "  subsection Surface features\n    set Face = rotor\n    subsection Rayleigh pads\n"
    << "      set Number = 1\n      set Phase = " << phase
    << "\n      set Pad angle = " << pad_angle << "\n      set Step fraction = " << step_fraction
    << "\n      set Step depth = " << depth << "\n    end\n  end\nend\n"
    << "subsection Operating conditions\n  set Viscosity = 1.2e-3\n  set Inner pressure = 1e5\n"
    << "  set Outer pressure = 1e5\nend\n"
    << "subsection Cavitation\n  set Model = none\nend\n"
    << "subsection Discretization\n  set Polynomial degree = 2\n  set Radial cells = 4\n"
    << "  set Circumferential cells = " << circumferential_cells
    << "\n  set Error estimate = false\nend\n"
    // a stator too heavy to move in 30 ms (1e15 kg, 1e15 kg m^2), untilted, no contact, no
    // runout, fixed coning: the film is that of the pad alone
    << "subsection Stator ring\n  set Mass = 1e15\n  set Transverse inertia = 1e15\nend\n"
    << "subsection Rotor runout\n  set Tilt = 0\nend\n"
    << "subsection Face contact\n  set Model = none\nend\n"
    << "subsection Thermal coning\n  set Model = none\nend\n"
    << "subsection Ramps\n  set Speed rest value = " << omega0
    << "\n  set Speed steady value = " << omega1 << "\n  set Speed t1 = " << t1
    << "\n  set Outer pressure rest value = 1e5\n  set Outer pressure steady value = 1e5\n"
    << "  set Inner pressure rest value = 1e5\n  set Inner pressure steady value = 1e5\nend\n"
    // fields asked for between output rows: written at the first row at or after each
    << "subsection Transient\n  set Film level = finite element\n  set Initial axial offset = 0\n"
    << "  set End time = 0.03\n  set Output interval = 0.005\n"
    << "  set Field output times = 0.002, 0.012, 0.026\n  set Plot = false\nend\n";
  return s.str();
}

/// The (timestep, file) entries of a PVD collection, in order.
std::vector<std::pair<double, std::string>> read_pvd(const std::string &text)
{
  std::vector<std::pair<double, std::string>> entries;
  const std::regex dataset(R"re(<DataSet[^>]*timestep="([^"]*)"[^>]*file="([^"]*)")re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset);
       it != std::sregex_iterator(); ++it)
    entries.emplace_back(std::stod((*it)[1]), (*it)[2]);
  return entries;
}

/// The grid of a .pvtu (the pieces it names) or a .vtu.
vtkSmartPointer<vtkUnstructuredGrid> read_grid(const fs::path &file)
{
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  if (file.extension() == ".pvtu")
  {
    auto reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
    reader->SetFileName(file.c_str());
    reader->Update();
    grid = reader->GetOutput();
  }
  else
  {
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    reader->SetFileName(file.c_str());
    reader->Update();
    grid = reader->GetOutput();
  }
  return grid;
}

/// Runs the case through `launcher` (empty, or mpirun) in `dir` and checks the files it writes;
/// `ranks`: the MPI ranks summary.json must name.
void run_and_check(const std::string &directory, const std::string &launcher,
                   const unsigned int ranks)
{
  const fs::path dir = fresh_directory(directory);
  const CliResult r = run_sealfe(dir, "transient", case_prm(), launcher);
  ASSERT_EQ(r.status, 0) << r.err;
  const fs::path out = dir / "out";

  // transient.csv: one row per Output interval, 0 .. 30 ms; rotor_speed and rotor_angle are the
  // ramp and its integral (closed forms; the CSV holds every double exactly, so what is left is
  // the round-off of the sums that make them: 1e-12 relative is ~5000 u of double precision)
  const auto csv = read_csv(read_file(out / "transient.csv"));
  const std::vector<double> &time = csv.at("time");
  ASSERT_EQ(time.size(), 7u);
  for (std::size_t k = 0; k < time.size(); ++k)
  {
    EXPECT_NEAR(time[k], 0.005 * k, 1e-12);
    EXPECT_NEAR(csv.at("rotor_speed")[k], speed(time[k]), 1e-12 * omega1);
    EXPECT_NEAR(csv.at("rotor_angle")[k], rotor_angle(time[k]), 1e-12 * rotor_angle(0.03));
  }

  // transient_fields.pvd: one data set per field output time, at the first output row at or
  // after it (5, 15 and 30 ms), each a time of transient.csv
  const auto pvd = read_pvd(read_file(out / "transient_fields.pvd"));
  const std::vector<double> asked = {0.002, 0.012, 0.026}, expected_times = {0.005, 0.015, 0.03};
  ASSERT_EQ(pvd.size(), asked.size());
  for (std::size_t i = 0; i < pvd.size(); ++i)
  {
    EXPECT_NEAR(pvd[i].first, expected_times[i], 1e-12) << pvd[i].second;
    const auto row = std::find_if(time.begin(), time.end(),
                                  [&](const double t) { return t >= asked[i] - 1e-12; });
    ASSERT_NE(row, time.end());
    EXPECT_DOUBLE_EQ(pvd[i].first, *row) << "not the first row at or after " << asked[i];
  }

  // the written fields, in the stator frame: at time t the pad stands at its rotor-frame angles
  // + phi(t). The film is solved in the pad's frame on a mesh with nodes on the step angles
  // (Align with features: 96 cells, a multiple of the one pad, doc/textures.md), and written
  // with its points turned by phi(t); the patches are subdivided by the degree (2), so the
  // written points are the Q2 nodes, every half cell (0.033 rad) in theta. So the pressure's
  // extremes (nodal: the Rayleigh peak at the step, the trough where the pocket begins) and the
  // pocket's edges (a node on a step carries its cell's side of the film) stand at the exact angles
  // but for the rounding of the VTU's Float32 points: each coordinate to a relative u = 2^-24
  // (6.0e-8), which moves atan2(y, x) by at most |x y| 2u / r^2 <= u rad. Tolerance 2u; a node
  // one spacing off would miss it by 0.033 rad, and unturned the pad would be off by
  // phi(t) = 0.31, 1.25, 2.75 rad.
  const double u32 = std::ldexp(1.0, -24), angle_tolerance = 2 * u32;
  const double pocket = step_fraction * pad_angle;
  // the film is the same (turned) at every output and the Reynolds equation is linear in the
  // speed: the pressure rise above the ambient p_a = 1e5 Pa over omega(t) is one number. Each
  // written p has a Float32 rounding error of at most u p_max, so two quotients differ by at most
  // 2 u p_max / (p_max - p_a) relative (+ the solver's 1e-12); with the rise above p_a (the 1D
  // Rayleigh step, 6 mu U (h1 - h2) L1 L2 / (h1^3 L2 + h2^3 L1) = 9e6 Pa at the first output's
  // 75 rad/s on the mean radius, less the side leakage of the 10 mm dam) that is below 4 u =
  // 2.4e-7: tolerance 1e-6.
  std::vector<double> rise_per_speed;
  for (const auto &[t, file] : pvd)
  {
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : out / file;
    ASSERT_TRUE(fs::exists(path)) << path;
    const auto grid = read_grid(path);
    ASSERT_GT(grid->GetNumberOfPoints(), 0) << path;
    vtkDataArray *p = grid->GetPointData()->GetArray("pressure");
    vtkDataArray *h = grid->GetPointData()->GetArray("film_thickness");
    ASSERT_TRUE(p && h) << path;
    const double phi = rotor_angle(t);
    const double pocket_centre = phase - pocket / 2 + phi; // stator frame
    const double step = phase - pocket + phi, pocket_start = phase + phi;
    double p_max = -1e300, p_min = 1e300, angle_max = 0, angle_min = 0;
    double in_pocket_worst = 0, land_worst = 0; // how far a point falls on the wrong side
    unsigned int n_pocket = 0;
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
    {
      double x[3];
      grid->GetPoint(i, x);
      const double theta = std::atan2(x[1], x[0]), r = std::hypot(x[0], x[1]);
      const double offset = std::abs(angle_difference(theta, pocket_centre));
      const double pressure = p->GetComponent(i, 0), film = h->GetComponent(i, 0);
      if (pressure > p_max)
        p_max = pressure, angle_max = theta;
      if (pressure < p_min)
        p_min = pressure, angle_min = theta;
      if (film > C0 + depth / 2) // in the pocket: within its arc
      {
        ++n_pocket;
        in_pocket_worst = std::max(in_pocket_worst, offset - pocket / 2);
      }
      else if (std::abs(r - ri) > 1e-6 * ri && std::abs(r - ro) > 1e-6 * ro)
        // on the land: outside it (the pocket's radial edges are the dam's circles, where either
        // side's film is a right answer)
        land_worst = std::max(land_worst, pocket / 2 - offset);
    }
    std::cout << "t = " << t << " s, phi = " << phi << " rad: pressure max " << p_max << " Pa at "
              << angle_max << " rad (step at " << std::remainder(step, 2 * M_PI) << ", off by "
              << angle_difference(angle_max, step) << "), min " << p_min << " Pa at " << angle_min
              << " rad (pocket start at " << std::remainder(pocket_start, 2 * M_PI) << ", off by "
              << angle_difference(angle_min, pocket_start) << "); pocket points " << n_pocket
              << ", overreach " << in_pocket_worst << ", land inside " << land_worst << " rad\n";
    EXPECT_GT(n_pocket, 0u);
    EXPECT_LE(in_pocket_worst, angle_tolerance);
    EXPECT_LE(land_worst, angle_tolerance);
    EXPECT_LE(std::abs(angle_difference(angle_max, step)), angle_tolerance);
    EXPECT_LE(std::abs(angle_difference(angle_min, pocket_start)), angle_tolerance);
    EXPECT_GT(p_max, 2e5); // the step lifts above 2 p_a (the rise bound above), the pocket's
                           // entry below the ambient 1e5 Pa
    EXPECT_LT(p_min, 1e5);
    rise_per_speed.push_back((p_max - 1e5) / speed(t));
  }
  for (const double q : rise_per_speed)
    EXPECT_NEAR(q, rise_per_speed.back(), 1e-6 * rise_per_speed.back()) << "Pa / (rad/s)";

  // summary.json: a complete run to the end time, its files, the film level, no contact
  const auto s = nlohmann::json::parse(read_file(out / "summary.json"));
  for (const char *key :
       {"complete", "end_time", "final_state", "film_model", "film_evaluations", "steps",
        "integrator", "contact_events", "first_lift_off", "last_touch_down", "max_contact_force",
        "leaked_volume", "files", "csv_notes", "integration_wall_time"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_TRUE(s.at("complete").get<bool>());
  EXPECT_DOUBLE_EQ(s.at("end_time").get<double>(), time.back());
  EXPECT_DOUBLE_EQ(s.at("final_state").at("time").get<double>(), time.back());
  EXPECT_GT(s.at("film_evaluations").get<int>(), 0);
  EXPECT_TRUE(s.at("contact_events").empty());
  EXPECT_EQ(s.at("max_contact_force").get<double>(), 0.0);
  const auto files = s.at("files").get<std::vector<std::string>>();
  for (const char *f : {"transient.csv", "transient_fields.pvd"})
    EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f;
  // the stator stays where it started (1e15 kg)
  EXPECT_NEAR(s.at("final_state").at("axial_offset").get<double>(), 0.0, 1e-6 * C0);
  EXPECT_EQ(s.at("mpi_ranks").get<unsigned int>(), ranks);
}
} // namespace

TEST(TransientRotorFields, RotorPadStandsAtItsAnglePlusTheRotorsTurnInTheWrittenFields)
{
  run_and_check("sealfe_transient_rotor_fields", "", 1);
}

// The same on two ranks: the film solved with its mesh split, the fields written as one .pvtu of
// two pieces per output time (read whole through VTK), the same claims to the same tolerances.
TEST(TransientRotorFields, TheSameOnTwoRanks)
{
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "needs mpirun";
  // this test is itself an MPI process (singleton): its OMPI_/PMIX_ variables must not reach the
  // mpirun it starts
  run_and_check("sealfe_transient_rotor_fields_np2",
                "for v in $(env | cut -d= -f1 | grep -E '^(OMPI_|PMIX_|OPAL_)'); do unset $v; "
                "done; OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                "OMPI_MCA_rmaps_base_oversubscribe=1 timeout 300 mpirun -np 2 ",
                2);
}
