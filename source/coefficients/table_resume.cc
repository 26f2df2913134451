#include <sealfe/coefficients/table_resume.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace table
{
namespace
{
/// deal.II mangles entry names in its JSON output (non-alphanumerics as _XX hex).
std::string demangle(const std::string &s)
{
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == '_' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2])))
    {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
      out += s[i];
  return out;
}

/// `text` split at ',' and ':' with the blanks removed.
std::vector<std::string> tokens(const std::string &text)
{
  std::vector<std::string> out(1);
  for (const char c : text)
    if (c == ',' || c == ':')
      out.emplace_back();
    else if (!std::isspace(static_cast<unsigned char>(c)))
      out.back() += c;
  return out;
}

bool is_number(const std::string &s, double &value)
{
  if (s.empty())
    return false;
  char *end = nullptr;
  value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

std::string quoted(const nlohmann::json &value)
{
  return value.is_string() ? "'" + value.get<std::string>() + "'" : "(not recorded)";
}
} // namespace

nlohmann::json recorded_parameters(const dealii::ParameterHandler &prm)
{
  std::ostringstream text;
  prm.print_parameters(text, dealii::ParameterHandler::JSON);
  nlohmann::json recorded = nlohmann::json::object();
  std::function<void(const nlohmann::json &, const std::string &)> walk =
      [&](const nlohmann::json &node, const std::string &path)
  {
    for (const auto &[key, value] : node.items())
    {
      if (!value.is_object() || value.contains("alias"))
        continue; // an old name of another entry
      const std::string name = path + demangle(key);
      if (value.contains("value"))
      {
        if (name != "Output directory" && name != "Table/Resume" && name != "Table/Plot")
          recorded[name] = value["value"].get<std::string>();
      }
      else
        walk(value, name + "/");
    }
  };
  walk(nlohmann::json::parse(text.str()), "");
  return recorded;
}

bool same_value(const std::string &a, const std::string &b)
{
  const auto ta = tokens(a), tb = tokens(b);
  if (ta.size() != tb.size())
    return false;
  for (std::size_t i = 0; i < ta.size(); ++i)
  {
    double x, y;
    if (is_number(ta[i], x) && is_number(tb[i], y) ? x != y : ta[i] != tb[i])
      return false;
  }
  return true;
}

PreviousTable read_previous(const std::string &directory, const std::string &file,
                            const nlohmann::json &parameters, const std::string &header,
                            const std::vector<std::string> &row_prefix)
{
  namespace fs = std::filesystem;
  PreviousTable previous;
  const fs::path summary_file = fs::path(directory) / "summary.json";
  if (!fs::exists(summary_file))
    return previous;
  const std::string where = "Table: Resume = true, but the previous run in '" + directory + "'";
  nlohmann::json summary;
  try
  {
    std::ifstream in(summary_file);
    summary = nlohmann::json::parse(in);
  }
  catch (std::exception &)
  {
    throw std::runtime_error(where + " has an unreadable summary.json: set Resume = false");
  }
  if (summary.value("sub_command", std::string()) != "table")
    throw std::runtime_error(where + " is not a table (sub-command '" +
                             summary.value("sub_command", std::string("?")) +
                             "'): set Resume = false, or another Output directory");
  const nlohmann::json old = summary.value("parameters", nlohmann::json::object());
  if (old.empty())
    throw std::runtime_error(where + " records no parameters (written by an older sealfe): set "
                                     "Resume = false");
  // every parameter, in both directions: an entry present in one run only is a difference
  for (const auto &[name, value] : parameters.items())
    if (!old.contains(name) || !old[name].is_string() ||
        !same_value(old[name].get<std::string>(), value.get<std::string>()))
      throw std::runtime_error(
          where + " had '" + name +
          "' = " + (old.contains(name) ? quoted(old[name]) : "(not recorded)") + ", now " +
          quoted(value) + ": resume only with the same parameters (or set Resume = false)");
  for (const auto &[name, value] : old.items())
    if (!parameters.contains(name))
      throw std::runtime_error(where + " had '" + name + "' = " + quoted(value) +
                               ", which this sealfe does not know: set Resume = false");

  const fs::path table_file = fs::path(directory) / file;
  std::ifstream in(table_file);
  if (!in)
    throw std::runtime_error(where + " has no " + file + ": set Resume = false");
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '#'))
    ;
  if (line != header)
    throw std::runtime_error(where + " wrote other columns in " + file +
                             " (another sealfe version): set Resume = false");
  while (std::getline(in, line))
  {
    if (line.empty() || line[0] == '#')
      continue;
    const std::size_t comma = line.find(',');
    unsigned long i = row_prefix.size();
    try
    {
      i = std::stoul(line.substr(0, comma));
    }
    catch (std::exception &)
    {
    }
    if (i >= row_prefix.size() || line.compare(0, row_prefix[i].size(), row_prefix[i]) != 0 ||
        previous.rows.count(i))
      throw std::runtime_error(where + " has a row in " + file +
                               " that is not a point of this table ('" + line.substr(0, 60) +
                               "...'): set Resume = false");
    previous.rows[i] = line;
  }
  previous.found = true;
  previous.complete = summary.value("complete", true) && previous.rows.size() == row_prefix.size();
  return previous;
}
} // namespace table
} // namespace sealfe
