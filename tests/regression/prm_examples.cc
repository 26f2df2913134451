// Every example in prm/ runs through the command line and its key results stay where they were:
// prm/<name>.reference.json names the sub-command, the files the run must write, and values of
// summary.json (by JSON pointer) or of a CSV cell, each with a relative tolerance and the reason
// for it. The run writes into its own temporary directory (the prm is included and its Output
// directory overridden), so the examples themselves stay untouched.
#include <gtest/gtest.h>

#include <sealfe/io/csv.h>

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

/// doc/csv.md: one header line of `name [unit]` fields (text columns: the bare name), no comment
/// lines, the same number of fields in every row, numbers wherever the header gives a unit, so
/// that a plain pandas.read_csv(file) gives numeric columns with units in their names.
void expect_csv_convention(const fs::path &file)
{
  const std::set<std::string> text_columns = {"role", "status", "configuration", "objective"};
  std::ifstream in(file);
  std::string line;
  ASSERT_TRUE(std::getline(in, line)) << file;
  const std::vector<std::string> header = split(line);
  std::vector<bool> numeric;
  for (const std::string &h : header)
  {
    const auto open = h.find(" [");
    const bool text = text_columns.count(h) > 0;
    EXPECT_TRUE(text ||
                (open != std::string::npos && open > 0 && h.back() == ']' && h.size() > open + 3))
        << file.filename() << ": header field '" << h << "' is not 'name [unit]'";
    EXPECT_EQ(h.find_first_of("# \t", 0), text ? std::string::npos : open) << h;
    numeric.push_back(!text);
  }
  unsigned int rows = 0;
  while (std::getline(in, line))
  {
    ++rows;
    std::vector<std::string> cells = split(line);
    if (!line.empty() && line.back() == ',')
      cells.emplace_back();
    ASSERT_EQ(cells.size(), header.size()) << file.filename() << " row " << rows << ": " << line;
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (numeric[c] && !cells[c].empty()) // empty: a missing value (NaN for pandas)
      {
        char *end = nullptr;
        std::strtod(cells[c].c_str(), &end);
        EXPECT_EQ(end, cells[c].c_str() + cells[c].size())
            << file.filename() << " row " << rows << " " << header[c] << " = '" << cells[c] << "'";
      }
  }
  EXPECT_GT(rows, 0u) << file;
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

  for (const auto &e : fs::directory_iterator(out))
    if (e.path().extension() == ".csv")
      expect_csv_convention(e.path());

  const json summary = json::parse(read(out / "summary.json"));
  // every summary names the version and git revision that wrote it
  EXPECT_EQ(summary.value("version", ""), SEALFE_VERSION);
  EXPECT_FALSE(summary.value("git_revision", "").empty());
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
                                           "transient", "rayleigh_pads", "spiral_grooves",
                                           "dimples_jfo", "dimples_fitted"),
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
  EXPECT_EQ(examples.size(), 13u); // the instantiation above lists them
}

// The numbers of every CSV read back to the same double, in the shortest text that does.
TEST(CsvConvention, NumbersReadBackExactly)
{
  using sealfe::csv::number;
  for (const double v : {0.1, 1.0 / 3.0, -443.67238978513905, 1e-300, 6.02214076e23, 0.0, 5e-324,
                         1.7976931348623157e308})
    EXPECT_EQ(std::strtod(number(v).c_str(), nullptr), v) << number(v);
  EXPECT_EQ(number(0.1), "0.1");
  EXPECT_EQ(number(2.5e-8), "2.5e-08");
  EXPECT_EQ(sealfe::csv::header({{"force_z", "N"}, {"role", ""}, {"index", "-"}}),
            "force_z [N],role,index [-]");
  sealfe::csv::Writer w({{"a", "m"}, {"b", ""}});
  w.add_row({1.5, "x, y"});
  EXPECT_EQ(w.text(), "a [m],b\n1.5,x; y\n");
  EXPECT_THROW(w.add_row({1.0}), std::logic_error);
}
