// Bad input to `sealfe solve`: each case exits non-zero with one clear line naming the problem,
// and writes no summary.json.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
struct Result
{
  int status;
  std::string err;
};

fs::path work_dir()
{
  const fs::path d =
      fs::temp_directory_path() /
      ("sealfe_input_" +
       std::to_string(::testing::UnitTest::GetInstance()->current_test_info()->line()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Runs `sealfe solve <prm>` with the given prm body (Output directory set inside `dir`).
Result run_case(const fs::path &dir, const std::string &body, bool write_file = true)
{
  const fs::path prm = dir / "case.prm";
  if (write_file)
  {
    std::ofstream out(prm);
    out << "set Output directory = " << (dir / "out").string() << "\n" << body;
  }
  const std::string cmd = std::string(SEALFE_BINARY) + " solve " + prm.string() + " > " +
                          (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
  const int raw = std::system(cmd.c_str());
  std::ifstream e(dir / "stderr");
  std::stringstream s;
  s << e.rdbuf();
  return {WEXITSTATUS(raw), s.str()};
}

void expect_refused(const fs::path &dir, const Result &r, const std::string &needle)
{
  EXPECT_NE(r.status, 0);
  // exactly one line, naming the problem
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
}
} // namespace

TEST(SolveInput, MissingParameterFile)
{
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "", false), "missing or unreadable");
}

TEST(SolveInput, UnknownEntry)
{
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "subsection Geometry\n  set Inner radiuss = 0.03\nend\n"),
                 "Inner radiuss");
}

TEST(SolveInput, UnknownSubsection)
{
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "subsection Geometri\n  set Inner radius = 0.03\nend\n"),
                 "Geometri");
}

TEST(SolveInput, InnerRadiusNotBelowOuter)
{
  const fs::path d = work_dir();
  expect_refused(d,
                 run_case(d, "subsection Geometry\n  set Inner radius = 0.05\n"
                             "  set Outer radius = 0.04\nend\n"),
                 "Inner radius");
}

TEST(SolveInput, NonPositiveClearance)
{
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "subsection Geometry\n  set Clearance = 0\nend\n"), "Clearance");
}

TEST(SolveInput, NonPositiveViscosity)
{
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "subsection Operating conditions\n  set Viscosity = -1e-3\nend\n"),
                 "Viscosity");
}

TEST(SolveInput, FilmTouchesDownSaysWhereAndHowMuch)
{
  // Flat face tilted by 3e-5 rad: the thinnest film is at (ro, theta = pi):
  // h = 1e-6 - 3e-5 * 0.0408 = -2.24e-7 m.
  const fs::path d = work_dir();
  const Result r = run_case(d, "subsection Geometry\n  set Tilt = 3e-5\n  set Coning = 0\nend\n");
  expect_refused(d, r, "touches down");
  EXPECT_NE(r.err.find("r = 0.0408"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("theta = 3.14159"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2.24e-07"), std::string::npos) << r.err;
}

TEST(SolveInput, MissingMeshFile)
{
  const fs::path d = work_dir();
  expect_refused(
      d, run_case(d, "subsection Discretization\n  set Mesh file = /nonexistent.msh\nend\n"),
      "Mesh file");
}

TEST(SolveInput, MeshThatIsNotTheAnnulus)
{
  // The shipped mesh is the default dam; a Geometry with other radii does not match it.
  const fs::path d = work_dir();
  const std::string mesh = std::string(SEALFE_SOURCE_DIR) + "/meshes/annulus.msh";
  expect_refused(d,
                 run_case(d, "subsection Geometry\n  set Inner radius = 0.03\nend\n"
                             "subsection Discretization\n  set Mesh file = " +
                                 mesh + "\nend\n"),
                 "not an annulus");
}

TEST(SolveInput, BadRunDoesNotOverwriteGoodResult)
{
  const fs::path d = work_dir();
  ASSERT_EQ(run_case(d, "subsection Discretization\n  set Circumferential cells = 16\n"
                        "  set Radial cells = 2\nend\n")
                .status,
            0);
  ASSERT_TRUE(fs::exists(d / "out" / "summary.json"));
  const auto stamp = fs::last_write_time(d / "out" / "summary.json");
  const Result r = run_case(d, "subsection Geometry\n  set Clearance = -1\nend\n");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(fs::last_write_time(d / "out" / "summary.json"), stamp);
}

TEST(SolveInput, NonIntegerWaveNumber)
{
  // 2.5 waves: the film would jump at theta = 0 (issue 14, item 14)
  const fs::path d = work_dir();
  expect_refused(d,
                 run_case(d, "subsection Geometry\n  set Wave amplitude = 1e-7\n"
                             "  set Wave number = 2.5\nend\n"),
                 "Wave number must be a whole number");
}

TEST(SolveInput, MappingBelowTheElementDegree)
{
  // a mapping of degree 1 under Q2 elements: its circumferential error (order 2) would not be
  // bounded by the error estimate (order of the elements)
  const fs::path d = work_dir();
  expect_refused(d, run_case(d, "subsection Discretization\n  set Mapping degree = 1\nend\n"),
                 "Mapping degree 1 is below the Polynomial degree 2");
}

TEST(SolveInput, MoreWavesThanTheMeshResolves)
{
  // 1e4 waves on 128 cells of degree 2: 0.0256 nodes per wave
  const fs::path d = work_dir();
  expect_refused(d,
                 run_case(d, "subsection Geometry\n  set Wave amplitude = 1e-7\n"
                             "  set Wave number = 10000\nend\n"),
                 "nodes per wave");
}

TEST(SolveInput, ClearMessages)
{
  // a directory as parameter file
  {
    const fs::path d = work_dir();
    const std::string cmd = std::string(SEALFE_BINARY) + " solve " + d.string() + " > " +
                            (d / "stdout").string() + " 2> " + (d / "stderr").string();
    EXPECT_NE(std::system(cmd.c_str()), 0);
    std::ifstream e(d / "stderr");
    std::stringstream s;
    s << e.rdbuf();
    EXPECT_NE(s.str().find("is a directory"), std::string::npos) << s.str();
  }
  // an unknown subsection: the file name in brackets is closed
  {
    const fs::path d = work_dir();
    const Result r = run_case(d, "subsection Geometri\n  set Inner radius = 0.03\nend\n");
    EXPECT_NE(r.err.find("case.prm>:"), std::string::npos) << r.err;
  }
  // numbers in messages as typed, not in fixed point ("0.000000")
  {
    const fs::path d = work_dir();
    const Result r = run_case(d, "subsection Geometry\n  set Inner radius = 0\nend\n");
    expect_refused(d, r, "Inner radius must be positive (got 0 m)");
  }
}

TEST(SolveInput, MeshBeyondTheMachinesMemory)
{
  // Global refinements = 12 ran until killed; Radial cells = 1e9 ended in std::bad_alloc
  for (const std::string entry : {"Global refinements = 12", "Radial cells = 1000000000"})
  {
    const fs::path d = work_dir();
    expect_refused(d, run_case(d, "subsection Discretization\n  set " + entry + "\nend\n"),
                   "GB of memory");
  }
  // a mistyped Mesh size (1e-6 m for 1e-3 m) would start gmsh on about 1e10 cells: refused, from
  // the area of the dam over size^2, before gmsh runs
  {
    const fs::path d = work_dir();
    expect_refused(d, run_case(d, "subsection Discretization\n  set Mesh size = 1e-6\nend\n"),
                   "raise Mesh size");
  }
}

// Output/Fields: an unknown name, and a field the model does not have, are refused before the
// solve with the name of the field
TEST(SolveInput, FieldListNamesTheBadField)
{
  {
    const fs::path d = work_dir();
    expect_refused(d, run_case(d, "subsection Output\n  set Fields = pressure, presure\nend\n"),
                   "unknown field 'presure'");
  }
  {
    const fs::path d = work_dir();
    expect_refused(d,
                   run_case(d, "subsection Output\n  set Fields = pressure, liquid fraction\n"
                               "end\n"),
                   "liquid fraction needs Cavitation/Model = jfo");
  }
  {
    const fs::path d = work_dir();
    expect_refused(d, run_case(d, "subsection Output\n  set Fields = flow factors\nend\n"),
                   "flow factors needs rough faces");
  }
}
