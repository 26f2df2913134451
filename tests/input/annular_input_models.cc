// Bad input to `sealfe annular` is refused with one clear line that names the parameter.
#include <sealfe/annular/annular_seal.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace sealfe::annular;

namespace
{
using Settings = std::vector<std::pair<std::string, std::string>>;

/// Runs the sub-command with the defaults changed by `settings` (entries of "Annular seal";
/// "Lambda sweep/X" for the sweep) and returns the error message ("" if none was thrown).
std::string error_of(const Settings &settings)
{
  dealii::ParameterHandler prm;
  declare_parameters(prm);
  prm.enter_subsection("Annular seal");
  for (const auto &[entry, value] : settings)
  {
    if (entry.rfind("Lambda sweep/", 0) == 0)
    {
      prm.enter_subsection("Lambda sweep");
      prm.set(entry.substr(13), value);
      prm.leave_subsection();
    }
    else
      prm.set(entry, value);
  }
  prm.leave_subsection();
  // one directory per test: ctest runs these tests as concurrent processes, and two runs writing
  // the same file in one directory rename each other's temporary file (output::
  // write_file_atomically's name.tmp: "cannot write ...: No such file or directory", seen in CI)
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sealfe_annular_input_" +
                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(dir);
  try
  {
    run(prm, dir.string());
  }
  catch (const std::runtime_error &e)
  {
    return e.what();
  }
  return "";
}

void expect_refused(const Settings &settings, const std::string &parameter)
{
  Settings s = settings;
  s.insert(s.begin(), {"Lambda sweep/Points", "0"}); // no sweep: keep the good cases fast
  const std::string message = error_of(s);
  ASSERT_FALSE(message.empty()) << "accepted: " << settings.back().first << " = "
                                << settings.back().second;
  EXPECT_NE(message.find(parameter), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  EXPECT_EQ(message.rfind("Annular seal: ", 0), 0u) << message;
}
} // namespace

TEST(AnnularInput, DefaultsAreAccepted)
{
  EXPECT_EQ(error_of({{"Lambda sweep/Points", "0"}}), "");
}

TEST(AnnularInput, ClearanceRatioBelowOne)
{
  expect_refused({{"Clearance ratio", "0.8"}}, "Clearance ratio");
  expect_refused({{"Geometry type", "tapered"}, {"Clearance ratio", "0.99"}}, "Clearance ratio");
  // an inlet clearance smaller than the outlet clearance is the same mistake
  expect_refused({{"Clearance ratio", ""}, {"Inlet clearance", "1e-4"}}, "Inlet clearance");
  expect_refused({{"Clearance ratio", "abc"}}, "Clearance ratio");
  // a straight seal has H = 1 whatever the entry says; a tapered seal with H = 1 is allowed
  EXPECT_EQ(error_of({{"Lambda sweep/Points", "0"},
                      {"Geometry type", "straight"},
                      {"Clearance ratio", "0.5"}}),
            "");
}

TEST(AnnularInput, ClearancesGivenTwiceOrNotAtAll)
{
  expect_refused({{"Inlet clearance", "2e-4"}}, "Inlet clearance or Clearance ratio");
  expect_refused({{"Clearance ratio", ""}}, "Inlet clearance or Clearance ratio");
}

TEST(AnnularInput, StepPositionOutsideZeroOne)
{
  for (const char *g : {"0", "-0.2", "1.01"})
    expect_refused({{"Step position", g}}, "Step position");
  EXPECT_EQ(error_of({{"Lambda sweep/Points", "0"}, {"Step position", "1"}}), "");
  expect_refused({{"Optimise", "stiffness"}, {"Step position upper bound", "1.5"}},
                 "Step position upper bound");
  expect_refused({{"Optimise", "stiffness"}, {"Step position upper bound", "0"}},
                 "Step position upper bound");
}

TEST(AnnularInput, NonPositiveLengthsAndClearances)
{
  for (const char *v : {"0", "-0.01"})
  {
    expect_refused({{"Length", v}}, "Length");
    expect_refused({{"Diameter", v}}, "Diameter");
    expect_refused({{"Outlet clearance", v}}, "Outlet clearance");
    expect_refused({{"Clearance ratio", ""}, {"Inlet clearance", v}}, "Inlet clearance");
  }
}

TEST(AnnularInput, NonPositiveDensityFrictionAndPressure)
{
  for (const char *v : {"0", "-1"})
  {
    expect_refused({{"Density", v}}, "Density");
    expect_refused({{"Friction factor", v}}, "Friction factor");
    expect_refused({{"Pressure drop", v}}, "Pressure drop");
    expect_refused({{"Viscosity", v}}, "Viscosity");
    expect_refused({{"Friction model", "fully rough"}, {"Relative roughness", v}},
                   "Relative roughness");
  }
  expect_refused({{"Pressure specification", "inlet and outlet"},
                  {"Inlet pressure", "1e5"},
                  {"Outlet pressure", "2e5"}},
                 "Inlet pressure");
  expect_refused({{"Entrance loss coefficient", "-0.1"}}, "Entrance loss coefficient");
}

TEST(AnnularInput, OptimisingAStraightSeal)
{
  expect_refused({{"Geometry type", "straight"}, {"Optimise", "stiffness"}}, "Optimise");
  expect_refused({{"Optimise", "stiffness"}, {"Clearance ratio upper bound", "1"}},
                 "Clearance ratio upper bound");
}

TEST(AnnularInput, BadLambdaSweep)
{
  expect_refused({{"Lambda sweep/Values", "0.1, x"}}, "Lambda sweep");
  expect_refused({{"Lambda sweep/Values", "0.1, -2"}}, "Lambda sweep");
  expect_refused({{"Lambda sweep/Points", "5"}, {"Lambda sweep/Minimum", "0"}}, "Lambda sweep");
  expect_refused(
      {{"Lambda sweep/Points", "5"}, {"Lambda sweep/Minimum", "2"}, {"Lambda sweep/Maximum", "1"}},
      "Lambda sweep");
}
