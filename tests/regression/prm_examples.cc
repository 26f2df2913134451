// Every example in prm/ runs through the command line and its key results stay where they were:
// prm/<name>.reference.json names the sub-command, the files the run must write, and values of
// summary.json (by JSON pointer) or of a CSV cell, each with a relative tolerance and the reason
// for it. The run writes into its own temporary directory (the prm is included and its Output
// directory overridden), so the examples themselves stay untouched.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
const fs::path prm_dir = fs::path(SEALFE_SOURCE_DIR) / "prm";

std::string read(const fs::path &f)
{
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string &line)
{
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');)
    cells.push_back(cell);
  return cells;
}

/// Cell (data row, column name) of a CSV file with one header line.
std::string csv_cell(const fs::path &file, const unsigned int row, const std::string &column)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split(line);
  const auto col = std::find(header.begin(), header.end(), column);
  if (col == header.end())
    throw std::runtime_error("no column '" + column + "' in " + file.string());
  for (unsigned int i = 0; i <= row; ++i)
    if (!std::getline(in, line))
      throw std::runtime_error("no data row " + std::to_string(row) + " in " + file.string());
  return split(line).at(col - header.begin());
}

/// Numbers within the relative tolerance (0: equal); anything else equal as JSON.
void expect_matches(const json &reference, const json &value, const double relative_tolerance,
                    const std::string &what)
{
  if (reference.is_number() && value.is_number())
  {
    const double r = reference.get<double>(), v = value.get<double>();
    EXPECT_LE(std::abs(v - r), relative_tolerance * std::abs(r))
        << what << ": " << std::setprecision(17) << v << " against the pinned " << r;
  }
  else
    EXPECT_EQ(value, reference) << what;
}

class PrmExample : public ::testing::TestWithParam<std::string>
{
};
} // namespace

TEST_P(PrmExample, RunsAndKeepsItsPinnedResults)
{
  const std::string name = GetParam();
  const json reference = json::parse(read(prm_dir / (name + ".reference.json")));
  const fs::path dir = fs::temp_directory_path() / ("sealfe_prm_example_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "out";
  std::ofstream(dir / "case.prm") << "include " << (prm_dir / (name + ".prm")).string() << "\n"
                                  << "set Output directory = " << out.string() << "\n";
  const std::string cmd = std::string(SEALFE_BINARY) + " " +
                          reference["sub_command"].get<std::string>() + " " +
                          (dir / "case.prm").string() + " > " + (dir / "log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read(dir / "log");

  for (const auto &file : reference["output_files"])
    EXPECT_TRUE(fs::exists(out / file.get<std::string>())) << file;

  const json summary = json::parse(read(out / "summary.json"));
  for (const auto &pin : reference["values"])
  {
    const double tolerance = pin["relative_tolerance"];
    if (pin.contains("pointer"))
    {
      const json::json_pointer pointer(pin["pointer"].get<std::string>());
      ASSERT_TRUE(summary.contains(pointer)) << pin["pointer"];
      expect_matches(pin["value"], summary[pointer], tolerance,
                     pin["pointer"].get<std::string>() + " (" + pin["why"].get<std::string>() +
                         ")");
    }
    else
    {
      const std::string cell =
          csv_cell(out / pin["file"].get<std::string>(), pin["row"], pin["column"]);
      expect_matches(pin["value"], json(std::stod(cell)), tolerance,
                     pin["file"].get<std::string>() + " row " + pin["row"].dump() + " " +
                         pin["column"].get<std::string>());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Prm, PrmExample,
                         ::testing::Values("solve", "wavy_jfo", "coefficients", "table",
                                           "stability", "response", "annular", "equilibrium",
                                           "transient"),
                         [](const auto &info) { return info.param; });

TEST(PrmExamples, EveryExampleHasAReference)
{
  std::set<std::string> examples, references;
  for (const auto &e : fs::directory_iterator(prm_dir))
  {
    const std::string file = e.path().filename().string();
    if (e.path().extension() == ".prm")
      examples.insert(e.path().stem().string());
    else if (file.size() > 15 && file.substr(file.size() - 15) == ".reference.json")
      references.insert(file.substr(0, file.size() - 15));
  }
  EXPECT_EQ(examples, references);
  EXPECT_EQ(examples.size(), 9u); // the instantiation above lists them
}
