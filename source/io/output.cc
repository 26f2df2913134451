#include <sealfe/io/output.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
} // namespace output
} // namespace sealfe
