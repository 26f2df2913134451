// `sealfe solve` on its defaults: summary.json has the documented keys in SI units, the VTU has
// the documented point fields on the curved geometry, and the default seal's force is within its
// own error estimate of the exact axisymmetric value (443.682 N,
// tests/validation/reynolds_exact.cc).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace
{
fs::path run_default(const std::string &name)
{
  const fs::path dir = fs::temp_directory_path() / ("sealfe_regression_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "case.prm") << "set Output directory = " << (dir / "out").string() << "\n";
  const std::string cmd = std::string(SEALFE_BINARY) + " solve " + (dir / "case.prm").string() +
                          " > " + (dir / "log").string() + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return dir / "out";
}
/// The (single) VTU piece in `out`, read.
vtkSmartPointer<vtkXMLUnstructuredGridReader> read_vtu(const fs::path &out)
{
  fs::path vtu;
  for (const auto &e : fs::directory_iterator(out))
    if (e.path().extension() == ".vtu")
      vtu = e.path();
  EXPECT_FALSE(vtu.empty());
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName(vtu.c_str());
  reader->Update();
  return reader;
}
} // namespace

TEST(SolveOutput, SummaryKeysAndDefaultSeal)
{
  const fs::path out = run_default("summary");
  std::ifstream in(out / "summary.json");
  ASSERT_TRUE(in.good());
  const auto s = nlohmann::json::parse(in);
  for (const char *key :
       {"force_z", "moment_x", "moment_y", "moment_restoring", "moment_transverse", "leakage_inner",
        "leakage_outer", "friction_torque", "min_film", "max_pressure", "min_pressure", "dofs",
        "wall_time", "error_estimate", "cavitated_fraction", "version", "git_revision"})
    EXPECT_TRUE(s.contains(key)) << key;
  for (const char *key : {"force_z", "moment_x", "moment_y", "leakage_inner"})
    EXPECT_TRUE(s["error_estimate"].contains(key)) << key;
  const double F = s["force_z"], eF = s["error_estimate"]["force_z"];
  EXPECT_LE(std::abs(F - 443.6818), eF + 1e-3);
  EXPECT_LT(eF / F, 2e-4); // pinned: the default mesh estimates 1.2e-4 (true error 2.2e-5)
  EXPECT_DOUBLE_EQ(s["min_film"].get<double>(), 1e-6);
  EXPECT_DOUBLE_EQ(s["max_pressure"].get<double>(), 4e5);
  EXPECT_GT(s["leakage_inner"].get<double>(), 0); // po > pi: the flow leaves through r = ri
  EXPECT_NEAR(s["leakage_inner"].get<double>() + s["leakage_outer"].get<double>(), 0,
              1e-10 * s["leakage_inner"].get<double>());
  EXPECT_TRUE(fs::exists(out / "used_parameters.prm"));
  EXPECT_TRUE(fs::exists(out / "solution.pvd"));

  // `sealfe --version` names the CMake project version and the git revision the summary has
  EXPECT_EQ(s["version"], SEALFE_VERSION);
  const std::string revision = s["git_revision"];
  EXPECT_FALSE(revision.empty());
  const fs::path log = out.parent_path() / "version";
  ASSERT_EQ(std::system((std::string(SEALFE_BINARY) + " --version > " + log.string()).c_str()), 0);
  std::ifstream version(log);
  std::string line;
  std::getline(version, line);
  EXPECT_EQ(line, "sealfe " SEALFE_VERSION " (git " + revision + ")");
}

TEST(SolveOutput, VtuHasFieldsOnCurvedGeometry)
{
  const fs::path out = run_default("vtu");
  vtkSmartPointer<vtkXMLUnstructuredGridReader> reader = read_vtu(out);
  vtkUnstructuredGrid *grid = reader->GetOutput();
  ASSERT_GT(grid->GetNumberOfPoints(), 0);
  // one Lagrange cell of the element's degree (2 by default: 9 points) per finite element
  ASSERT_GT(grid->GetNumberOfCells(), 0);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    ASSERT_EQ(grid->GetCellType(c), VTK_LAGRANGE_QUADRILATERAL);
    ASSERT_EQ(grid->GetCell(c)->GetNumberOfPoints(), 9);
  }
  vtkDataArray *p = grid->GetPointData()->GetArray("pressure");
  vtkDataArray *h = grid->GetPointData()->GetArray("film_thickness");
  vtkDataArray *q = grid->GetPointData()->GetArray("volume_flux");
  ASSERT_NE(p, nullptr);
  ASSERT_NE(h, nullptr);
  ASSERT_NE(q, nullptr);
  EXPECT_EQ(q->GetNumberOfComponents(), 3); // VTK pads 2D vectors to 3 components
  double max_h_error = 0, max_outside = 0, min_r = 1, max_r = 0;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double x[3];
    grid->GetPoint(i, x);
    const double r = std::hypot(x[0], x[1]);
    min_r = std::min(min_r, r);
    max_r = std::max(max_r, r);
    // h = C0 + beta (r - ri) for the default seal, evaluated at the output point
    max_h_error = std::max(max_h_error, std::abs(h->GetTuple1(i) - (1e-6 + 1e-3 * (r - 0.0355))));
    max_outside = std::max(max_outside, std::max(0.0355 - r, r - 0.0408));
    EXPECT_GE(p->GetTuple1(i), -1e-6);
    EXPECT_LE(p->GetTuple1(i), 4e5 + 1e-6);
  }
  // VTU coordinates are float32 (relative rounding 6e-8, so about 3e-9 m here).
  EXPECT_LT(max_h_error, 1e-11);
  // Curved output: boundary points lie on the circles (a straight-sided mesh would put its edge
  // midpoints inside the outer circle by ro (1 - cos(pi/128)) = 1.2e-5 m).
  EXPECT_LT(max_outside, 1e-8);
  EXPECT_NEAR(min_r, 0.0355, 1e-8);
  EXPECT_NEAR(max_r, 0.0408, 1e-8);
  // the owning MPI rank is a cell array (one value per cell: 0 for this one-rank run)
  vtkDataArray *rank = grid->GetCellData()->GetArray("rank");
  ASSERT_NE(rank, nullptr);
  ASSERT_EQ(rank->GetNumberOfTuples(), grid->GetNumberOfCells());
  EXPECT_EQ(rank->GetRange()[0], 0);
  EXPECT_EQ(rank->GetRange()[1], 0);
  EXPECT_EQ(grid->GetPointData()->GetArray("rank"), nullptr);
}

// The volume flux written is the one the JFO film equation conserves, q = -K grad p + s c. In a
// cell whose nodes are all cavitated the pressure is p_cav throughout (grad p = 0), so for a
// smooth film rotating at w_r with the stator at rest |q| = s h w_r r / 2 (the Couette flux
// h u_mean carrying the liquid fraction s), not the full-film h w_r r / 2. Checked at every output
// point of such cells to the float32 precision of the VTU (three factors of relative rounding
// 6e-8: 1e-6 allows for it).
TEST(SolveOutput, JfoVolumeFluxCarriesTheLiquidFraction)
{
  const fs::path dir = fs::temp_directory_path() / "sealfe_regression_jfo_flux";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream example(fs::path(SEALFE_SOURCE_DIR) / "prm" / "wavy_jfo.prm");
  std::ofstream(dir / "case.prm") << std::string(std::istreambuf_iterator<char>(example), {})
                                  << "set Output directory = " << (dir / "out").string() << "\n";
  const std::string cmd = std::string(SEALFE_BINARY) + " solve " + (dir / "case.prm").string() +
                          " > " + (dir / "log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName((dir / "out" / "solution_0000.0.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid *grid = reader->GetOutput();
  vtkDataArray *q = grid->GetPointData()->GetArray("volume_flux");
  vtkDataArray *s = grid->GetPointData()->GetArray("liquid_fraction");
  vtkDataArray *h = grid->GetPointData()->GetArray("film_thickness");
  vtkDataArray *cavitated = grid->GetPointData()->GetArray("cavitated");
  ASSERT_TRUE(q && s && h && cavitated);
  const double rotor_speed = 1000; // rad/s, prm/wavy_jfo.prm
  unsigned int checked = 0;
  double min_liquid = 1, max_error = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    vtkIdList *points = grid->GetCell(c)->GetPointIds();
    bool all_cavitated = true;
    for (vtkIdType k = 0; k < points->GetNumberOfIds(); ++k)
      all_cavitated = all_cavitated && cavitated->GetTuple1(points->GetId(k)) > 0.5;
    if (!all_cavitated)
      continue;
    for (vtkIdType k = 0; k < points->GetNumberOfIds(); ++k)
    {
      const vtkIdType i = points->GetId(k);
      double x[3];
      grid->GetPoint(i, x);
      const double expected =
          s->GetTuple1(i) * h->GetTuple1(i) * 0.5 * rotor_speed * std::hypot(x[0], x[1]);
      const double *flux = q->GetTuple3(i);
      max_error = std::max(max_error, std::abs(std::hypot(flux[0], flux[1]) - expected) / expected);
      min_liquid = std::min(min_liquid, s->GetTuple1(i));
      ++checked;
    }
  }
  ASSERT_GT(checked, 100u);
  EXPECT_LT(min_liquid, 0.5); // a real cavity: the full-film flux would be off by 2x or more
  EXPECT_LT(max_error, 1e-6);
}

// Every sub-command writes into its own default directory, sealfe-output/<sub-command>, so that
// one run never replaces the summary.json of another (annular used to overwrite solve's).
TEST(SolveOutput, EachSubCommandHasItsOwnDefaultDirectory)
{
  const fs::path dir = fs::temp_directory_path() / "sealfe_regression_default_directory";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // (--print-parameters starts the program once per sub-command: three of them suffice)
  for (const std::string command : {"solve", "annular", "transient"})
  {
    const fs::path listing = dir / (command + ".prm");
    ASSERT_EQ(std::system((std::string(SEALFE_BINARY) + " --print-parameters " + command + " > " +
                           listing.string())
                              .c_str()),
              0);
    std::ifstream in(listing);
    std::string line;
    bool found = false;
    while (std::getline(in, line))
      found = found || line == "set Output directory = sealfe-output/" + command;
    EXPECT_TRUE(found) << command;
  }
  // a bare run (no prm) from dir: the default directory is relative to the working directory
  const std::string cmd = "cd " + dir.string() + " && " + SEALFE_BINARY + " equilibrium > log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir / "sealfe-output" / "equilibrium" / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "sealfe-output" / "summary.json"));
}

// Round-off shown as round-off. On an axisymmetric seal the moments are exactly zero by symmetry;
// what the solver computes is round-off, and it must lie below the round-off bound summary.json
// gives (eps * viscous pressure scale / pressure range, times the moment scale p_range * area *
// ro; doc/guarantees.md) and be printed as 0. A tilted seal's moment is a physical result
// (Green 2002: a restoring moment of the order of the tilt stiffness times the tilt) and is
// printed as a number with its discretisation estimate. --timings adds deal.II's TimerOutput table.
TEST(SolveOutput, RoundOffMomentsPrintedAsZeroAndTimings)
{
  const fs::path dir = fs::temp_directory_path() / "sealfe_regression_round_off";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto run = [&dir](const std::string &name, const std::string &body, const std::string &flags)
  {
    std::ofstream(dir / (name + ".prm"))
        << "set Output directory = " << (dir / name).string() << "\n"
        << body << "subsection Output\n  set Write fields = false\nend\n";
    const std::string cmd = std::string(SEALFE_BINARY) + " " + flags + " solve " +
                            (dir / (name + ".prm")).string() + " > " +
                            (dir / (name + ".log")).string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << name;
    std::ifstream log(dir / (name + ".log"));
    return std::string(std::istreambuf_iterator<char>(log), {});
  };
  const std::string axisymmetric = run("axisymmetric", "", "--timings");
  const auto s = nlohmann::json::parse(std::ifstream(dir / "axisymmetric" / "summary.json"));
  for (const char *m : {"moment_x", "moment_y"})
  {
    const double bound = s["round_off"]["absolute_bound"][m];
    EXPECT_LE(std::abs(s[m].get<double>()), bound) << m;
    // the bound is far below any moment a seal carries (1e-6 N m: 1e-9 of the tilt stiffness
    // times a 1 urad tilt of this seal is ~1e-3 N m)
    EXPECT_LT(bound, 1e-6) << m;
    EXPECT_NE(axisymmetric.find(std::string(m) + "             0 N m (round-off"),
              std::string::npos)
        << axisymmetric;
  }
  EXPECT_NE(axisymmetric.find("| run solve "), std::string::npos) << axisymmetric;

  const std::string tilted = run("tilted", "subsection Geometry\n  set Tilt = 1e-5\nend\n", "");
  EXPECT_EQ(tilted.find("round-off"), std::string::npos) << tilted;
  EXPECT_NE(tilted.find("discretisation"), std::string::npos) << tilted;
  EXPECT_EQ(tilted.find("TimerOutput"), std::string::npos);
  EXPECT_EQ(tilted.find("| run solve "), std::string::npos) << tilted;
}

// Output/Fields = a list: the VTU carries those point arrays and no other (plus the rank cell
// array); the pressure is the same field as in a full write.
TEST(SolveOutput, FieldListWritesOnlyThoseFields)
{
  const fs::path dir = fs::temp_directory_path() / "sealfe_regression_field_list";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "case.prm") << "set Output directory = " << (dir / "out").string() << "\n"
                                  << "subsection Output\n  set Fields = pressure, film thickness\n"
                                  << "end\n";
  const std::string cmd = std::string(SEALFE_BINARY) + " solve " + (dir / "case.prm").string() +
                          " > " + (dir / "log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  vtkSmartPointer<vtkXMLUnstructuredGridReader> reader = read_vtu(dir / "out");
  vtkPointData *points = reader->GetOutput()->GetPointData();
  EXPECT_EQ(points->GetNumberOfArrays(), 2);
  EXPECT_NE(points->GetArray("pressure"), nullptr);
  EXPECT_NE(points->GetArray("film_thickness"), nullptr);
  EXPECT_EQ(points->GetArray("volume_flux"), nullptr);
  EXPECT_NE(reader->GetOutput()->GetCellData()->GetArray("rank"), nullptr);
  // default seal: the pressure lies between the sealed pressures 0 and 4e5 Pa
  EXPECT_GE(points->GetArray("pressure")->GetRange()[0], -1e-6);
  EXPECT_LE(points->GetArray("pressure")->GetRange()[1], 4e5 + 1e-6);
}
