#include <sealfe/io/output.h>

#include <sealfe/io/interrupt.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sealfe
{
namespace output
{
void make_directory(const std::string &directory)
{
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec || !std::filesystem::is_directory(directory))
    throw std::runtime_error("Output directory '" + directory +
                             "' cannot be created: " + ec.message());
}

void write_file_atomically(const std::string &directory, const std::string &name,
                           const std::string &text)
{
  const std::string final_name = directory + "/" + name;
  const std::string temporary = final_name + ".tmp";
  {
    std::ofstream out(temporary);
    out << text;
    if (!out)
      throw std::runtime_error("cannot write '" + temporary + "'");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, final_name, ec);
  if (ec)
    throw std::runtime_error("cannot write '" + final_name + "': " + ec.message());
}

void write_summary(const std::string &directory, const nlohmann::json &summary)
{
  write_file_atomically(directory, "summary.json", summary.dump(2) + "\n");
}

void write_used_parameters(const std::string &directory, const dealii::ParameterHandler &prm)
{
  std::ostringstream s;
  prm.print_parameters(s, dealii::ParameterHandler::ShortPRM);
  write_file_atomically(directory, "used_parameters.prm", s.str());
}
namespace
{
namespace fs = std::filesystem;

/// The staging and output directories of the run in progress (for published_name).
std::pair<std::string, std::string> &current_staging()
{
  static std::pair<std::string, std::string> names;
  return names;
}
} // namespace

StagedOutput::StagedOutput(const std::string &directory_, const std::string &tag)
    : directory(directory_)
{
  if (directory.empty())
    throw std::runtime_error("Output directory is empty: name a directory");
  std::error_code ec;
  const bool existed = fs::exists(directory, ec);
  if (existed && !fs::is_directory(directory, ec))
    throw std::runtime_error("Output directory '" + directory +
                             "' cannot be created: a file of that name is in the way");
  make_directory(directory);
  created_directory = !existed;
  staging = (fs::path(directory) / (".sealfe-partial-" + tag)).string();
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec)
  {
    if (created_directory)
      fs::remove(directory, ec);
    throw std::runtime_error("Output directory '" + directory + "' is not writable: " +
                             (ec ? ec.message() : "cannot create " + staging));
  }
  current_staging() = {staging, directory};
}

StagedOutput::~StagedOutput()
{
  std::error_code ec;
  fs::remove_all(staging, ec);
  if (!published && created_directory)
    fs::remove(directory, ec); // only if empty
  current_staging() = {};
}

void StagedOutput::publish()
{
  // A signal now would leave a directory without summary.json: it waits for the last rename.
  const interrupt::HoldSignals hold;
  std::vector<fs::path> files;
  for (const auto &entry : fs::directory_iterator(staging))
    files.push_back(entry.path());
  // summary.json last, used_parameters.prm just before it: a directory with a summary.json of
  // this run holds all of this run's files.
  auto rank = [](const fs::path &f)
  {
    const std::string name = f.filename().string();
    return name == "summary.json" ? 2 : name == "used_parameters.prm" ? 1 : 0;
  };
  std::stable_sort(files.begin(), files.end(),
                   [&](const fs::path &a, const fs::path &b) { return rank(a) < rank(b); });
  std::error_code ec;
  fs::remove(fs::path(directory) / "summary.json", ec);
  for (const fs::path &f : files)
  {
    const fs::path target = fs::path(directory) / f.filename();
    if (fs::is_directory(target, ec) && !fs::is_directory(f, ec))
      throw std::runtime_error("cannot write '" + target.string() + "': a directory is in the way");
    fs::rename(f, target, ec);
    if (ec)
      throw std::runtime_error("cannot write '" + target.string() + "': " + ec.message());
  }
  published = true;
}

std::string published_name(const std::string &text)
{
  const auto &[staging, directory] = current_staging();
  if (staging.empty())
    return text;
  std::string out = text;
  for (std::size_t at = out.find(staging); at != std::string::npos;
       at = out.find(staging, at + directory.size()))
    out.replace(at, staging.size(), directory);
  return out;
}

void check_finite(const nlohmann::json &summary)
{
  std::function<void(const nlohmann::json &, const std::string &)> walk =
      [&](const nlohmann::json &node, const std::string &where)
  {
    if (node.is_number_float() && !std::isfinite(node.get<double>()))
    {
      std::ostringstream s;
      s << "the result " << where << " = " << node.get<double>()
        << " is not a finite number: an input is beyond what the model can represent in double "
           "precision (check the magnitudes of the inputs); nothing was written";
      throw std::runtime_error(s.str());
    }
    if (node.is_object())
      for (const auto &[key, value] : node.items())
        walk(value, where.empty() ? key : where + "." + key);
    else if (node.is_array())
      for (std::size_t i = 0; i < node.size(); ++i)
        walk(node[i], where + "[" + std::to_string(i) + "]");
  };
  walk(summary, "");
}

void check_finite_csv(const std::string &file)
{
  std::ifstream in(file);
  std::string line, header;
  for (unsigned int number = 1; std::getline(in, line); ++number)
  {
    if (line.empty() || line[0] == '#')
      continue;
    if (header.empty())
    {
      header = line;
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string f; std::getline(row, f, ',');)
    {
      std::string lower;
      for (const char c : f)
        if (!std::isspace(static_cast<unsigned char>(c)))
          lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      fields.push_back(lower);
    }
    if (std::any_of(fields.begin(), fields.end(),
                    [](const std::string &f) { return f.rfind("failed", 0) == 0; }))
      continue;
    for (std::size_t i = 0; i < fields.size(); ++i)
    {
      std::string column;
      std::istringstream h(header);
      for (std::size_t j = 0; j <= i && std::getline(h, column, ',');)
        ++j;
      if (column.rfind("err_", 0) == 0)
        continue; // an error estimate that is not available
      std::string f = fields[i];
      if (!f.empty() && (f[0] == '-' || f[0] == '+'))
        f.erase(0, 1);
      if (f.rfind("nan", 0) == 0 || f.rfind("inf", 0) == 0)
        throw std::runtime_error(
            "the result " + column + " in line " + std::to_string(number) + " of " +
            fs::path(file).filename().string() + " is " + fields[i] +
            ": an input is beyond what the model can represent in double precision (check the "
            "magnitudes of the inputs); nothing was written");
    }
  }
}
} // namespace output
} // namespace sealfe
